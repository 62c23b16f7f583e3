//! The intensity gradient the preprocessing uses: central differences of the
//! normalized intensity, before any transfer function (the preprocessing is
//! independent of it; the paper's grad tau(f(x)) only exists at render time).

use glam::{UVec3, Vec3};

use crate::scene::Volume;

/// Central-difference gradient of the normalized intensity at voxel `p`, in
/// intensity per d_min along each world axis. Neighbours are clamped to the
/// volume, so at a border the difference is one-sided over half the distance,
/// as a CLAMP_TO_EDGE texel fetch on the GPU gives.
///
/// Each difference is multiplied by [`gradient_scale`]: one correctly rounded
/// f32 product, which the GPU sweep reproduces bit for bit on any Vulkan
/// device (a division would not be: Vulkan allows 2.5 ulp for it).
pub fn central_gradient(volume: &Volume, p: UVec3) -> Vec3 {
    let scale = gradient_scale(volume.spacing);
    let mut g = [0.0f32; 3];
    for (axis, g) in g.iter_mut().enumerate() {
        let mut lo = p;
        let mut hi = p;
        lo[axis] = p[axis].saturating_sub(1);
        hi[axis] = (p[axis] + 1).min(volume.dims[axis] - 1);
        let difference = volume.voxel(hi.x, hi.y, hi.z) - volume.voxel(lo.x, lo.y, lo.z);
        *g = difference * scale[axis];
    }
    Vec3::from(g)
}

/// 0.5 d_min / spacing per axis, in f64 and rounded to f32 once: the factor
/// that turns a central difference into intensity per d_min (0.5 exactly on
/// isotropic axes). Computed on the host for the CPU and the GPU alike.
pub fn gradient_scale(spacing: Vec3) -> [f32; 3] {
    let d_min = spacing.min_element() as f64;
    spacing.to_array().map(|s| (0.5 * d_min / s as f64) as f32)
}
