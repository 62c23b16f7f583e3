//! Ground truth of ambient occlusion and colour bleeding: per voxel
//! and hemisphere, the occlusion and environment colour over the same sphere
//! radius r that the clustered histograms summarize, but keeping what they
//! discard: the medium attenuates along each direction (a wall hides what is
//! behind it), and nothing is clustered. Rays along a fixed set of direction
//! pairs (w, -w) from the voxel centre to r; per ray occlusion 1 - T(r) and
//! colour sum T alpha rgb; each direction goes to the hemisphere its side of
//! the intensity-gradient plane names, as in the histograms. The mean per
//! hemisphere is a lookup per voxel for [`crate::techniques::ao::render::AoRenderer::per_voxel`].
//!
//! [`reference_cpu`] here (f64), the GPU version in [`gpu`].

pub mod gpu;
pub mod unclustered;

use glam::{DVec3, UVec3};

use crate::scene::{TransferLut, Volume};
use crate::techniques::ao::gradient::central_gradient;

/// How finely the ground truth samples the sphere.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AoReferenceParams {
    /// r in d_min, as `ao.radius`.
    pub radius: u32,
    /// Direction pairs (w and -w): 2 x this many rays per voxel.
    pub pairs: u32,
    /// Largest sample spacing along a ray, in d_min.
    pub step: f64,
}

impl AoReferenceParams {
    /// Samples per ray over [0.5, r] and their spacing (the voxel's own half
    /// voxel is left out, as the histograms leave out the centre).
    pub fn samples(&self) -> (u32, f64) {
        let length = (self.radius as f64 - 0.5).max(0.0);
        let steps = (length / self.step).ceil().max(1.0);
        (steps as u32, length / steps)
    }
}

/// `pairs` unit directions spread over the sphere (a Fibonacci lattice); each
/// is used with its opposite.
pub fn direction_pairs(pairs: u32) -> Vec<[f32; 3]> {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    (0..pairs)
        .map(|i| {
            let z = 1.0 - (2.0 * i as f64 + 1.0) / (2.0 * pairs as f64) * 2.0;
            let r = (1.0 - z * z).max(0.0).sqrt();
            let phi = golden * i as f64;
            [(r * phi.cos()) as f32, (r * phi.sin()) as f32, z as f32]
        })
        .collect()
}

/// Voxels per d_min along each axis (d_min / spacing).
pub fn step_scale(volume: &Volume) -> DVec3 {
    let spacing = volume.spacing.as_dvec3();
    DVec3::splat(spacing.min_element()) / spacing
}

/// The ground truth on the CPU, in f64: per voxel `[forward, backward]`, each
/// `(E rgb, O)`, in the layout of the per-voxel lookup (entry 2 v + h).
pub fn reference_cpu(volume: &Volume, lut: &TransferLut, params: &AoReferenceParams) -> Vec<[f32; 4]> {
    let directions = direction_pairs(params.pairs);
    let (steps, h) = params.samples();
    let scale = step_scale(volume);
    let dims = volume.dims;
    let inside = |q: DVec3| (0..3).all(|a| q[a] >= 0.0 && q[a] <= 1.0);
    let ray = |x: DVec3, w: DVec3| -> [f64; 4] {
        let (mut c, mut t_rest) = (DVec3::ZERO, 1.0);
        for i in 0..steps {
            let t = 0.5 + (i as f64 + 0.5) * h;
            let uvw = (x + w * scale * t + 0.5) / dims.as_dvec3();
            if !inside(uvw) {
                break;
            }
            let [r, g, b, sigma] = lut.sample(volume.sample_f64(uvw.to_array()));
            let alpha = 1.0 - (-sigma * h).exp();
            c += t_rest * alpha * DVec3::new(r, g, b);
            t_rest *= 1.0 - alpha;
        }
        [c.x, c.y, c.z, 1.0 - t_rest]
    };
    let mut out = vec![[0f32; 4]; 2 * volume.voxel_count()];
    for z in 0..dims.z {
        for y in 0..dims.y {
            for x in 0..dims.x {
                let v = UVec3::new(x, y, z);
                let g = central_gradient(volume, v).as_dvec3();
                let centre = v.as_dvec3();
                let (mut forward, mut backward) = ([0f64; 4], [0f64; 4]);
                for w in &directions {
                    let w = DVec3::new(w[0] as f64, w[1] as f64, w[2] as f64);
                    let (plus, minus) = (ray(centre, w), ray(centre, -w));
                    let side = w.dot(g);
                    let (a, b) = if side < 0.0 {
                        (1.0, 0.0)
                    } else if side > 0.0 {
                        (0.0, 1.0)
                    } else {
                        (0.5, 0.5)
                    };
                    for k in 0..4 {
                        forward[k] += a * plus[k] + b * minus[k];
                        backward[k] += b * plus[k] + a * minus[k];
                    }
                }
                let index = ((z * dims.y + y) * dims.x + x) as usize;
                let n = params.pairs as f64;
                out[2 * index] = forward.map(|s| (s / n) as f32);
                out[2 * index + 1] = backward.map(|s| (s / n) as f32);
            }
        }
    }
    out
}
