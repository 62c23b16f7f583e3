//! Camera control with the mouse: drag with the left button to orbit about the
//! target, with the right (or middle) button to pan, the wheel to zoom; and
//! light control: Ctrl and the left button drag the panel's selected light.

use crate::scene::{Camera, Light, LightKind};
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
    let (right, up) = view_axes(c);
    let shift = (-right * dx + up * dy) * per_pixel;
    Camera { eye: c.eye + shift, target: c.target + shift, ..c }
}

/// The view's right and up directions.
fn view_axes(c: Camera) -> (Vec3, Vec3) {
    let right = c.forward().cross(c.up).normalize_or(Vec3::X);
    (right, right.cross(c.forward()))
}

/// `light` dragged by (`dx`, `dy`) pixels in a view `height` pixels high: a
/// point or spot light moves on the plane facing the camera through it (as
/// far per pixel as `pan` moves the camera at that depth), a directional
/// light turns (as far per pixel as `orbit` turns the camera).
pub fn drag_light(light: Light, c: Camera, dx: f32, dy: f32, height: u32) -> Light {
    let (right, up) = view_axes(c);
    let kind = match light.kind {
        LightKind::Directional { direction } => {
            let yaw = Quat::from_axis_angle(up, (dx * ORBIT_DEG_PER_PIXEL).to_radians());
            let pitch = Quat::from_axis_angle(right, (dy * ORBIT_DEG_PER_PIXEL).to_radians());
            LightKind::Directional { direction: yaw * pitch * direction }
        }
        LightKind::Point { position } => LightKind::Point { position: on_view_plane(c, position, dx, dy, height) },
        LightKind::Spot { position, direction, inner_cone_deg, outer_cone_deg } => LightKind::Spot {
            position: on_view_plane(c, position, dx, dy, height),
            direction,
            inner_cone_deg,
            outer_cone_deg,
        },
    };
    Light { kind, ..light }
}

/// `p` moved by (`dx`, `dy`) pixels on the plane facing the camera.
fn on_view_plane(c: Camera, p: Vec3, dx: f32, dy: f32, height: u32) -> Vec3 {
    let (right, up) = view_axes(c);
    let depth = (p - c.eye).dot(c.forward()).abs().max(1e-3);
    p + (right * dx - up * dy) * (depth / height.max(1) as f32)
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

    #[test]
    fn a_dragged_light_moves_on_the_view_plane_or_turns() {
        let c = Camera::orbit(Vec3::ZERO, 3.0, 30.0, 20.0, Projection::Perspective { fov_y_deg: 30.0 });
        let point = Light {
            kind: LightKind::Point { position: Vec3::new(0.5, 0.2, 0.1) },
            color: Vec3::ONE,
            intensity: 1.0,
            falloff: crate::scene::Falloff::None,
        };
        let LightKind::Point { position: p0 } = point.kind else { unreachable!() };
        let LightKind::Point { position: p1 } = drag_light(point, c, 20.0, -10.0, 100).kind else { unreachable!() };
        let shift = p1 - p0;
        assert!(shift.length() > 0.1, "{shift}");
        assert!(shift.dot(c.forward()).abs() < 1e-5, "stays at its depth");
        let right = c.forward().cross(c.up).normalize();
        assert!(shift.dot(right) > 0.0 && shift.dot(right.cross(c.forward())) > 0.0, "right and up, as dragged");
        let sun = Light { kind: LightKind::Directional { direction: Vec3::new(1.0, -1.0, -1.0) }, ..point };
        let LightKind::Directional { direction } = drag_light(sun, c, 30.0, 0.0, 100).kind else { unreachable!() };
        assert!(
            (direction.length() - 3f32.sqrt()).abs() < 1e-4 && (direction - Vec3::new(1.0, -1.0, -1.0)).length() > 0.1
        );
        assert_eq!(drag_light(point, c, 0.0, 0.0, 100), point);
    }
}
