//! Named transfer-function presets, and an automatic transfer function built from
//! a volume's histogram (used for `--volume FILE` and `transfer.auto = true`).
//!
//! Alphas are opacities per voxel of length (see [`super::transfer`]), so a preset
//! looks alike on volumes of different resolution only as far as the structures
//! have the same thickness in voxels.

use super::synthetic::{
    CORNELL_BACK_WALL, CORNELL_CEILING, CORNELL_FLOOR, CORNELL_LEFT_WALL, CORNELL_RIGHT_WALL, CORNELL_SHORT_BOX,
    CORNELL_TALL_BOX, SLAB_VALUE, SPHERE_VALUE,
};
use super::transfer::{ControlPoint, TransferFunction};
use super::volume::Volume;

/// Names accepted by [`preset`] (and by `transfer.preset` in scene files).
pub const PRESET_NAMES: [&str; 7] =
    ["grayscale-ramp", "ct-bone", "ct-engine", "phantom", "spheres", "cornell", "slab-sphere"];

fn tf(points: &[(f32, [f32; 4])]) -> TransferFunction {
    TransferFunction { points: points.iter().map(|&(value, rgba)| ControlPoint { value, rgba }).collect() }
}

fn rgba(rgb: [f32; 3], a: f32) -> [f32; 4] {
    [rgb[0], rgb[1], rgb[2], a]
}

/// The preset called `name`, or `None` if there is none (see [`PRESET_NAMES`]).
pub fn preset(name: &str) -> Option<TransferFunction> {
    Some(match name {
        // Grey level and opacity both rise linearly with the value.
        "grayscale-ramp" => tf(&[(0.0, [0.0, 0.0, 0.0, 0.0]), (1.0, [1.0, 1.0, 1.0, 0.1])]),
        // Generic CT rescaled to [0, 1]: air and fat clear, soft tissue faint
        // red, bone opaque ivory.
        "ct-bone" => tf(&[
            (0.0, [0.8, 0.45, 0.35, 0.0]),
            (0.35, [0.8, 0.45, 0.35, 0.0]),
            (0.5, [0.9, 0.6, 0.5, 0.02]),
            (0.7, [1.0, 0.9, 0.8, 0.4]),
            (1.0, [1.0, 1.0, 0.95, 0.8]),
        ]),
        // The CT engine (engine.vti): air and its noise (< ~70/255) clear, the
        // aluminium block (~130-160) a faint blue-grey, the dense parts (> ~190)
        // opaque orange to white.
        "ct-engine" => tf(&[
            (0.0, [0.3, 0.4, 0.6, 0.0]),
            (0.3, [0.3, 0.4, 0.6, 0.0]),
            (0.5, [0.55, 0.65, 0.8, 0.03]),
            (0.63, [0.6, 0.7, 0.85, 0.06]),
            (0.72, [0.9, 0.6, 0.3, 0.1]),
            (0.8, [1.0, 0.7, 0.35, 0.5]),
            (1.0, [1.0, 0.9, 0.75, 0.8]),
        ]),
        // Shepp-Logan (synthetic "shepp-logan"): outside and ventricles (0) clear,
        // brain (0.2) a faint haze, features (0.3) orange, skull (1) translucent
        // white (it is only 1-2 voxels thick).
        "phantom" => tf(&[
            (0.0, [0.0, 0.0, 0.0, 0.0]),
            (0.1, [0.85, 0.55, 0.5, 0.0]),
            // Brain matter: a faint haze, so the small ellipsoids inside show.
            (0.2, [0.85, 0.55, 0.5, 0.003]),
            (0.25, [0.85, 0.55, 0.5, 0.003]),
            (0.3, [1.0, 0.55, 0.2, 0.25]),
            (0.4, [0.3, 0.6, 1.0, 0.25]),
            // Skull: translucent.
            (0.6, [0.95, 0.95, 0.9, 0.01]),
            (1.0, [0.95, 0.95, 0.9, 0.03]),
        ]),
        // Three spheres (255) nearly opaque light grey; the anti-aliased surface
        // ramps up in opacity.
        "spheres" => tf(&[(0.0, [0.9, 0.9, 0.9, 0.0]), (0.2, [0.9, 0.9, 0.9, 0.0]), (1.0, [0.9, 0.9, 0.9, 0.9])]),
        "cornell" => cornell(),
        "slab-sphere" => slab_sphere(),
        _ => return None,
    })
}

/// A narrow opaque band of colour `rgb` around each raw U8 value, clear between
/// bands: for labelled volumes whose parts are distinct values.
fn bands(materials: &[(u8, [f32; 3], f32)]) -> TransferFunction {
    const HALF_PLATEAU: f32 = 0.02;
    const HALF_WIDTH: f32 = 0.04;
    let mut sorted = materials.to_vec();
    sorted.sort_by_key(|m| m.0);
    let mut points = vec![(0.0, rgba(sorted[0].1, 0.0))];
    for &(raw, rgb, a) in &sorted {
        let v = raw as f32 / 255.0;
        points.push(((v - HALF_WIDTH).max(0.0), rgba(rgb, 0.0)));
        points.push(((v - HALF_PLATEAU).max(0.0), rgba(rgb, a)));
        points.push(((v + HALF_PLATEAU).min(1.0), rgba(rgb, a)));
        points.push(((v + HALF_WIDTH).min(1.0), rgba(rgb, if v + HALF_WIDTH >= 1.0 { a } else { 0.0 })));
    }
    tf(&points)
}

/// Cornell box (synthetic "cornell-box"): white floor, ceiling and back wall, red
/// left wall, green right wall, a blue short box (which a TF edit can remove, as
/// in the colour-bleeding paper's Fig. 5) and a white tall box, all opaque.
fn cornell() -> TransferFunction {
    const WHITE: [f32; 3] = [0.75, 0.75, 0.75];
    const OPAQUE: f32 = 0.9;
    bands(&[
        (CORNELL_FLOOR, WHITE, OPAQUE),
        (CORNELL_CEILING, WHITE, OPAQUE),
        (CORNELL_BACK_WALL, WHITE, OPAQUE),
        (CORNELL_LEFT_WALL, [0.63, 0.065, 0.05], OPAQUE),
        (CORNELL_RIGHT_WALL, [0.14, 0.45, 0.09], OPAQUE),
        (CORNELL_SHORT_BOX, [0.2, 0.3, 0.75], OPAQUE),
        (CORNELL_TALL_BOX, WHITE, OPAQUE),
    ])
}

/// Slab under sphere (synthetic "slab-under-sphere"): grey slab and orange
/// sphere, both nearly opaque so the shadow is crisp. The surfaces are smooth
/// ramps 1.5 voxels wide (synthetic::TRANSITION_VOXELS), so each part's opacity
/// rises over its own ramp rather than in one step, and a view ray's samples see
/// a smooth surface. The sphere's ramp passes through every value below its
/// own on its way to air, the slab's among them, so it wears a grey film of the
/// slab's band. The band's opacity therefore rises over the whole of the slab's
/// ramp (values 0.02 to the slab's), which makes that film about 0.7 voxel
/// deep: two view samples half a voxel apart see it. A band as narrow as the
/// sphere's own left a film a third of a voxel deep that one sample in a step
/// hits or misses pixel by pixel (grain in every lit technique: IPSVI 35.6 dB
/// against 43.9 dB at 128x128). The band falls back to clear just below the
/// sphere's opaque values (0.62 to 1, 0.57 voxel deep).
fn slab_sphere() -> TransferFunction {
    const GREY: [f32; 3] = [0.8, 0.8, 0.8];
    const ORANGE: [f32; 3] = [1.0, 0.6, 0.3];
    let slab = SLAB_VALUE as f32 / 255.0;
    tf(&[
        (0.0, rgba(GREY, 0.0)),
        (0.02, rgba(GREY, 0.0)),
        (slab - 0.02, rgba(GREY, 0.5)),
        (slab + 0.02, rgba(GREY, 0.5)),
        (0.60, rgba(ORANGE, 0.0)),
        (0.62, rgba(ORANGE, 0.0)),
        (SPHERE_VALUE as f32 / 255.0, rgba(ORANGE, 0.95)),
    ])
}

/// Bins of the histogram the automatic transfer function looks at.
const AUTO_BINS: usize = 256;
/// Half width of the box filter that smooths the histogram before looking for
/// its valley, so that noise in sparse bins does not end the background early.
const AUTO_SMOOTHING: usize = 4;
/// Fraction of the foreground voxels below the top of the opacity ramp.
const AUTO_TOP_PERCENTILE: f64 = 0.99;
/// Opacity per voxel at the top of the ramp.
pub const AUTO_MAX_ALPHA: f32 = 0.6;

/// Automatic transfer function from the histogram of the normalized values.
///
/// The most frequent bin in the lower half is taken as the background (air,
/// empty space); the background extends up to the first valley of the smoothed
/// histogram above that peak (the end of the air's noise tail); the voxels
/// above it are the foreground. Opacity is 0 up to the foreground's median (or the
/// middle of its range, if lower) and rises from there, piecewise linearly with a
/// quarter at mid-ramp, to [`AUTO_MAX_ALPHA`] at the foreground's 99th percentile,
/// with a warm colour ramp from dark red through orange to pale yellow.
pub fn transfer_from_histogram(volume: &Volume) -> TransferFunction {
    let h = volume.histogram(AUTO_BINS);
    let (lo, hi) = auto_ramp(&h);
    const DARK: [f32; 3] = [0.55, 0.12, 0.05];
    const ORANGE: [f32; 3] = [0.95, 0.45, 0.15];
    const PALE: [f32; 3] = [1.0, 0.92, 0.8];
    let mut points = vec![(0.0, rgba(DARK, 0.0)), (lo, rgba(DARK, 0.0))];
    points.push(((lo + hi) * 0.5, rgba(ORANGE, AUTO_MAX_ALPHA * 0.25)));
    points.push((hi, rgba(PALE, AUTO_MAX_ALPHA)));
    if hi < 1.0 {
        points.push((1.0, rgba(PALE, AUTO_MAX_ALPHA)));
    }
    tf(&points)
}

/// Start (clear) and top (opaque) of the automatic opacity ramp, as normalized
/// values with `0 <= lo < hi <= 1`.
fn auto_ramp(h: &[u64]) -> (f32, f32) {
    let n = h.len();
    let bin_width = 1.0 / n as f32;
    let peak = (0..n / 2).fold(0, |best, i| if h[i] > h[best] { i } else { best });
    // Mean (not sum) over the window, so the clipped windows at the ends do not
    // look like a rise.
    let smoothed: Vec<f64> = (0..n)
        .map(|i| {
            let window = &h[i.saturating_sub(AUTO_SMOOTHING)..(i + AUTO_SMOOTHING + 1).min(n)];
            window.iter().sum::<u64>() as f64 / window.len() as f64
        })
        .collect();
    // First bin above the peak where the smoothed histogram stops falling.
    let valley = (peak + 1..n - 1).find(|&i| smoothed[i] <= smoothed[i + 1]).unwrap_or(n - 1);
    let count_from = |from: usize| -> u64 { h[from.min(n)..].iter().sum() };
    // A histogram that falls all the way (no second population): everything above
    // the background peak is foreground.
    let start = if count_from(valley + 1) > 0 { valley + 1 } else { peak + 1 };
    let foreground = count_from(start);
    if foreground == 0 {
        // Constant volume: nothing but background; keep a valid ramp above it.
        let lo = ((peak + 1) as f32 * bin_width).min(1.0 - bin_width);
        return (lo, 1.0);
    }
    let percentile_bin = |fraction: f64| {
        let target = (foreground as f64 * fraction).ceil() as u64;
        let mut seen = 0;
        (start..n)
            .find(|&i| {
                seen += h[i];
                seen >= target
            })
            .unwrap_or(n - 1)
    };
    let top = percentile_bin(AUTO_TOP_PERCENTILE);
    // The upper half of the foreground is what shows; but never start above the
    // middle of the foreground's range, so a volume that is mostly one bright value
    // (solid objects with anti-aliased edges) keeps its edges.
    let median = percentile_bin(0.5);
    let first = median.min((start + top) / 2);
    let hi = ((top + 1) as f32 * bin_width).min(1.0);
    let lo = (first as f32 * bin_width).min(hi - bin_width);
    (lo, hi)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::synthetic::SyntheticKind;
    use crate::scene::synthetic::{cornell_box, noise, shepp_logan, slab_under_sphere, three_spheres};

    #[test]
    fn every_preset_is_a_valid_transfer_function() {
        for name in PRESET_NAMES {
            let tf = preset(name).unwrap_or_else(|| panic!("preset {name} missing"));
            assert!(TransferFunction::new(tf.points.clone()).is_ok(), "preset {name} is invalid: {tf:?}");
            assert!(tf.points.iter().any(|p| p.rgba[3] > 0.0), "preset {name} is fully transparent");
        }
        assert!(preset("no-such-preset").is_none());
        for kind in SyntheticKind::ALL {
            assert!(preset(kind.default_preset()).is_some(), "{}", kind.name());
        }
    }

    #[test]
    fn cornell_preset_colours_left_red_and_right_green_and_air_clear() {
        let tf = preset("cornell").unwrap();
        let left = tf.eval(CORNELL_LEFT_WALL as f32 / 255.0);
        let right = tf.eval(CORNELL_RIGHT_WALL as f32 / 255.0);
        assert!(left[0] > 2.0 * left[1] && left[3] > 0.5, "{left:?}");
        assert!(right[1] > 2.0 * right[0] && right[3] > 0.5, "{right:?}");
        assert_eq!(tf.eval(0.0)[3], 0.0);
        // Clear between the bands of neighbouring parts.
        let between = (CORNELL_LEFT_WALL as f32 + CORNELL_RIGHT_WALL as f32) / 2.0 / 255.0;
        assert_eq!(tf.eval(between)[3], 0.0);
    }

    #[test]
    fn slab_sphere_preset_makes_both_parts_opaque() {
        let tf = preset("slab-sphere").unwrap();
        // The slab is thick (n / 10 voxels): half opaque per voxel is plenty.
        assert!(tf.eval(SLAB_VALUE as f32 / 255.0)[3] >= 0.5);
        assert!(tf.eval(1.0)[3] >= 0.9);
        assert_eq!(tf.eval(0.0)[3], 0.0);
    }

    #[test]
    fn auto_transfer_is_clear_at_the_background_and_opaque_on_the_objects() {
        // (volume, an object value present in it)
        let cases = [
            (three_spheres(32), 1.0),
            (slab_under_sphere(32), 1.0),
            (cornell_box(32), CORNELL_TALL_BOX as f32 / 255.0),
            (shepp_logan(32), 1.0),
        ];
        for (volume, object) in cases {
            let tf = transfer_from_histogram(&volume);
            assert!(TransferFunction::new(tf.points.clone()).is_ok(), "{}: {tf:?}", volume.name);
            assert_eq!(tf.eval(0.0)[3], 0.0, "{}: background must be clear", volume.name);
            assert!(tf.eval(object)[3] > 0.05, "{}: object {object} invisible: {tf:?}", volume.name);
        }
    }

    #[test]
    fn auto_transfer_skips_a_noisy_air_tail() {
        // Air: a peak at 0 falling off over 40 bins; material: a block around 140.
        let mut h = vec![0u64; 256];
        for (i, c) in h.iter_mut().enumerate().take(40) {
            *c = 100_000 >> (i / 4);
        }
        for c in &mut h[130..150] {
            *c = 5_000;
        }
        let (lo, hi) = auto_ramp(&h);
        // Clear past the air's tail, opacity rising below the block.
        assert!((40.0 / 256.0..130.0 / 256.0).contains(&lo), "ramp starts at {lo}");
        // 99 % of a block uniform over bins 130..150 lie below bin 149's top edge.
        assert_eq!(hi, 150.0 / 256.0);
    }

    #[test]
    fn auto_transfer_handles_constant_and_noise_volumes() {
        let mut constant = three_spheres(8);
        constant.data = crate::scene::VoxelData::U8(vec![0; 512]);
        let tf = transfer_from_histogram(&constant);
        assert!(TransferFunction::new(tf.points.clone()).is_ok());
        assert_eq!(tf.eval(0.0)[3], 0.0);
        let tf = transfer_from_histogram(&noise(16, 1));
        assert!(TransferFunction::new(tf.points.clone()).is_ok());
    }
}
