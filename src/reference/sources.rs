//! Source terms `S(p)` of the view march (what one sample sends toward the eye
//! per unit of its opacity): Blinn-Phong for the baselines and the scattering
//! of the reference models (i) and (ii). Unshaded DVR is just `rgb`.

use glam::DVec3;

use super::medium::Medium;
use super::shadow::trace_shadow;
use crate::scene::light_paths::{cone, falloff, radiance, toward_light};
use crate::scene::{Light, OpticalModel, PhongSettings};

/// Below this gradient length a sample counts as unshaded (no normal).
pub const MIN_GRADIENT: f64 = 1e-6;

/// Gradient of the normalized scalar by central differences one texel apart,
/// in scalar units per voxel along each axis.
pub fn gradient(medium: &Medium, p: DVec3) -> DVec3 {
    let uvw = medium.uvw(p);
    let texel = DVec3::ONE / medium.dims();
    let mut g = DVec3::ZERO;
    for axis in 0..3 {
        let mut e = DVec3::ZERO;
        e[axis] = texel[axis];
        g[axis] = (medium.smooth_scalar_at_uvw(uvw + e) - medium.smooth_scalar_at_uvw(uvw - e)) / 2.0;
    }
    g
}

/// Blinn-Phong without shadows; `view_dir` is the unit view-ray direction.
pub fn phong(
    medium: &Medium,
    settings: &PhongSettings,
    lights: &[Light],
    p: DVec3,
    rgb: DVec3,
    view_dir: DVec3,
) -> DVec3 {
    let ambient = settings.ambient as f64;
    let diffuse = settings.diffuse as f64;
    let specular = settings.specular as f64;
    let shininess = settings.shininess as f64;
    // Without lights or without a normal the sample is shaded flat (the
    // contract's constant fallback, written as the GPU shader writes it).
    if lights.is_empty() {
        return rgb * (ambient + diffuse);
    }
    let g = gradient(medium, p);
    let len = g.length();
    if len < MIN_GRADIENT {
        return rgb * (ambient + diffuse);
    }
    let mut n = -g / len;
    if n.dot(-view_dir) < 0.0 {
        n = -n;
    }
    let mut s = rgb * ambient;
    for light in lights {
        let path = toward_light(light, p);
        let w = path.toward;
        let lit = radiance(light) * falloff(light, &path, medium.voxel_length()) * cone(light, &path);
        // w == view_dir leaves the half vector undefined: no highlight then.
        let half = (w - view_dir).normalize_or_zero();
        let highlight = n.dot(half).max(0.0).powf(shininess);
        s += lit * (rgb * diffuse * n.dot(w).max(0.0) + DVec3::splat(specular * highlight));
    }
    s
}

/// Single scattering of every light (model (i)) or emissive scattering (model
/// (ii)): `rgb * (emission + sum_l [radiance * falloff * cone * Tl (+ El)])`;
/// with `chromatic`, `Tl` is per channel under coloured extinction.
#[allow(clippy::too_many_arguments)]
pub fn scattering(
    medium: &Medium,
    lights: &[Light],
    model: OpticalModel,
    chromatic: bool,
    emission: f64,
    shadow_step_voxels: f64,
    p: DVec3,
    rgb: DVec3,
) -> DVec3 {
    let gather = match model {
        OpticalModel::SingleScattering => None,
        OpticalModel::EmissiveScattering => Some(emission),
    };
    let mut light_in = DVec3::splat(emission);
    for light in lights {
        let path = toward_light(light, p);
        let shadow = trace_shadow(medium, light, p, &path, shadow_step_voxels, gather);
        let transmittance = if chromatic { shadow.coloured } else { DVec3::splat(shadow.transmittance) };
        let direct =
            radiance(light) * falloff(light, &path, medium.voxel_length()) * cone(light, &path) * transmittance;
        light_in += match model {
            OpticalModel::SingleScattering => direct,
            OpticalModel::EmissiveScattering => direct + shadow.emission,
        };
    }
    rgb * light_in
}
