//! Light sources: directional, point and spot, with colour and intensity (HDR).
//!
//! Conventions (docs/optical-model.md): a directional light's `direction` is the
//! direction the light travels (from the light into the scene). Point and spot
//! lights have no distance falloff unless `falloff` says inverse-square; a spot
//! light is full inside `inner_cone_deg`, zero outside `outer_cone_deg`, and
//! smooth-stepped between (half-angles).
//!
//! Far lights ([`Light::far_limit`]): a point or spot light whose distance from
//! the volume's centre is so large that the volume's bounding radius is below
//! f32 precision of it (`radius < distance * f32::EPSILON`) sends parallel rays
//! across the volume as far as f32 can tell, and its distance (squared, for the
//! falloff) may not even be representable. Every scene replaces it by the
//! directional light it approaches, before any technique or the reference sees
//! it: travelling from its position toward the centre, its radiance scaled by
//! its falloff and spot cone at the centre (in f64).

use glam::Vec3;

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LightKind {
    Directional { direction: Vec3 },
    Point { position: Vec3 },
    Spot { position: Vec3, direction: Vec3, inner_cone_deg: f32, outer_cone_deg: f32 },
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Falloff {
    None,
    /// 1 / max(d, voxel_length)^2, clamped so a light inside the volume stays finite.
    InverseSquare,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Light {
    pub kind: LightKind,
    /// Linear RGB colour.
    pub color: Vec3,
    pub intensity: f32,
    pub falloff: Falloff,
}

impl Light {
    /// Radiance scale (colour * intensity), before shadowing.
    pub fn radiance(&self) -> Vec3 {
        self.color * self.intensity
    }

    /// The directional limit of a far point or spot light (see the module
    /// docs), or the light unchanged. `radius`: the volume box's bounding
    /// radius, the box centred at the origin.
    pub fn far_limit(&self, radius: f32) -> Light {
        let position = match self.kind {
            LightKind::Point { position } | LightKind::Spot { position, .. } => position,
            LightKind::Directional { .. } => return *self,
        };
        let distance = position.as_dvec3().length();
        if !position.is_finite() || (radius as f64) >= distance * f32::EPSILON as f64 {
            return *self;
        }
        use crate::scene::light_paths::{cone, falloff, toward_light};
        let at_centre = toward_light(self, glam::DVec3::ZERO);
        let scale = falloff(self, &at_centre, 0.0) * cone(self, &at_centre);
        // `+ 0` turns the negation's -0 components into +0: the light then is
        // the directional light written with plain zeros, bit for bit (IPSVI's
        // cache lays its texels out by the sign of z, and 1/-0 is -inf).
        Light {
            kind: LightKind::Directional { direction: (-at_centre.toward).as_vec3() + Vec3::ZERO },
            color: self.color,
            intensity: (self.intensity as f64 * scale) as f32,
            falloff: Falloff::None,
        }
    }

    /// Whether [`Light::far_limit`] turns this light into a directional one.
    pub fn is_far(&self, radius: f32) -> bool {
        self.far_limit(radius) != *self
    }

    /// Unit direction from point `p` toward the light, and the distance to it
    /// (infinite for directional lights).
    pub fn toward_light(&self, p: Vec3) -> (Vec3, f32) {
        match self.kind {
            LightKind::Directional { direction } => (-direction.normalize_or(Vec3::NEG_Y), f32::INFINITY),
            LightKind::Point { position } | LightKind::Spot { position, .. } => {
                let d = position - p;
                let len = d.length();
                (if len > 0.0 { d / len } else { Vec3::Y }, len)
            }
        }
    }
}

#[cfg(test)]
mod far_limit_tests {
    use super::*;

    fn point(position: Vec3, falloff: Falloff) -> Light {
        Light { kind: LightKind::Point { position }, color: Vec3::ONE, intensity: 2.0, falloff }
    }

    #[test]
    fn near_lights_stay_and_far_ones_become_directional_from_their_side() {
        let r = 0.87;
        for d in [1.0f32, 1e3, 1e6] {
            assert!(!point(Vec3::new(d, 0.0, 0.0), Falloff::None).is_far(r), "{d} is near");
        }
        for d in [1e8f32, 1e20, 3e38] {
            let l = point(Vec3::new(d, 0.0, 0.0), Falloff::None).far_limit(r);
            assert_eq!(l.kind, LightKind::Directional { direction: Vec3::NEG_X }, "{d}");
            assert_eq!(l.intensity, 2.0);
        }
    }

    #[test]
    fn the_limit_carries_the_falloff_and_cone_at_the_centre() {
        let l = point(Vec3::new(0.0, 1e10, 0.0), Falloff::InverseSquare).far_limit(0.87);
        assert_eq!(l.falloff, Falloff::None);
        assert!((l.intensity as f64 - 2e-20).abs() < 1e-26, "{}", l.intensity);
        let spot = |axis: Vec3| Light {
            kind: LightKind::Spot {
                position: Vec3::new(1e9, 0.0, 0.0),
                direction: axis,
                inner_cone_deg: 10.0,
                outer_cone_deg: 20.0,
            },
            color: Vec3::ONE,
            intensity: 3.0,
            falloff: Falloff::None,
        };
        assert_eq!(spot(Vec3::NEG_X).far_limit(0.87).intensity, 3.0, "the centre on the axis: full");
        assert_eq!(spot(Vec3::Y).far_limit(0.87).intensity, 0.0, "the centre outside the cone: none");
    }
}
