//! Camera control with the mouse: drag with the left button to orbit about the
//! target, with the right (or middle) button to pan, the wheel to zoom.

use crate::scene::Camera;
use glam::{Quat, Vec3};

/// Degrees of orbit per pixel dragged.
const ORBIT_DEG_PER_PIXEL: f32 = 0.4;
/// Fraction of the distance to the target per wheel line.
const ZOOM_PER_LINE: f32 = 0.1;

pub fn orbit(c: Camera, dx: f32, dy: f32) -> Camera {
    let offset = c.eye - c.target;
    let yaw = Quat::from_axis_angle(Vec3::Y, (-dx * ORBIT_DEG_PER_PIXEL).to_radians());
    let right = c.forward().cross(c.up).normalize_or(Vec3::X);
    let pitch = Quat::from_axis_angle(right, (-dy * ORBIT_DEG_PER_PIXEL).to_radians());
    let moved = yaw * pitch * offset;
    // Stop short of the poles, where the up vector would flip.
    if moved.normalize_or(Vec3::Z).dot(Vec3::Y).abs() > 0.995 {
        return Camera { eye: c.target + yaw * offset, ..c };
    }
    Camera { eye: c.target + moved, ..c }
}

pub fn zoom(c: Camera, lines: f32) -> Camera {
    let offset = (c.eye - c.target) * (1.0 - ZOOM_PER_LINE).powf(lines);
    Camera { eye: c.target + offset, ..c }
}

/// Moves eye and target in the view plane; `height` is the window height in pixels.
pub fn pan(c: Camera, dx: f32, dy: f32, height: u32) -> Camera {
    let distance = (c.eye - c.target).length();
    let per_pixel = distance / height.max(1) as f32;
    let right = c.forward().cross(c.up).normalize_or(Vec3::X);
    let up = right.cross(c.forward());
    let shift = (-right * dx + up * dy) * per_pixel;
    Camera { eye: c.eye + shift, target: c.target + shift, ..c }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Projection;

    #[test]
    fn orbit_keeps_the_distance_zoom_scales_it_pan_keeps_the_view_direction() {
        let c = Camera::orbit(Vec3::ZERO, 3.0, 30.0, 20.0, Projection::Perspective { fov_y_deg: 30.0 });
        let o = orbit(c, 50.0, 10.0);
        assert!(((o.eye - o.target).length() - 3.0).abs() < 1e-4);
        assert!((o.eye - c.eye).length() > 0.1);
        let z = zoom(c, 2.0);
        assert!(((z.eye - z.target).length() - 3.0 * 0.81).abs() < 1e-4);
        let p = pan(c, 10.0, 0.0, 100);
        assert!((p.forward() - c.forward()).length() < 1e-5 && (p.target - c.target).length() > 0.0);
    }
}
