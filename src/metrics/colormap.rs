//! A small approximation of matplotlib's "inferno" colour map: perceptually
//! ordered (lightness rises monotonically) and readable in greyscale print.

/// sRGB key colours of inferno at t = 0, 0.1, ..., 1.
const INFERNO: [[u8; 3]; 11] = [
    [0, 0, 4],
    [22, 11, 57],
    [66, 10, 104],
    [106, 23, 110],
    [147, 38, 103],
    [188, 55, 84],
    [221, 81, 58],
    [243, 120, 25],
    [252, 165, 10],
    [246, 215, 70],
    [252, 255, 164],
];

/// Colour of `t` in [0, 1] (clamped; NaN maps to 0), linearly interpolated
/// between the key colours.
pub fn inferno(t: f32) -> [u8; 3] {
    let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
    let x = t * (INFERNO.len() - 1) as f32;
    let i = (x.floor() as usize).min(INFERNO.len() - 2);
    let f = x - i as f32;
    let (a, b) = (INFERNO[i], INFERNO[i + 1]);
    let mut out = [0u8; 3];
    for c in 0..3 {
        let v = a[c] as f32 + (b[c] as f32 - a[c] as f32) * f;
        out[c] = v.round().clamp(0.0, 255.0) as u8;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn luma(c: [u8; 3]) -> f32 {
        0.2126 * c[0] as f32 + 0.7152 * c[1] as f32 + 0.0722 * c[2] as f32
    }

    #[test]
    fn ends_and_key_colours() {
        assert_eq!(inferno(0.0), INFERNO[0]);
        assert_eq!(inferno(1.0), INFERNO[10]);
        assert_eq!(inferno(0.5), INFERNO[5]);
        assert_eq!(inferno(-3.0), INFERNO[0]);
        assert_eq!(inferno(7.0), INFERNO[10]);
        assert_eq!(inferno(f32::NAN), INFERNO[0]);
    }

    #[test]
    fn lightness_rises_monotonically() {
        let mut last = -1.0;
        for i in 0..=100 {
            let l = luma(inferno(i as f32 / 100.0));
            assert!(l > last, "luma falls at t = {}", i as f32 / 100.0);
            last = l;
        }
    }
}
