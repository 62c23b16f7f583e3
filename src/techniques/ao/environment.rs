//! Environment colour E_env and occlusion O_env of every codebook cluster
//! (section 4.1, equations 4-5), recomputed on the GPU from the transfer
//! function whenever it changes: the TF at each bin (glsl/ao_env_bins.comp),
//! then each cluster's histogram weighted with it (glsl/ao_env.comp); the
//! codebook is uploaded once. [`cpu_environment`] is the same sum on the CPU, the reference of the
//! GPU pass and the lookup of the unclustered histograms.
//!
//! Normalization: the paper divides by 2/3 pi r^3, the volume of the
//! hemisphere; our histograms are weighted by 1/d^2 and divided by N_r, so a
//! fully occupied hemisphere sums to [`SphereStencil::full_hemisphere_mass`]
//! (about 3 / (2 r^2) times less than 2/3 pi r^3 would need), and dividing by
//! 2/3 pi r^3 would leave O_env far below 1 even fully enclosed. We divide by
//! the full-hemisphere mass, so O_env = 1 exactly for an opaque, fully occupied
//! hemisphere and 0 for empty surroundings (docs/ao.md).

use ash::vk;
use bytemuck::{Pod, Zeroable};
use gpu_allocator::MemoryLocation;

use super::histogram::SphereStencil;
use super::render_settings::AoMode;
use super::settings::AoSettings;
use crate::render::{RenderError, ResourceNeed};
use crate::scene::{TransferLut, Volume};
use crate::shaders::ao_env as shader;
use crate::shaders::ao_env_bins as bins_shader;
use crate::vk::barriers::{Access, Barrier};
use crate::vk::commands::submit_and_wait;
use crate::vk::descriptors::Resource;
use crate::vk::pipeline::{ComputePipeline, ComputePipelineDesc};
use crate::vk::staging::{device_buffer_with_data, read_device_buffer};
use crate::vk::{Buffer, Context, Profiler};

/// The update's name: debug label and profiler scope of both passes.
pub const PASS: &str = "ao_environment";
/// Its two passes (per-dispatch detail scopes).
pub const BINS_PASS: &str = "ao_environment_bins";
pub const CLUSTERS_PASS: &str = "ao_environment_clusters";

/// The push constants of glsl/ao_env_bins.comp.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct BinParams {
    pub bins: u32,
    pub lut_size: f32,
}

crate::assert_gpu_layout!(BinParams, bins_shader::layout::BIN_PARAMS, [bins, lut_size]);

/// The push constants of glsl/ao_env.comp.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct EnvParams {
    pub clusters: u32,
    pub bins: u32,
    /// 1 / [`SphereStencil::full_hemisphere_mass`].
    pub inv_mass: f32,
    pub glow_low: f32,
    pub glow_high: f32,
    pub pad0: u32,
    pub pad1: u32,
    pub pad2: u32,
}

crate::assert_gpu_layout!(
    EnvParams,
    shader::layout::ENV_PARAMS,
    [clusters, bins, inv_mass, glow_low, glow_high, pad0, pad1, pad2]
);

/// h(j) of section 4.4: h_max (`glow_max`, applied by the renderer) for
/// intensities in `glow_range`, else 1. The lookup's glow block needs only
/// which intensities glow.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GlowMapping {
    pub range: [f32; 2],
}

impl GlowMapping {
    pub fn from_settings(s: &AoSettings) -> Option<GlowMapping> {
        s.mode.has_glow().then_some(GlowMapping { range: s.glow_range })
    }

    /// Whether intensity `s` glows: (h(s) - 1) / (h_max - 1), 1 or 0.
    pub fn glows(&self, s: f32) -> bool {
        s >= self.range[0] && s <= self.range[1]
    }
}

/// The normalization of equations 4-5: what a fully occupied hemisphere's
/// histogram sums to.
pub fn hemisphere_mass(volume: &Volume, radius: u32) -> f64 {
    SphereStencil::new(radius, volume.spacing).full_hemisphere_mass()
}

/// Centre intensity of bin `j` of `bins` (docs/ao.md, "Bins").
pub fn bin_intensity(j: usize, bins: usize) -> f32 {
    (j as f32 + 0.5) / bins as f32
}

/// Equations 4-5 for `histograms` (`count x bins`, each a normalized local
/// histogram): `(E_env rgb, O_env)` per histogram, then with `glow` one more
/// block of `(glow colour, glow intensity)`, the same sums over the glowing
/// intensities only (glsl/ao_env.comp). In f64, the GPU's reference.
pub fn cpu_environment(
    histograms: &[f32],
    bins: usize,
    lut: &TransferLut,
    mass: f64,
    glow: Option<GlowMapping>,
) -> Vec<[f32; 4]> {
    let count = histograms.len() / bins;
    let per_bin: Vec<([f64; 4], f64)> = (0..bins)
        .map(|j| {
            let s = bin_intensity(j, bins);
            let t = lut.sample(s as f64);
            let a = 1.0 - (-t[3]).exp();
            ([t[0], t[1], t[2], a], glow.map_or(0.0, |g| g.glows(s) as u32 as f64))
        })
        .collect();
    let mut env = vec![[0f32; 4]; count * if glow.is_some() { 2 } else { 1 }];
    for c in 0..count {
        let h = &histograms[c * bins..(c + 1) * bins];
        let (mut e, mut g) = ([0f64; 4], [0f64; 4]);
        for (j, &lh) in h.iter().enumerate() {
            let ([r, gr, b, a], hj) = per_bin[j];
            let w = a * lh as f64;
            for (k, v) in [r, gr, b, 1.0].into_iter().enumerate() {
                e[k] += w * v;
                g[k] += hj * w * v;
            }
        }
        env[c] = e.map(|v| (v / mass) as f32);
        if glow.is_some() {
            env[count + c] = g.map(|v| (v / mass) as f32);
        }
    }
    env
}

/// The codebook on the GPU (uploaded once) and the lookup computed from it.
pub struct GpuEnvironment {
    pub clusters: u32,
    pub bins: u32,
    codebook: Buffer,
    /// `(tau_alpha tau_rgb, tau_alpha)` per bin; only the shaders touch it
    /// (bound in both passes' sets), it lives as long as they do.
    _bin_weights: Buffer,
    /// `(E_env, O_env)` per cluster, then the glow block in glow mode.
    pub env: Buffer,
    bins_pipeline: ComputePipeline,
    bins_set: vk::DescriptorSet,
    bin_params: BinParams,
    pipeline: ComputePipeline,
    set: vk::DescriptorSet,
    params: EnvParams,
}

impl GpuEnvironment {
    /// Uploads `codebook` (`clusters x bins`) and builds the pass; nothing is
    /// computed until [`GpuEnvironment::update`].
    pub fn new(
        ctx: &Context,
        codebook: &[f32],
        (clusters, bins): (u32, u32),
        lut: &Buffer,
        mass: f64,
        glow: Option<GlowMapping>,
    ) -> Result<GpuEnvironment, RenderError> {
        let codebook = device_buffer_with_data(ctx, "ao codebook", codebook, vk::BufferUsageFlags::STORAGE_BUFFER)?;
        let entries = env_entries(clusters, glow.is_some());
        // Device-local: every frame's shader reads it; tests read it back by a copy.
        let env = Buffer::new(
            ctx,
            "ao environment",
            entries * 16,
            vk::BufferUsageFlags::STORAGE_BUFFER | vk::BufferUsageFlags::TRANSFER_SRC,
            MemoryLocation::GpuOnly,
        )?;
        let bin_weights = Buffer::new(
            ctx,
            "ao bin weights",
            bins as u64 * 16,
            vk::BufferUsageFlags::STORAGE_BUFFER,
            MemoryLocation::GpuOnly,
        )?;
        let mut bins_pipeline = ComputePipeline::new(
            ctx,
            &ComputePipelineDesc { name: BINS_PASS, shader: &bins_shader::INTERFACE, specialization: &[], max_sets: 1 },
        )?;
        let bins_set = bins_pipeline.create_set(&[
            (bins_shader::BIN_WEIGHTS, Resource::StorageBuffer(&bin_weights)),
            (bins_shader::TRANSFER_LUT, Resource::StorageBuffer(lut)),
        ])?;
        let bin_params = BinParams { bins, lut_size: (lut.size / 16) as f32 };
        let mut pipeline = ComputePipeline::new(
            ctx,
            &ComputePipelineDesc {
                name: CLUSTERS_PASS,
                shader: &shader::INTERFACE,
                specialization: &[(0, glow.is_some() as u32)],
                max_sets: 1,
            },
        )?;
        let set = pipeline.create_set(&[
            (shader::CODEBOOK, Resource::StorageBuffer(&codebook)),
            (shader::ENVIRONMENT, Resource::StorageBuffer(&env)),
            (shader::BIN_WEIGHTS, Resource::StorageBuffer(&bin_weights)),
        ])?;
        // No glow: an empty band (the shader does not read it then).
        let g = glow.unwrap_or(GlowMapping { range: [1.0, 0.0] });
        let params = EnvParams {
            clusters,
            bins,
            inv_mass: (1.0 / mass) as f32,
            glow_low: g.range[0],
            glow_high: g.range[1],
            pad0: 0,
            pad1: 0,
            pad2: 0,
        };
        Ok(GpuEnvironment {
            clusters,
            bins,
            codebook,
            _bin_weights: bin_weights,
            env,
            bins_pipeline,
            bins_set,
            bin_params,
            pipeline,
            set,
            params,
        })
    }

    /// Recomputes the lookup from the transfer LUT bound at creation (call it
    /// after the LUT changed): two dispatches in their own submission,
    /// followed by the barriers that make the lookup visible to the frame's
    /// shaders and to the host.
    pub fn update(&self, ctx: &Context, profiler: &mut Profiler) -> Result<(), RenderError> {
        submit_and_wait(ctx, "ao_environment_update", |rec| {
            let scope = profiler.begin(rec, PASS)?;
            let detail = profiler.begin_detail(rec, BINS_PASS)?;
            rec.bind(&self.bins_pipeline, self.bins_set);
            rec.push(&self.bins_pipeline, &self.bin_params);
            rec.dispatch(self.bins.div_ceil(64), 1, 1);
            profiler.end(rec, detail)?;
            // The clusters' pass weights every histogram with the bins' TF.
            rec.barrier(&Barrier::memory(
                "ao_bin_weights_write_to_environment_read",
                Access::COMPUTE_WRITE,
                Access::COMPUTE_READ,
            ));
            let detail = profiler.begin_detail(rec, CLUSTERS_PASS)?;
            rec.bind(&self.pipeline, self.set);
            rec.push(&self.pipeline, &self.params);
            rec.dispatch(self.clusters.div_ceil(64), 1, 1);
            profiler.end(rec, detail)?;
            profiler.end(rec, scope)?;
            // The frames that follow read the lookup in their shaders (tests
            // read it back through `read`, which orders its own copy).
            rec.barrier(&Barrier::memory(
                "ao_environment_write_to_render_read",
                Access::COMPUTE_WRITE,
                Access::COMPUTE_READ,
            ));
            Ok(())
        })?;
        Ok(())
    }

    /// The lookup as last computed (a copy through a read-back buffer).
    pub fn read(&self, ctx: &Context) -> Result<Vec<[f32; 4]>, RenderError> {
        Ok(read_device_buffer(ctx, &self.env, (self.env.size / 16) as usize)?)
    }

    pub fn codebook_bytes(&self) -> u64 {
        self.codebook.size
    }
}

/// vec4 entries of the lookup.
fn env_entries(clusters: u32, glow: bool) -> u64 {
    clusters as u64 * if glow { 2 } else { 1 }
}

/// What [`GpuEnvironment::new`] allocates.
pub fn resources(clusters: u32, bins: u32, mode: AoMode) -> Vec<ResourceNeed> {
    vec![
        ResourceNeed::of::<f32>("ao codebook", clusters as usize * bins as usize),
        ResourceNeed::of::<[f32; 4]>("ao bin weights", bins as usize),
        ResourceNeed::buffer("ao environment", env_entries(clusters, mode.has_glow()) * 16),
    ]
}
