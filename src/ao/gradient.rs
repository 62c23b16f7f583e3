//! The intensity gradient the preprocessing uses: central differences of the
//! normalized intensity, before any transfer function (the preprocessing is
//! independent of it; the paper's grad tau(f(x)) only exists at render time).

use glam::{UVec3, Vec3};

use crate::scene::Volume;

/// Central-difference gradient of the normalized intensity at voxel `p`, in
/// intensity per d_min along each world axis. Neighbours are clamped to the
/// volume, so at a border the difference is one-sided over half the distance,
/// as a CLAMP_TO_EDGE texel fetch on the GPU gives.
pub fn central_gradient(volume: &Volume, p: UVec3) -> Vec3 {
    let d_min = volume.spacing.min_element();
    let mut g = [0.0f32; 3];
    for (axis, g) in g.iter_mut().enumerate() {
        let mut lo = p;
        let mut hi = p;
        lo[axis] = p[axis].saturating_sub(1);
        hi[axis] = (p[axis] + 1).min(volume.dims[axis] - 1);
        let difference = volume.voxel(hi.x, hi.y, hi.z) - volume.voxel(lo.x, lo.y, lo.z);
        *g = difference * 0.5 * d_min / volume.spacing[axis];
    }
    Vec3::from(g)
}
