//! The error model of 8-bit sub-texel weights (docs/filtering.md), evaluated
//! per pixel: how far a GPU image filtered with `render.filter = "gpu-8bit"`
//! (or by NVIDIA, AMD or Intel hardware) may lie from the same image filtered
//! exactly, from the scene alone. The accuracy tests add it to their
//! exact-filter tolerances; with exact filtering every term is zero.
//!
//! The chain, each step a bound on the one before:
//! 1. a weight is off by at most `e_w` per axis (1/512 rounded to 8 bits);
//!    trilinear interpolation is linear in each weight with a slope of at most
//!    the largest difference along that axis within the cell: the scalar of a
//!    sample in cell c is off by `ds_c <= e_w (D_x + D_y + D_z)`;
//! 2. the transfer LUT is piecewise linear: sigma and colour move by at most
//!    `ds_c` times the LUT's largest slope over the cell's values (+- ds_c);
//! 3. the view march `I = sum_k T_k a_k S_k + T_N B`: `|dI/dtau_k| <= T_k M_k`
//!    with `M_k` the largest source (or background) at or behind sample k,
//!    and `|dI/dS_k| = T_k a_k`; with every quantity at its perturbed worst
//!    (`T_k e^{dtau before k}`, `a_k + dtau_k`, `S + dS`):
//!    `|dI| <= sum_k T_k e^{dtau_<k} (M_k dtau_k + (a_k + dtau_k) dS_k)`, plus
//!    `T_min e^{dtau} M` where early termination may stop at another sample;
//! 4. a lit sample's source `rgb (emission + sum_l L_l T_l (+ E_l))` moves by
//!    `d rgb` times it plus `rgb` times `sum_l L_l T_l (e^{dtau_l} - 1)` (the
//!    shadow ray's optical depth error `dtau_l`, marched like step 3) and, for
//!    model (ii), the emission `E_l` gathered on the way, bounded as step 3
//!    bounds a pixel.
//!
//! Gradient shading (Phong) is outside the model: a normal's direction moves
//! without bound where the gradient vanishes.

use glam::DVec3;

use super::cpu::{CpuRenderKind, EARLY_TERMINATION_TRANSMITTANCE};
use super::medium::Medium;
use super::parallel::render_rows;
use super::ray_start::ray_start_phase;
use super::validate::CpuRenderError;
use crate::linear_image::LinearImage;
use crate::scene::light_paths::{cone, falloff, radiance, toward_light};
use crate::scene::{Light, LightKind, OpticalModel, RayBasis, Scene, TransferLut, VolumeFilter};

/// Per-cell bounds of steps 1 and 2: the cell whose lower corner is voxel c
/// (its upper corner clamped to the volume, as clamp-to-edge does).
struct CellBounds {
    dims: [usize; 3],
    /// Scalar error.
    scalar: Vec<f32>,
    /// Sigma error (optical depth per voxel).
    sigma: Vec<f32>,
    /// Largest colour-channel error.
    rgb: Vec<f32>,
}

/// Largest absolute slope (per unit scalar) of a LUT channel group over a
/// range of segments: a sparse table, O(1) per query.
struct SlopeTable {
    levels: Vec<Vec<f32>>,
    texels: usize,
}

impl SlopeTable {
    fn new(lut: &TransferLut, channels: std::ops::Range<usize>) -> SlopeTable {
        let n = lut.texels.len();
        let base: Vec<f32> = lut
            .texels
            .windows(2)
            .map(|w| channels.clone().map(|c| (w[1][c] - w[0][c]).abs()).fold(0.0, f32::max) * n as f32)
            .collect();
        let segments = base.len();
        // Level j: the largest slope of the 2^j segments from each index.
        let mut levels = vec![base];
        while 1usize << levels.len() <= segments {
            let half = 1 << (levels.len() - 1);
            let prev = &levels[levels.len() - 1];
            let next: Vec<f32> = (0..prev.len() - half).map(|i| prev[i].max(prev[i + half])).collect();
            levels.push(next);
        }
        SlopeTable { levels, texels: n }
    }

    /// Largest slope where the LUT is sampled for scalars in [lo, hi].
    fn max_over(&self, lo: f64, hi: f64) -> f64 {
        let segments = self.levels[0].len();
        if segments == 0 {
            return 0.0;
        }
        let seg = |s: f64| ((s * self.texels as f64 - 0.5).floor().max(0.0) as usize).min(segments - 1);
        let (a, b) = (seg(lo), seg(hi));
        let level = (usize::BITS - 1 - (b - a + 1).leading_zeros()) as usize;
        let l = &self.levels[level];
        l[a].max(l[b + 1 - (1 << level)]) as f64
    }
}

impl CellBounds {
    fn new(scene: &Scene, lut: &TransferLut, weight_error: f64) -> CellBounds {
        let v = &scene.volume;
        let dims = v.dims.to_array().map(|n| n as usize);
        let [nx, ny, nz] = dims;
        let at = |x: usize, y: usize, z: usize| v.data.normalized(x + nx * (y + ny * z)) as f64;
        let sigma_slopes = SlopeTable::new(lut, 3..4);
        let rgb_slopes = SlopeTable::new(lut, 0..3);
        let count = nx * ny * nz;
        let (mut scalar, mut sigma, mut rgb) = (vec![0.0; count], vec![0.0; count], vec![0.0; count]);
        for z in 0..nz {
            for y in 0..ny {
                for x in 0..nx {
                    let hi = [(x + 1).min(nx - 1), (y + 1).min(ny - 1), (z + 1).min(nz - 1)];
                    let corners: [f64; 8] = std::array::from_fn(|i| {
                        at(
                            if i & 1 == 0 { x } else { hi[0] },
                            if i & 2 == 0 { y } else { hi[1] },
                            if i & 4 == 0 { z } else { hi[2] },
                        )
                    });
                    // Largest difference along each axis: corner pairs differing in that bit.
                    let mut d = [0.0f64; 3];
                    for (i, &c) in corners.iter().enumerate() {
                        for (a, da) in d.iter_mut().enumerate() {
                            if i & (1 << a) == 0 {
                                *da = da.max((corners[i | (1 << a)] - c).abs());
                            }
                        }
                    }
                    let ds = weight_error * (d[0] + d[1] + d[2]);
                    let lo = corners.iter().copied().fold(f64::INFINITY, f64::min) - ds;
                    let hi = corners.iter().copied().fold(f64::NEG_INFINITY, f64::max) + ds;
                    let i = x + nx * (y + ny * z);
                    scalar[i] = ds as f32;
                    sigma[i] = (ds * sigma_slopes.max_over(lo, hi)) as f32;
                    rgb[i] = (ds * rgb_slopes.max_over(lo, hi)) as f32;
                }
            }
        }
        CellBounds { dims, scalar, sigma, rgb }
    }

    /// (sigma error, colour error) at texture coordinates `uvw`: the largest
    /// over the cells within a hair of it (f32 and f64 positions may fall on
    /// either side of a texel centre).
    fn at(&self, uvw: DVec3) -> (f64, f64) {
        const HAIR: f64 = 1e-3;
        let mut range = [[0usize; 2]; 3];
        for (a, r) in range.iter_mut().enumerate() {
            let n = self.dims[a] as f64;
            let t = (uvw[a] * n - 0.5).clamp(0.0, n - 1.0);
            let cell = |t: f64| (t.floor().max(0.0) as usize).min(self.dims[a] - 1);
            *r = [cell(t - HAIR), cell(t + HAIR)];
        }
        let (mut sigma, mut rgb) = (0.0f64, 0.0f64);
        for z in range[2][0]..=range[2][1] {
            for y in range[1][0]..=range[1][1] {
                for x in range[0][0]..=range[0][1] {
                    let i = x + self.dims[0] * (y + self.dims[1] * z);
                    sigma = sigma.max(self.sigma[i] as f64);
                    rgb = rgb.max(self.rgb[i] as f64);
                }
            }
        }
        (sigma, rgb)
    }

    fn largest_scalar_error(&self) -> f64 {
        self.scalar.iter().copied().fold(0.0f32, f32::max) as f64
    }
}

/// A scene prepared for bounds at one size (like [`super::CpuRenderer`]).
pub struct FilterBound<'a> {
    scene: &'a Scene,
    lights: Vec<Light>,
    kind: CpuRenderKind,
    medium: Medium<'a>,
    cells: CellBounds,
    basis: RayBasis,
    width: u32,
    height: u32,
    step_voxels: f64,
    min_transmittance: f64,
}

/// One view sample of step 3.
struct SampleTerms {
    transmittance: f64,
    alpha: f64,
    depth_error: f64,
    source: f64,
    source_error: f64,
}

impl<'a> FilterBound<'a> {
    /// The bound for `scene` rendered as `kind` at `width` x `height` with
    /// `filter`; Phong is refused (outside the model).
    pub fn new(
        scene: &'a Scene,
        kind: CpuRenderKind,
        filter: VolumeFilter,
        width: u32,
        height: u32,
    ) -> Result<Self, CpuRenderError> {
        if kind == CpuRenderKind::Phong {
            return Err(CpuRenderError::Unsupported(
                "the 8-bit filter error model does not cover gradient (Phong) shading".into(),
            ));
        }
        let medium = Medium::new(&scene.volume, &scene.transfer);
        let cells = CellBounds::new(scene, medium.lut(), filter.weight_error());
        let (step_voxels, min_transmittance) = match kind {
            CpuRenderKind::Reference(_) => (scene.reference.step_voxels, scene.reference.min_transmittance as f64),
            _ => (scene.render.step_voxels, EARLY_TERMINATION_TRANSMITTANCE),
        };
        Ok(FilterBound {
            scene,
            lights: scene.rendered_lights(),
            kind,
            medium,
            cells,
            basis: scene.camera.basis(width, height),
            width,
            height,
            step_voxels: step_voxels as f64,
            min_transmittance,
        })
    }

    /// The largest error of one filtered scalar anywhere in the volume.
    pub fn largest_scalar_error(&self) -> f64 {
        self.cells.largest_scalar_error()
    }

    /// Per pixel (the same in every channel): the largest difference 8-bit
    /// weights may make.
    pub fn image(&self) -> LinearImage {
        let pixels = render_rows(self.width, self.height, |x, y| [self.pixel(x, y) as f32; 3]);
        LinearImage { width: self.width, height: self.height, pixels }
    }

    fn pixel(&self, x: u32, y: u32) -> f64 {
        let (nx, ny) = RayBasis::ndc(x, y, self.width, self.height);
        let (o, d) = self.basis.ray_f64(nx as f64, ny as f64);
        let (o, d) = (DVec3::from_array(o), DVec3::from_array(d));
        let background = self.scene.render.background.max_element() as f64;
        let Some((t0, t1)) = self.medium.intersect(o, d) else { return 0.0 };
        let phase = ray_start_phase(self.scene.render.jitter, x, y);
        let vl = self.medium.voxel_length();
        let steps = ((t1 - t0) / (self.step_voxels * vl)).ceil().max(1.0);
        let h = (t1 - t0) / steps;
        let hv = h / vl;
        let mut samples = Vec::with_capacity(steps as usize);
        let mut transmittance = 1.0;
        let mut terminated = false;
        for i in 0..steps as u64 {
            let p = o + d * (t0 + (i as f64 + phase) * h);
            let m = self.medium.at(p);
            let (sigma_error, rgb_error) = self.cells.at(self.medium.uvw(p));
            let alpha = 1.0 - (-m.sigma * hv).exp();
            let (source, source_error) = self.source(p, m.rgb.max_element(), rgb_error);
            samples.push(SampleTerms { transmittance, alpha, depth_error: sigma_error * hv, source, source_error });
            transmittance *= 1.0 - alpha;
            if transmittance < self.min_transmittance {
                terminated = true;
                break;
            }
        }
        // M_k: the largest perturbed source at or behind k, or the background.
        let mut behind = background;
        let mut largest = vec![0.0; samples.len()];
        for (k, s) in samples.iter().enumerate().rev() {
            behind = behind.max(s.source + s.source_error);
            largest[k] = behind;
        }
        let mut bound = 0.0;
        let mut depth_before = 0.0f64;
        for (s, m) in samples.iter().zip(&largest) {
            let t = s.transmittance * depth_before.exp();
            bound += t * (m * s.depth_error + (s.alpha + s.depth_error) * s.source_error);
            depth_before += s.depth_error;
        }
        if terminated && depth_before > 0.0 {
            bound += self.min_transmittance * depth_before.exp() * largest.first().copied().unwrap_or(background);
        }
        bound
    }

    /// (source, its largest error) of a sample of colour `rgb` (largest
    /// channel) and colour error `rgb_error` at `p`.
    fn source(&self, p: DVec3, rgb: f64, rgb_error: f64) -> (f64, f64) {
        let CpuRenderKind::Reference(model) = self.kind else { return (rgb, rgb_error) };
        let emission = self.scene.render.emission as f64;
        let mut light_in = emission;
        let mut light_error = 0.0;
        for light in &self.lights {
            let path = toward_light(light, p);
            let lit = (radiance(light) * falloff(light, &path, self.medium.voxel_length()) * cone(light, &path))
                .max_element();
            let shadow = self.shadow(light, p, path.toward, path.distance, model);
            light_in += lit * shadow.transmittance + shadow.emission;
            light_error += lit * shadow.transmittance * (shadow.depth_error.exp() - 1.0) + shadow.emission_error;
        }
        (rgb * light_in, rgb_error * (light_in + light_error) + rgb * light_error)
    }

    /// The shadow ray from `p` toward a light, marched as [`super::shadow`]
    /// marches it, with its optical-depth error and, for model (ii), the
    /// gathered emission and its error (bounded as [`Self::pixel`] bounds a pixel).
    fn shadow(&self, light: &Light, p: DVec3, toward: DVec3, light_distance: f64, model: OpticalModel) -> Shadow {
        let mut distance = self.medium.exit_distance(p, toward);
        if !matches!(light.kind, LightKind::Directional { .. }) {
            distance = distance.min(light_distance);
        }
        let chromatic = self.scene.reference.chromatic;
        let mut out = Shadow { transmittance: 1.0, depth_error: 0.0, emission: 0.0, emission_error: 0.0 };
        if distance <= 0.0 {
            return out;
        }
        let vl = self.medium.voxel_length();
        let steps = (distance / (self.scene.reference.shadow_step_voxels as f64 * vl)).ceil().max(1.0);
        let g = distance / steps;
        let gv = g / vl;
        let gather = matches!(model, OpticalModel::EmissiveScattering);
        let emission = self.scene.render.emission as f64;
        let (mut tau, mut rgb_max, mut rgb_error_max) = (0.0f64, 0.0f64, 0.0f64);
        for j in 0..steps as u64 {
            let q = p + toward * ((j as f64 + 0.5) * g);
            let m = self.medium.at(q);
            let (sigma_error, rgb_error) = self.cells.at(self.medium.uvw(q));
            if gather {
                out.emission += (-tau).exp() * (1.0 - (-m.sigma * gv).exp()) * emission * m.rgb.max_element();
                rgb_max = rgb_max.max(m.rgb.max_element());
                rgb_error_max = rgb_error_max.max(rgb_error);
            }
            tau += m.sigma * gv;
            // Coloured extinction's depth sigma (1 - rgb) moves by at most
            // d sigma + (sigma + d sigma) d rgb per channel.
            out.depth_error +=
                gv * if chromatic { sigma_error + (m.sigma + sigma_error) * rgb_error } else { sigma_error };
        }
        // Coloured transmittance is at most 1: the grey one would understate it.
        out.transmittance = if chromatic { 1.0 } else { (-tau).exp() };
        if gather {
            let e = out.depth_error;
            out.emission_error = emission * ((rgb_max + rgb_error_max) * e * e.exp() + rgb_error_max);
        }
        out
    }
}

struct Shadow {
    transmittance: f64,
    depth_error: f64,
    emission: f64,
    emission_error: f64,
}

/// The per-pixel bound image of `scene` rendered as `kind` with `filter`.
pub fn filter_bound_image(
    scene: &Scene,
    kind: CpuRenderKind,
    filter: VolumeFilter,
    width: u32,
    height: u32,
) -> Result<LinearImage, CpuRenderError> {
    Ok(FilterBound::new(scene, kind, filter, width, height)?.image())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::synthetic::three_spheres;

    #[test]
    fn exact_filtering_and_homogeneous_volumes_have_no_error() {
        let mut scene =
            crate::scene::default_scene::default_scene(&crate::scene::technique_settings::NoTechniqueTables, &[])
                .unwrap();
        scene.volume = three_spheres(16);
        let exact = FilterBound::new(&scene, CpuRenderKind::Dvr, VolumeFilter::Exact, 8, 8).unwrap();
        assert_eq!(exact.largest_scalar_error(), 0.0);
        assert_eq!(exact.image().max_value(), 0.0);
        let gpu = FilterBound::new(&scene, CpuRenderKind::Dvr, VolumeFilter::Gpu8Bit, 8, 8).unwrap();
        assert!(gpu.largest_scalar_error() > 0.0 && gpu.image().max_value() > 0.0);
        if let crate::scene::VoxelData::U8(v) = &mut scene.volume.data {
            v.fill(200);
        }
        let flat = FilterBound::new(&scene, CpuRenderKind::Dvr, VolumeFilter::Gpu8Bit, 8, 8).unwrap();
        assert_eq!(flat.image().max_value(), 0.0);
        assert!(FilterBound::new(&scene, CpuRenderKind::Phong, VolumeFilter::Gpu8Bit, 8, 8).is_err());
    }

    #[test]
    fn slope_table_answers_range_maxima() {
        let lut = TransferLut { texels: (0..10).map(|i| [0.0, 0.0, 0.0, (i * i) as f32]).collect() };
        let t = SlopeTable::new(&lut, 3..4);
        // Segment k's slope is (2k + 1) * 10; scalars 0.05..0.15 cover segments 0..1.
        assert_eq!(t.max_over(0.0, 0.15), 30.0);
        assert_eq!(t.max_over(0.0, 1.0), 170.0);
        assert_eq!(t.max_over(0.55, 0.56), 110.0);
    }
}
