//! Light sources: directional, point and spot, with colour and intensity (HDR).
//!
//! Conventions (docs/optical-model.md): a directional light's `direction` is the
//! direction the light travels (from the light into the scene). Point and spot
//! lights have no distance falloff unless `falloff` says inverse-square; a spot
//! light is full inside `inner_cone_deg`, zero outside `outer_cone_deg`, and
//! smooth-stepped between (half-angles).

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
