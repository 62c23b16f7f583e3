//! Where the volume sits in world space.
//!
//! The volume's bounding box is centred at the origin; its longest physical side
//! (dims * spacing) has length 1. All lengths in scenes (camera distance, light
//! positions, step sizes) are in these world units; step sizes in scene files are
//! given in voxels and converted with [`VolumeBox::voxel_length`].

use glam::{UVec3, Vec3};

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VolumeBox {
    /// Half the box size along each axis.
    pub half_extent: Vec3,
    /// World length of the smallest voxel spacing: the unit of step sizes and the
    /// reference length of transfer-function opacities.
    pub voxel_length: f32,
}

impl VolumeBox {
    pub fn new(dims: UVec3, spacing: Vec3) -> Self {
        let physical = dims.as_vec3() * spacing;
        let longest = physical.max_element().max(f32::MIN_POSITIVE);
        VolumeBox { half_extent: physical / longest * 0.5, voxel_length: spacing.min_element() / longest }
    }

    pub fn min(&self) -> Vec3 {
        -self.half_extent
    }

    pub fn max(&self) -> Vec3 {
        self.half_extent
    }

    /// Texture coordinate in [0, 1]^3 of a world position.
    pub fn to_uvw(&self, p: Vec3) -> Vec3 {
        (p + self.half_extent) / (2.0 * self.half_extent)
    }

    /// Ray/box intersection: `(t_near, t_far)` with `t_near >= 0`, or `None` when
    /// the ray misses. `dir` need not be normalized; components may be zero.
    pub fn intersect(&self, origin: Vec3, dir: Vec3) -> Option<(f32, f32)> {
        let (n, f) = intersect_f64(
            self.half_extent.as_dvec3().to_array(),
            origin.as_dvec3().to_array(),
            dir.as_dvec3().to_array(),
        )?;
        Some((n as f32, f as f32))
    }

    /// The eight corners.
    pub fn corners(&self) -> [Vec3; 8] {
        let h = self.half_extent;
        let mut c = [Vec3::ZERO; 8];
        for (i, corner) in c.iter_mut().enumerate() {
            *corner = Vec3::new(
                if i & 1 == 0 { -h.x } else { h.x },
                if i & 2 == 0 { -h.y } else { h.y },
                if i & 4 == 0 { -h.z } else { h.z },
            );
        }
        c
    }
}

/// Slab test in f64 against the box [-half, half]. Zero direction components are
/// handled without dividing by zero.
pub fn intersect_f64(half: [f64; 3], origin: [f64; 3], dir: [f64; 3]) -> Option<(f64, f64)> {
    let mut t0 = 0.0f64;
    let mut t1 = f64::INFINITY;
    for a in 0..3 {
        if dir[a].abs() < 1e-30 {
            if origin[a] < -half[a] || origin[a] > half[a] {
                return None;
            }
            continue;
        }
        let inv = 1.0 / dir[a];
        let mut ta = (-half[a] - origin[a]) * inv;
        let mut tb = (half[a] - origin[a]) * inv;
        if ta > tb {
            std::mem::swap(&mut ta, &mut tb);
        }
        t0 = t0.max(ta);
        t1 = t1.min(tb);
    }
    (t0 < t1).then_some((t0, t1))
}
