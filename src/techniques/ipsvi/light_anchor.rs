//! The light's image-space anchor the sweep starts from (what only IPSVI needs
//! of the image space, [`crate::render::image_space`]).

use crate::render::image_space::ImageSpace;
use crate::scene::LightKind;
use glam::{Vec2, Vec3};

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

// The sweep's part of the image space, kept here since only IPSVI uses it.
impl ImageSpace {
    /// Image direction (pixels) of a small world displacement, orthographic only.
    fn image_direction(&self, v: Vec3) -> Vec2 {
        let l = self.lateral(v);
        Vec2::new(l.x * 0.5 * self.width as f32, -l.y * 0.5 * self.height as f32)
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
