//! Light space: a plane of texels fitted to the volume as seen from the light,
//! where IPSVI keeps its illumination cache and half-angle slicing its light
//! buffer (IPSVI paper's light-frustum adaptation, section 5.2); square texels
//! so the aspect is kept. Directional lights: an orthographic light view. Point
//! and spot lights outside the volume's bounding sphere: a perspective light
//! frustum around the box. Lights inside it: an octahedral map of all
//! directions around the light.

use crate::scene::{LightKind, VolumeBox};
use glam::Vec3;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LightProjection {
    Orthographic = 0,
    Perspective = 1,
    Octahedral = 2,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightSpacePlane {
    pub projection: LightProjection,
    /// Light position, or (directional) a point behind the whole volume.
    pub origin: Vec3,
    /// Light travel direction (orthographic) or frustum axis (perspective).
    pub axis: Vec3,
    pub u: Vec3,
    pub v: Vec3,
    /// Start of the cache along u and v, in plane units (world or tangent).
    pub a0: f32,
    pub b0: f32,
    /// Texel size in the same units.
    pub texel: f32,
    pub size: u32,
}

impl LightSpacePlane {
    pub fn fit(light: &LightKind, bx: &VolumeBox, size: u32) -> LightSpacePlane {
        LightSpacePlane::fit_to(light, &bx.corners(), bx.half_extent.length(), size)
    }

    /// Fitted to the box of `corners`; `radius` is the volume's bounding sphere
    /// (about the origin), which decides whether a point light is inside it.
    pub fn fit_to(light: &LightKind, corners: &[Vec3; 8], radius: f32, size: u32) -> LightSpacePlane {
        let size = size.max(2);
        match *light {
            LightKind::Directional { direction } => {
                let axis = direction.normalize_or(Vec3::NEG_Y);
                let (u, v) = axis.any_orthonormal_pair();
                let (lo, hi) = extent(corners.iter().map(|c| (c.dot(u), c.dot(v))));
                let (a0, b0, texel) = square(lo, hi, size);
                LightSpacePlane {
                    projection: LightProjection::Orthographic,
                    origin: -axis * (2.0 * radius + 1.0),
                    axis,
                    u,
                    v,
                    a0,
                    b0,
                    texel,
                    size,
                }
            }
            LightKind::Point { position } | LightKind::Spot { position, .. } => {
                if position.length() > radius * 1.05 {
                    let axis = (-position).normalize();
                    let (u, v) = axis.any_orthonormal_pair();
                    let (lo, hi) = extent(corners.iter().map(|c| {
                        let q = *c - position;
                        let z = q.dot(axis);
                        (q.dot(u) / z, q.dot(v) / z)
                    }));
                    let (a0, b0, texel) = square(lo, hi, size);
                    LightSpacePlane {
                        projection: LightProjection::Perspective,
                        origin: position,
                        axis,
                        u,
                        v,
                        a0,
                        b0,
                        texel,
                        size,
                    }
                } else {
                    // Texel "size" of the octahedral map: the angle one texel spans, roughly.
                    let texel = std::f32::consts::PI / size as f32;
                    LightSpacePlane {
                        projection: LightProjection::Octahedral,
                        origin: position,
                        axis: Vec3::Z,
                        u: Vec3::X,
                        v: Vec3::Y,
                        a0: 0.0,
                        b0: 0.0,
                        texel,
                        size,
                    }
                }
            }
        }
    }

    /// Continuous cache coordinates of world point p (texel centres at i + 0.5)
    /// and its distance along its light ray: the same mapping as the shader.
    pub fn coord(&self, p: Vec3) -> (f32, f32, f32) {
        let q = p - self.origin;
        match self.projection {
            LightProjection::Orthographic => {
                ((q.dot(self.u) - self.a0) / self.texel, (q.dot(self.v) - self.b0) / self.texel, q.dot(self.axis))
            }
            LightProjection::Perspective => {
                let z = q.dot(self.axis).max(1e-12);
                ((q.dot(self.u) / z - self.a0) / self.texel, (q.dot(self.v) / z - self.b0) / self.texel, q.length())
            }
            LightProjection::Octahedral => {
                let d = q.normalize_or(Vec3::Z);
                let s = d.x.abs() + d.y.abs() + d.z.abs();
                let (mut ex, mut ey) = (d.x / s, d.y / s);
                if d.z < 0.0 {
                    let (ox, oy) = (ex, ey);
                    ex = (1.0 - oy.abs()) * if ox >= 0.0 { 1.0 } else { -1.0 };
                    ey = (1.0 - ox.abs()) * if oy >= 0.0 { 1.0 } else { -1.0 };
                }
                ((ex * 0.5 + 0.5) * self.size as f32, (ey * 0.5 + 0.5) * self.size as f32, q.length())
            }
        }
    }
}

fn extent(points: impl Iterator<Item = (f32, f32)>) -> ((f32, f32), (f32, f32)) {
    let mut lo = (f32::INFINITY, f32::INFINITY);
    let mut hi = (f32::NEG_INFINITY, f32::NEG_INFINITY);
    for (a, b) in points {
        lo = (lo.0.min(a), lo.1.min(b));
        hi = (hi.0.max(a), hi.1.max(b));
    }
    (lo, hi)
}

/// A square of `size` texels around the rectangle, one texel of margin per side.
fn square(lo: (f32, f32), hi: (f32, f32), size: u32) -> (f32, f32, f32) {
    let side = (hi.0 - lo.0).max(hi.1 - lo.1).max(1e-6);
    let texel = side / (size as f32 - 2.0).max(1.0);
    let centre = ((lo.0 + hi.0) * 0.5, (lo.1 + hi.1) * 0.5);
    let half = texel * size as f32 * 0.5;
    (centre.0 - half, centre.1 - half, texel)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::UVec3;

    fn inside(g: &LightSpacePlane, p: Vec3) -> bool {
        let (x, y, _) = g.coord(p);
        x >= 0.0 && y >= 0.0 && x <= g.size as f32 && y <= g.size as f32
    }

    #[test]
    fn every_corner_of_the_box_lands_on_the_cache() {
        let bx = VolumeBox::new(UVec3::new(64, 32, 48), Vec3::ONE);
        for light in [
            LightKind::Directional { direction: Vec3::new(0.3, -1.0, 0.2) },
            LightKind::Point { position: Vec3::new(2.0, 1.0, 0.5) },
            LightKind::Point { position: Vec3::new(0.1, 0.0, 0.0) },
        ] {
            let g = LightSpacePlane::fit(&light, &bx, 64);
            for c in bx.corners() {
                assert!(inside(&g, c), "{light:?}: corner {c} maps to {:?}", g.coord(c));
            }
        }
    }

    #[test]
    fn fitted_cache_is_tight_for_a_directional_light() {
        let bx = VolumeBox::new(UVec3::splat(32), Vec3::ONE);
        let g = LightSpacePlane::fit(&LightKind::Directional { direction: Vec3::NEG_Y }, &bx, 66);
        // The unit cube seen from above: 1 world unit over 64 texels plus margins.
        assert!((g.texel - 1.0 / 64.0).abs() < 1e-6, "{}", g.texel);
    }

    #[test]
    fn light_inside_the_volume_uses_the_octahedral_map() {
        let bx = VolumeBox::new(UVec3::splat(32), Vec3::ONE);
        let g = LightSpacePlane::fit(&LightKind::Point { position: Vec3::ZERO }, &bx, 32);
        assert_eq!(g.projection, LightProjection::Octahedral);
        let (_, _, t) = g.coord(Vec3::new(0.3, 0.0, 0.4));
        assert!((t - 0.5).abs() < 1e-6);
    }
}
