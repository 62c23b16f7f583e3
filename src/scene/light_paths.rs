//! Light geometry in f64: direction and distance to a light, distance falloff
//! and spot cone, as the discretization contract defines them.

use glam::DVec3;

use crate::scene::{Falloff, Light, LightKind};

/// Where a light is, seen from a point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightPath {
    /// Unit vector from the point toward the light.
    pub toward: DVec3,
    /// Distance to the light; infinite for directional lights.
    pub distance: f64,
}

/// Mirrors [`Light::toward_light`] in f64, with the same fallbacks: a zero
/// directional `direction` travels along -y, a point at the light's own position
/// looks up (+y).
pub fn toward_light(light: &Light, p: DVec3) -> LightPath {
    match light.kind {
        LightKind::Directional { direction } => {
            LightPath { toward: -direction.as_dvec3().normalize_or(DVec3::NEG_Y), distance: f64::INFINITY }
        }
        LightKind::Point { position } | LightKind::Spot { position, .. } => {
            let d = position.as_dvec3() - p;
            let len = d.length();
            LightPath { toward: if len > 0.0 { d / len } else { DVec3::Y }, distance: len }
        }
    }
}

/// Colour times intensity (HDR), before falloff, cone and shadowing.
pub fn radiance(light: &Light) -> DVec3 {
    light.color.as_dvec3() * light.intensity as f64
}

/// 1, or `1 / max(dist, voxel_length)^2` for inverse-square point and spot lights
/// (clamped so a light inside the volume stays finite). Directional lights: 1.
pub fn falloff(light: &Light, path: &LightPath, voxel_length: f64) -> f64 {
    let is_directional = matches!(light.kind, LightKind::Directional { .. });
    match light.falloff {
        Falloff::InverseSquare if !is_directional => {
            let d = path.distance.max(voxel_length);
            1.0 / (d * d)
        }
        _ => 1.0,
    }
}

/// Spot attenuation: smoothstep from the outer to the inner half-angle, a hard
/// step at the outer one when inner >= outer. 1 for other lights. A zero spot
/// axis falls back to -y, as on the GPU.
pub fn cone(light: &Light, path: &LightPath) -> f64 {
    let LightKind::Spot { direction, inner_cone_deg, outer_cone_deg, .. } = light.kind else {
        return 1.0;
    };
    let axis = direction.as_dvec3().normalize_or(DVec3::NEG_Y);
    let c = (-path.toward).dot(axis);
    let ci = (inner_cone_deg as f64).to_radians().cos();
    let co = (outer_cone_deg as f64).to_radians().cos();
    if ci <= co {
        if c >= co {
            1.0
        } else {
            0.0
        }
    } else {
        smoothstep(co, ci, c)
    }
}

/// GLSL smoothstep: `t * t * (3 - 2t)`, `t = clamp((x - e0) / (e1 - e0), 0, 1)`.
pub fn smoothstep(e0: f64, e1: f64, x: f64) -> f64 {
    let t = ((x - e0) / (e1 - e0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn spot(inner: f32, outer: f32) -> Light {
        Light {
            kind: LightKind::Spot {
                position: Vec3::new(0.0, 2.0, 0.0),
                direction: Vec3::new(0.0, -3.0, 0.0),
                inner_cone_deg: inner,
                outer_cone_deg: outer,
            },
            color: Vec3::ONE,
            intensity: 1.0,
            falloff: Falloff::InverseSquare,
        }
    }

    /// Point at angle `deg` off the spot axis, 2 units from the light.
    fn off_axis(deg: f64) -> DVec3 {
        let a = deg.to_radians();
        DVec3::new(0.0, 2.0, 0.0) + DVec3::new(a.sin(), -a.cos(), 0.0) * 2.0
    }

    #[test]
    fn directional_points_against_travel_direction() {
        let light = Light {
            kind: LightKind::Directional { direction: Vec3::new(0.0, 0.0, -5.0) },
            color: Vec3::ONE,
            intensity: 1.0,
            falloff: Falloff::InverseSquare,
        };
        let path = toward_light(&light, DVec3::ZERO);
        assert_eq!(path.toward, DVec3::Z);
        assert_eq!(path.distance, f64::INFINITY);
        // Inverse-square does not apply to directional lights.
        assert_eq!(falloff(&light, &path, 0.01), 1.0);
        assert_eq!(cone(&light, &path), 1.0);
    }

    #[test]
    fn inverse_square_is_clamped_at_one_voxel() {
        let light = spot(10.0, 20.0);
        let far = toward_light(&light, DVec3::new(0.0, -2.0, 0.0));
        assert_eq!(far.distance, 4.0);
        assert_eq!(falloff(&light, &far, 0.1), 1.0 / 16.0);
        let at_light = toward_light(&light, DVec3::new(0.0, 2.0, 0.0));
        assert_eq!(at_light.toward, DVec3::Y);
        assert_eq!(falloff(&light, &at_light, 0.1), 1.0 / (0.1 * 0.1));
    }

    #[test]
    fn spot_cone_is_full_inside_zero_outside_smooth_between() {
        let light = spot(10.0, 20.0);
        let at = |deg: f64| cone(&light, &toward_light(&light, off_axis(deg)));
        assert!((at(0.0) - 1.0).abs() < 1e-15);
        assert!((at(9.9) - 1.0).abs() < 1e-15);
        assert_eq!(at(20.1), 0.0);
        assert_eq!(at(90.0), 0.0);
        // Between: the smoothstep of the cosine, strictly decreasing with angle.
        let (a, b) = (at(12.0), at(18.0));
        assert!(1.0 > a && a > b && b > 0.0, "{a} {b}");
        let co = 20f64.to_radians().cos();
        let ci = 10f64.to_radians().cos();
        let t = (15f64.to_radians().cos() - co) / (ci - co);
        assert!((at(15.0) - t * t * (3.0 - 2.0 * t)).abs() < 1e-12);
    }

    #[test]
    fn spot_with_inner_not_below_outer_is_a_hard_step() {
        let light = spot(20.0, 20.0);
        let at = |deg: f64| cone(&light, &toward_light(&light, off_axis(deg)));
        assert_eq!(at(19.9), 1.0);
        assert_eq!(at(20.1), 0.0);
        let wider_inner = spot(30.0, 20.0);
        assert_eq!(cone(&wider_inner, &toward_light(&wider_inner, off_axis(25.0))), 0.0);
    }

    #[test]
    fn smoothstep_ends_and_middle() {
        assert_eq!(smoothstep(0.0, 1.0, -1.0), 0.0);
        assert_eq!(smoothstep(0.0, 1.0, 2.0), 1.0);
        assert_eq!(smoothstep(0.0, 1.0, 0.5), 0.5);
        assert!((smoothstep(0.0, 2.0, 0.5) - 0.15625).abs() < 1e-15);
    }
}
