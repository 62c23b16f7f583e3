//! Perspective and orthographic cameras, with an orbit constructor.
//!
//! Pixel (x, y) of a W x H image (y down) maps to ndc = ((x + 0.5) / W * 2 - 1,
//! 1 - (y + 0.5) / H * 2). The GPU receives the same [`RayBasis`] and forms rays
//! identically, so CPU and GPU renderers see the same rays.

use glam::Vec3;

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection {
    /// Vertical field of view in degrees.
    Perspective { fov_y_deg: f32 },
    /// Height of the view in world units.
    Orthographic { height: f32 },
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    pub eye: Vec3,
    pub target: Vec3,
    pub up: Vec3,
    pub projection: Projection,
}

/// What a ray generator needs: `origin + ndc.x * right + ndc.y * up` and direction
/// `forward (+ ndc.x * right + ndc.y * up for perspective)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayBasis {
    pub origin: Vec3,
    pub forward: Vec3,
    /// Scaled by half the view width (ortho) or tan(fov/2) * aspect (perspective).
    pub right: Vec3,
    /// Scaled by half the view height (ortho) or tan(fov/2) (perspective).
    pub up: Vec3,
    pub orthographic: bool,
}

impl Camera {
    /// Camera on a sphere around `target`: azimuth about +y from +z, elevation up
    /// from the xz plane, both in degrees.
    pub fn orbit(target: Vec3, distance: f32, azimuth_deg: f32, elevation_deg: f32, projection: Projection) -> Camera {
        let (az, el) = (azimuth_deg.to_radians(), elevation_deg.to_radians());
        let dir = Vec3::new(el.cos() * az.sin(), el.sin(), el.cos() * az.cos());
        let up = if el.cos().abs() < 1e-4 { Vec3::new(-az.sin(), 0.0, -az.cos()) * el.sin().signum() } else { Vec3::Y };
        Camera { eye: target + dir * distance, target, up, projection }
    }

    pub fn forward(&self) -> Vec3 {
        (self.target - self.eye).normalize_or(Vec3::NEG_Z)
    }

    pub fn basis(&self, width: u32, height: u32) -> RayBasis {
        let forward = self.forward();
        let mut right = forward.cross(self.up);
        if right.length_squared() < 1e-12 {
            right = forward.any_orthonormal_vector();
        }
        let right = right.normalize();
        let up = right.cross(forward);
        let aspect = width as f32 / height.max(1) as f32;
        match self.projection {
            Projection::Perspective { fov_y_deg } => {
                let t = (fov_y_deg.to_radians() * 0.5).tan();
                RayBasis { origin: self.eye, forward, right: right * t * aspect, up: up * t, orthographic: false }
            }
            Projection::Orthographic { height: h } => RayBasis {
                origin: self.eye,
                forward,
                right: right * h * 0.5 * aspect,
                up: up * h * 0.5,
                orthographic: true,
            },
        }
    }
}

impl RayBasis {
    /// The width of one pixel of an image `height` pixels high at world point
    /// `p` (pixels are square): its height at p's depth along the view.
    pub fn pixel_size_at(&self, p: Vec3, height: u32) -> f32 {
        let depth = if self.orthographic { 1.0 } else { (p - self.origin).dot(self.forward).max(1e-6) };
        2.0 * self.up.length() * depth / height.max(1) as f32
    }

    pub fn ndc(x: u32, y: u32, width: u32, height: u32) -> (f32, f32) {
        ((x as f32 + 0.5) / width as f32 * 2.0 - 1.0, 1.0 - (y as f32 + 0.5) / height as f32 * 2.0)
    }

    /// Ray through ndc (origin, unnormalized direction), in f64 for the reference.
    pub fn ray_f64(&self, nx: f64, ny: f64) -> ([f64; 3], [f64; 3]) {
        let o = self.origin.as_dvec3();
        let f = self.forward.as_dvec3();
        let r = self.right.as_dvec3();
        let u = self.up.as_dvec3();
        if self.orthographic {
            ((o + r * nx + u * ny).to_array(), f.to_array())
        } else {
            (o.to_array(), (f + r * nx + u * ny).normalize().to_array())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_pixel_grows_with_depth_in_perspective_and_not_in_orthographic_views() {
        let perspective = Camera::orbit(Vec3::ZERO, 2.0, 0.0, 0.0, Projection::Perspective { fov_y_deg: 90.0 });
        let b = perspective.basis(100, 100);
        // 90 degrees: the view is 2 * depth high, over 100 pixels.
        let at = |d: f32| b.pixel_size_at(b.origin + b.forward * d, 100);
        assert!((at(1.0) - 0.02).abs() < 1e-6 && (at(2.0) - 0.04).abs() < 1e-6, "{} {}", at(1.0), at(2.0));
        let ortho = Camera::orbit(Vec3::ZERO, 2.0, 0.0, 0.0, Projection::Orthographic { height: 3.0 });
        let o = ortho.basis(100, 50);
        for d in [0.5, 4.0] {
            assert!((o.pixel_size_at(o.origin + o.forward * d, 50) - 0.06).abs() < 1e-6);
        }
    }
}
