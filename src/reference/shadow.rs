//! Brute-force shadow ray from a sample toward one light (midpoint rule, as in
//! the discretization contract): transmittance to the light and, for model (ii),
//! the emission of the media on the way, attenuated on its way to the sample.

use glam::DVec3;

use super::medium::Medium;
use crate::scene::light_paths::LightPath;
use crate::scene::{Light, LightKind};

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadowSample {
    /// `Tl = exp(-tau)` from the sample to the light (or to the box exit).
    pub transmittance: f64,
    /// `El`: emission gathered along the shadow ray (zero unless asked for).
    pub emission: DVec3,
    /// Per-channel transmittance under coloured extinction (the `chromatic`
    /// option): optical depth `sigma * max(1 - rgb, 0)` per channel.
    pub coloured: DVec3,
}

/// Marches from `p` toward the light of `path` with steps of about
/// `step_voxels` voxels. `gather_emission` is the emission scale of model (ii),
/// `None` for model (i) (then `emission` is zero).
pub fn trace_shadow(
    medium: &Medium,
    light: &Light,
    p: DVec3,
    path: &LightPath,
    step_voxels: f64,
    gather_emission: Option<f64>,
) -> ShadowSample {
    let mut distance = medium.exit_distance(p, path.toward);
    if !matches!(light.kind, LightKind::Directional { .. }) {
        distance = distance.min(path.distance);
    }
    let mut result = ShadowSample { transmittance: 1.0, emission: DVec3::ZERO, coloured: DVec3::ONE };
    if distance <= 0.0 {
        return result;
    }
    let vl = medium.voxel_length();
    let steps = (distance / (step_voxels * vl)).ceil().max(1.0);
    let g = distance / steps;
    let gv = g / vl;
    let mut tau = 0.0f64;
    let mut tau_coloured = DVec3::ZERO;
    for j in 0..steps as u64 {
        let q = p + path.toward * ((j as f64 + 0.5) * g);
        let m = medium.at(q);
        if let Some(emission) = gather_emission {
            let a = 1.0 - (-m.sigma * gv).exp();
            result.emission += (-tau).exp() * a * emission * m.rgb;
        }
        tau += m.sigma * gv;
        tau_coloured += m.sigma * gv * (DVec3::ONE - m.rgb).max(DVec3::ZERO);
    }
    result.transmittance = (-tau).exp();
    result.coloured = (-tau_coloured).exp();
    result
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::light_paths::toward_light;
    use crate::scene::{ControlPoint, Falloff, TransferFunction, Volume, VoxelData};
    use glam::{UVec3, Vec3};

    fn homogeneous(alpha: f32) -> (Volume, TransferFunction) {
        let n = 8;
        let volume = Volume {
            name: "constant".into(),
            dims: UVec3::splat(n),
            spacing: Vec3::ONE,
            data: VoxelData::U8(vec![255; (n * n * n) as usize]),
            value_range: (0.0, 255.0),
            non_finite_voxels: 0,
            interpolation: Default::default(),
        };
        let transfer = TransferFunction { points: vec![ControlPoint { value: 0.0, rgba: [0.5, 0.25, 1.0, alpha] }] };
        (volume, transfer)
    }

    fn light_at(position: Vec3) -> Light {
        Light { kind: LightKind::Point { position }, color: Vec3::ONE, intensity: 1.0, falloff: Falloff::None }
    }

    #[test]
    fn homogeneous_medium_matches_closed_form() {
        let (volume, transfer) = homogeneous(0.2);
        let medium = Medium::new(&volume, &transfer);
        let sigma = medium.lut().texels[0][3] as f64;
        let rgb = DVec3::new(0.5, 0.25, 1.0);
        // From 0.3 below the top face straight up to a light far outside the box:
        // the ray leaves the box after 0.3 world units = 2.4 voxels.
        let p = DVec3::new(0.1, 0.2, -0.05);
        let light = light_at(Vec3::new(0.1, 3.0, -0.05));
        let path = toward_light(&light, p);
        let depth_voxels = 0.3 / medium.voxel_length();
        for step in [0.7, 0.5, 0.25] {
            let s = trace_shadow(&medium, &light, p, &path, step, Some(0.4));
            let t = (-sigma * depth_voxels).exp();
            assert!((s.transmittance - t).abs() < 1e-14, "{step}");
            // The emission of a homogeneous medium telescopes exactly:
            // sum_j exp(-tau_j) (1 - exp(-sigma gv)) = 1 - exp(-sigma D).
            let e = rgb * 0.4 * (1.0 - t);
            assert!((s.emission - e).abs().max_element() < 1e-14, "{step}");
            // Coloured extinction: each channel's depth is sigma * (1 - rgb).
            let coloured = (-(DVec3::ONE - rgb) * sigma * depth_voxels).exp();
            assert!((s.coloured - coloured).abs().max_element() < 1e-14, "{step}");
        }
    }

    #[test]
    fn light_inside_the_box_stops_the_ray_at_the_light() {
        let (volume, transfer) = homogeneous(0.2);
        let medium = Medium::new(&volume, &transfer);
        let sigma = medium.lut().texels[0][3] as f64;
        let p = DVec3::new(0.0, -0.25, 0.0);
        let light = light_at(Vec3::new(0.0, 0.25, 0.0));
        let path = toward_light(&light, p);
        let s = trace_shadow(&medium, &light, p, &path, 0.5, None);
        let expected = (-sigma * 0.5 / medium.voxel_length()).exp();
        assert!((s.transmittance - expected).abs() < 1e-14);
        assert_eq!(s.emission, DVec3::ZERO);
    }

    #[test]
    fn sample_at_the_light_is_unshadowed() {
        let (volume, transfer) = homogeneous(0.9);
        let medium = Medium::new(&volume, &transfer);
        let light = light_at(Vec3::new(0.125, 0.0, 0.0));
        let p = DVec3::new(0.125, 0.0, 0.0);
        let s = trace_shadow(&medium, &light, p, &toward_light(&light, p), 0.5, Some(1.0));
        assert_eq!(s.transmittance, 1.0);
        assert_eq!(s.emission, DVec3::ZERO);
    }
}
