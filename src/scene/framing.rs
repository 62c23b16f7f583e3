//! What the automatic camera frames: the box around the voxels the transfer
//! function makes visible (not the whole volume box, in which a small object
//! would fill half the frame), fitted so that its corners reach [`FRAME_FILL`]
//! of the view.

use glam::{UVec3, Vec3};

use super::camera::{Camera, Projection};
use super::transfer::TransferFunction;
use super::volume::Volume;
use super::VolumeBox;

/// The framed box's corners reach this fraction of the half view, so the
/// object inside (rounder than its box) fills about 80 % of the frame.
pub const FRAME_FILL: f32 = 0.9;

/// Bins of the value table that says which values the transfer function shows.
const VISIBLE_BINS: usize = 4096;

/// An axis-aligned world box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WorldBox {
    pub min: Vec3,
    pub max: Vec3,
}

impl WorldBox {
    pub fn of_volume(volume_box: &VolumeBox) -> WorldBox {
        WorldBox { min: volume_box.min(), max: volume_box.max() }
    }

    pub fn corners(&self) -> [Vec3; 8] {
        std::array::from_fn(|i| {
            Vec3::new(
                if i & 1 == 0 { self.min.x } else { self.max.x },
                if i & 2 == 0 { self.min.y } else { self.max.y },
                if i & 4 == 0 { self.min.z } else { self.max.z },
            )
        })
    }
}

/// Per bin of normalized values, whether the transfer function gives any value
/// in it opacity: it is piecewise linear, so the bin's ends and the control
/// points inside are enough.
fn visible_values(tf: &TransferFunction) -> Vec<bool> {
    (0..VISIBLE_BINS)
        .map(|k| {
            let (lo, hi) = (k as f32 / VISIBLE_BINS as f32, (k + 1) as f32 / VISIBLE_BINS as f32);
            let inner = tf.points.iter().filter(|p| p.value > lo && p.value < hi).map(|p| p.rgba[3]);
            inner.chain([tf.eval(lo)[3], tf.eval(hi)[3]]).any(|a| a > 0.0)
        })
        .collect()
}

/// The world box of the voxels (whole cells) that `tf` gives opacity, or the
/// volume's box when none has any.
pub fn visible_box(volume: &Volume, tf: &TransferFunction, volume_box: &VolumeBox) -> WorldBox {
    let visible = visible_values(tf);
    let d = volume.dims;
    let (mut lo, mut hi) = (UVec3::MAX, UVec3::ZERO);
    let mut index = 0;
    for z in 0..d.z {
        for y in 0..d.y {
            for x in 0..d.x {
                let v = volume.data.normalized(index).clamp(0.0, 1.0);
                if visible[((v * VISIBLE_BINS as f32) as usize).min(VISIBLE_BINS - 1)] {
                    let i = UVec3::new(x, y, z);
                    lo = lo.min(i);
                    hi = hi.max(i + UVec3::ONE);
                }
                index += 1;
            }
        }
    }
    if lo.cmpgt(hi).any() {
        return WorldBox::of_volume(volume_box);
    }
    let world = |i: UVec3| i.as_vec3() / d.as_vec3() * 2.0 * volume_box.half_extent - volume_box.half_extent;
    WorldBox { min: world(lo), max: world(hi) }
}

/// An orbit camera's distance (perspective) that puts every corner of `framed`
/// within [`FRAME_FILL`] of the view, or the orthographic view height that does.
pub struct Fit {
    pub distance: f32,
    pub ortho_height: f32,
}

pub fn fit_orbit(
    framed: &WorldBox,
    target: Vec3,
    azimuth_deg: f32,
    elevation_deg: f32,
    fov_y_deg: f32,
    aspect: f32,
) -> Fit {
    let probe = Camera::orbit(target, 1.0, azimuth_deg, elevation_deg, Projection::Orthographic { height: 2.0 });
    let basis = probe.basis(1, 1);
    let (right, up) = (basis.right.normalize(), basis.up.normalize());
    let toward_eye = (probe.eye - target).normalize();
    let tan_y = (fov_y_deg.to_radians() * 0.5).tan() * FRAME_FILL;
    let tan_x = tan_y * aspect;
    let (mut distance, mut half_height) = (0.0f32, 0.0f32);
    for c in framed.corners() {
        let rel = c - target;
        let (x, y, toward) = (rel.dot(right).abs(), rel.dot(up).abs(), rel.dot(toward_eye));
        // The corner's depth from the eye is distance - toward.
        distance = distance.max(x / tan_x + toward).max(y / tan_y + toward);
        half_height = half_height.max(y / FRAME_FILL).max(x / (aspect * FRAME_FILL));
    }
    Fit { distance, ortho_height: 2.0 * half_height.max(f32::MIN_POSITIVE) }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::presets;
    use crate::scene::synthetic::slab_under_sphere;

    #[test]
    fn the_visible_box_holds_the_voxels_with_opacity() {
        let v = slab_under_sphere(50);
        let vb = VolumeBox::new(v.dims, v.spacing);
        let b = visible_box(&v, &presets::preset("slab-sphere").unwrap(), &vb);
        // Slab x, z in [5, 45) voxels, sphere top at 40 voxels; the ramps add
        // one visible layer of voxels outside (the first voxel outside a
        // surface holds a sixth of its part's value, within the slab's band,
        // which starts at 0.02), and no more.
        let w = |voxels: f32| voxels / 50.0 - 0.5;
        assert!(b.min.abs_diff_eq(Vec3::new(w(4.0), w(4.0), w(4.0)), 1e-6), "{b:?}");
        assert!(b.max.abs_diff_eq(Vec3::new(w(46.0), w(41.0), w(46.0)), 1e-6), "{b:?}");
        // Nothing visible: the whole volume.
        let none =
            TransferFunction { points: vec![crate::scene::ControlPoint { value: 0.0, rgba: [1.0, 1.0, 1.0, 0.0] }] };
        assert_eq!(visible_box(&v, &none, &vb), WorldBox::of_volume(&vb));
    }

    #[test]
    fn the_fit_puts_the_farthest_corner_at_the_fill_fraction() {
        let framed = WorldBox { min: Vec3::new(-0.4, -0.4, -0.3), max: Vec3::new(0.4, 0.2, 0.3) };
        for (az, el, aspect) in [(30.0, 20.0, 1.0), (0.0, 45.0, 2.0), (200.0, -60.0, 0.5)] {
            let fit = fit_orbit(&framed, Vec3::ZERO, az, el, 30.0, aspect);
            let (w, h) = ((100.0 * aspect) as u32, 100);
            for projection in
                [Projection::Perspective { fov_y_deg: 30.0 }, Projection::Orthographic { height: fit.ortho_height }]
            {
                let cam = Camera::orbit(Vec3::ZERO, fit.distance, az, el, projection);
                let basis = cam.basis(w, h);
                let mut reach = 0.0f32;
                for c in framed.corners() {
                    // ndc of the corner: its offsets over the basis, divided by depth for perspective.
                    let rel = c - cam.eye;
                    let depth = rel.dot(basis.forward);
                    assert!(depth > 0.0);
                    let s = if basis.orthographic { 1.0 } else { depth };
                    let nx = rel.dot(basis.right) / basis.right.length_squared() / s;
                    let ny = rel.dot(basis.up) / basis.up.length_squared() / s;
                    reach = reach.max(nx.abs()).max(ny.abs());
                }
                assert!((reach - FRAME_FILL).abs() < 1e-4, "az {az} el {el} aspect {aspect} {projection:?}: {reach}");
            }
        }
    }
}
