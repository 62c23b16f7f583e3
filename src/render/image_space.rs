//! Where world points land on the image: continuous pixel coordinates of a
//! camera's view, and the pixels the volume's bounding box covers (the region
//! IPSVI sweeps and half-angle slicing shade).

use crate::scene::{RayBasis, VolumeBox};
use glam::{Vec2, Vec3};

/// Continuous pixel coordinates: pixel (x, y) covers [x, x+1) x [y, y+1), y down.
#[derive(Clone, Copy, Debug)]
pub struct ImageSpace {
    pub basis: RayBasis,
    pub width: u32,
    pub height: u32,
}

/// A rectangle of whole pixels, [x0, x1) x [y0, y1).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PixelRect {
    pub x0: u32,
    pub y0: u32,
    pub x1: u32,
    pub y1: u32,
}

impl PixelRect {
    pub fn is_empty(&self) -> bool {
        self.x0 >= self.x1 || self.y0 >= self.y1
    }
}

impl ImageSpace {
    pub fn ndc_to_pixel(&self, nx: f32, ny: f32) -> Vec2 {
        Vec2::new((nx + 1.0) * 0.5 * self.width as f32, (1.0 - ny) * 0.5 * self.height as f32)
    }

    /// Image-plane components of a world vector: (along right, along up) in ndc
    /// units per unit depth (perspective) or per world unit (orthographic).
    pub fn lateral(&self, v: Vec3) -> Vec2 {
        Vec2::new(
            v.dot(self.basis.right) / self.basis.right.length_squared(),
            v.dot(self.basis.up) / self.basis.up.length_squared(),
        )
    }

    /// Pixel coordinates of a world point; `None` behind a perspective camera.
    pub fn project(&self, p: Vec3) -> Option<Vec2> {
        let v = p - self.basis.origin;
        let l = self.lateral(v);
        if self.basis.orthographic {
            return Some(self.ndc_to_pixel(l.x, l.y));
        }
        let z = v.dot(self.basis.forward);
        (z > 1e-6).then(|| self.ndc_to_pixel(l.x / z, l.y / z))
    }

    /// Pixels covered by the projected bounding box; the whole image when a
    /// corner lies behind a perspective camera.
    pub fn projected_box(&self, bx: &VolumeBox) -> PixelRect {
        let full = PixelRect { x0: 0, y0: 0, x1: self.width, y1: self.height };
        let mut lo = Vec2::splat(f32::INFINITY);
        let mut hi = Vec2::splat(f32::NEG_INFINITY);
        for c in bx.corners() {
            match self.project(c) {
                Some(p) => {
                    lo = lo.min(p);
                    hi = hi.max(p);
                }
                None => return full,
            }
        }
        let clamp_x = |v: f32| v.clamp(0.0, self.width as f32);
        let clamp_y = |v: f32| v.clamp(0.0, self.height as f32);
        PixelRect {
            x0: clamp_x(lo.x.floor()) as u32,
            y0: clamp_y(lo.y.floor()) as u32,
            x1: clamp_x(hi.x.ceil()) as u32,
            y1: clamp_y(hi.y.ceil()) as u32,
        }
    }
}
