//! Where in its step each view ray's samples lie: the midpoint, or with
//! `render.jitter` a deterministic per-pixel phase, so that the sample planes
//! of neighbouring rays do not line up and beat against surfaces as rings and
//! stripes (the error becomes fine noise). The shaders compute the same hash
//! (glsl/view_ray.glsl), so CPU and GPU sample the same points.

/// lowbias32 (Wellons): an integer hash whose bits are all well mixed.
pub fn ray_start_hash(x: u32, y: u32) -> u32 {
    let mut h = x.wrapping_mul(0x8da6_b343) ^ y.wrapping_mul(0xd816_3841);
    h ^= h >> 16;
    h = h.wrapping_mul(0x7feb_352d);
    h ^= h >> 15;
    h = h.wrapping_mul(0x846c_a68b);
    h ^= h >> 16;
    h
}

/// Phase in [0, 1) of pixel (x, y)'s samples within their steps: sample `i`
/// lies at `t_enter + (i + phase) * h`. 24 bits of the hash, exact in f32 and
/// f64 alike; 0.5 (midpoints) without jitter.
pub fn ray_start_phase(jitter: bool, x: u32, y: u32) -> f64 {
    if jitter {
        (ray_start_hash(x, y) >> 8) as f64 / (1u32 << 24) as f64
    } else {
        0.5
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn phases_fill_the_step_evenly_and_differ_between_neighbours() {
        let mut bins = [0u32; 8];
        let mut same_as_left = 0;
        for y in 0..64 {
            for x in 0..64 {
                let p = ray_start_phase(true, x, y);
                assert!((0.0..1.0).contains(&p));
                bins[(p * 8.0) as usize] += 1;
                same_as_left += u32::from(x > 0 && p == ray_start_phase(true, x - 1, y));
            }
        }
        // 512 expected per bin; white noise stays well within +-25 %.
        assert!(bins.iter().all(|&b| (384..=640).contains(&b)), "{bins:?}");
        assert_eq!(same_as_left, 0);
        assert_eq!(ray_start_phase(false, 3, 7), 0.5);
    }
}
