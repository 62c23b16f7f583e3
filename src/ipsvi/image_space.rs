//! Where world points and the light land on the image: the projected bounding
//! box of the volume, and the light's image-space anchor the sweep starts from.

use crate::scene::{LightKind, RayBasis, VolumeBox};
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

/// How the light shows in the image (section 4.1 of the IPSVI paper, extended to
/// perspective cameras): light moving along one image direction (directional
/// light seen by an orthographic camera), light spreading out of an image point
/// (a light in front of the camera, or the vanishing point of a directional light
/// coming toward the camera), or light converging into one (behind the camera, or
/// the vanishing point of a light travelling away from the camera).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LightAnchor {
    /// Light travels along this image direction everywhere (not normalized).
    AtInfinity(Vec2),
    Source(Vec2),
    Sink(Vec2),
}

/// Beyond this many image widths away, an anchor point is treated as a direction.
const FAR_AWAY_IMAGES: f32 = 64.0;

impl ImageSpace {
    fn ndc_to_pixel(&self, nx: f32, ny: f32) -> Vec2 {
        Vec2::new((nx + 1.0) * 0.5 * self.width as f32, (1.0 - ny) * 0.5 * self.height as f32)
    }

    /// Image-plane components of a world vector: (along right, along up) in ndc
    /// units per unit depth (perspective) or per world unit (orthographic).
    fn lateral(&self, v: Vec3) -> Vec2 {
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

    /// Image direction (pixels) of a small world displacement, orthographic only.
    fn image_direction(&self, v: Vec3) -> Vec2 {
        let l = self.lateral(v);
        Vec2::new(l.x * 0.5 * self.width as f32, -l.y * 0.5 * self.height as f32)
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

    /// Where the light's rays appear to come from or go to in the image.
    pub fn light_anchor(&self, light: &LightKind) -> LightAnchor {
        let far = FAR_AWAY_IMAGES * self.width.max(self.height) as f32;
        match *light {
            LightKind::Directional { direction } => {
                let w = direction.normalize_or(Vec3::NEG_Y);
                if self.basis.orthographic {
                    return LightAnchor::AtInfinity(self.image_direction(w));
                }
                let z = w.dot(self.basis.forward);
                let l = self.lateral(w);
                let lateral_px = Vec2::new(l.x * self.width as f32, l.y * self.height as f32).length();
                if z.abs() * far <= lateral_px {
                    // The vanishing point is far outside the image: parallel sweep.
                    return LightAnchor::AtInfinity(Vec2::new(l.x * self.width as f32, -l.y * self.height as f32));
                }
                let vp = self.ndc_to_pixel(l.x / z, l.y / z);
                if z > 0.0 {
                    LightAnchor::Sink(vp)
                } else {
                    LightAnchor::Source(vp)
                }
            }
            LightKind::Point { position } | LightKind::Spot { position, .. } => {
                let v = position - self.basis.origin;
                let l = self.lateral(v);
                if self.basis.orthographic {
                    return LightAnchor::Source(self.ndc_to_pixel(l.x, l.y));
                }
                let z = v.dot(self.basis.forward);
                let lateral_px = Vec2::new(l.x * self.width as f32, l.y * self.height as f32).length();
                if z.abs() * far <= lateral_px {
                    // In the eye plane: light enters from that side of the image.
                    return LightAnchor::AtInfinity(Vec2::new(-l.x * self.width as f32, l.y * self.height as f32));
                }
                let p = self.ndc_to_pixel(l.x / z, l.y / z);
                if z > 0.0 {
                    LightAnchor::Source(p)
                } else {
                    LightAnchor::Sink(p)
                }
            }
        }
    }
}
