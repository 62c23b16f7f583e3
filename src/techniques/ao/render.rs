//! The frame of technique `ao` (glsl/ao_render.comp): the cluster ids and the
//! codebook uploaded once per renderer, the environment lookup recomputed on
//! the GPU per transfer-function change ([`GpuEnvironment`]), and the ray cast
//! that shades with it, in the mode `ao.mode` names. The same ray cast renders
//! a lookup per voxel (the unclustered histograms, the ground truth).

use ash::vk;
use bytemuck::{Pod, Zeroable};

use super::environment::{self, hemisphere_mass, GlowMapping, GpuEnvironment};
use super::render_settings::AoMode;
use super::settings::AoSettings;
use super::AoPreprocessed;
use crate::render::frame_params::{frame_params, FrameParams, MarchSteps};
use crate::render::raycast::ChunkedMarch;
use crate::render::recorded_frame::{render_recorded, RecordedFrame};
use crate::render::view_chunks::ChunkSync;
use crate::render::view_chunks::ViewChunks;
use crate::render::{FrameResult, GpuScene, RenderError, ResourceNeed};
use crate::scene::Scene;
use crate::shaders::ao_render as shader;
use crate::vk::descriptors::Resource;
use crate::vk::pipeline::{ComputePipeline, ComputePipelineDesc};
use crate::vk::staging::{device_buffer_with_data, Uploads};
use crate::vk::{Buffer, Profiler, Recorder};

/// The pass's name: debug label, profiler scope and technique name.
pub const PASS: &str = "ao";

/// `AoParams` of glsl/ao_render.comp (a std140 storage buffer).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct AoParams {
    pub entries: u32,
    pub isovalue: f32,
    pub phase_g: f32,
    pub glow_max: f32,
}

crate::assert_gpu_layout!(AoParams, shader::layout::AO_PARAMS, [entries, isovalue, phase_g, glow_max]);

/// Where the shading's environment comes from.
pub enum Lookup {
    /// Equations 4-5 per codebook cluster, on the GPU, indexed by the voxels'
    /// cluster ids.
    Clustered { ids: Buffer, environment: Box<GpuEnvironment> },
    /// `(E_env, O_env)` per voxel and hemisphere (entry 2 v + h), then the glow
    /// block; computed elsewhere (the unclustered histograms, the ground truth).
    PerVoxel { env: Buffer, placeholder_ids: Buffer },
}

/// What one scene's `ao` frames keep between frames.
pub struct AoRenderer {
    pub mode: AoMode,
    lookup: Lookup,
    params: AoParams,
}

impl AoRenderer {
    /// Uploads `pre`'s cluster ids and codebook for `gpu` (the renderer is
    /// bound to this scene's LUT and volume). The lookup is computed by
    /// [`AoRenderer::update_environment`].
    pub fn new(gpu: &GpuScene, pre: &AoPreprocessed, settings: &AoSettings) -> Result<AoRenderer, RenderError> {
        let dims = gpu.scene.volume.dims;
        if pre.dims != dims || pre.cluster_ids.len() != gpu.scene.volume.voxel_count() {
            return Err(RenderError::Invalid(format!(
                "ao: preprocessing of a {} volume for a {dims} volume",
                pre.dims
            )));
        }
        let ids =
            device_buffer_with_data(gpu.ctx, "ao cluster ids", &pre.cluster_ids, vk::BufferUsageFlags::STORAGE_BUFFER)?;
        let environment = GpuEnvironment::new(
            gpu.ctx,
            &pre.codebook,
            (pre.clusters, pre.bins),
            &gpu.lut,
            hemisphere_mass(&gpu.scene.volume, settings.radius),
            GlowMapping::from_settings(settings),
        )?;
        Ok(AoRenderer {
            mode: settings.mode,
            lookup: Lookup::Clustered { ids, environment: Box::new(environment) },
            params: params(settings, pre.clusters),
        })
    }

    /// A renderer of a lookup per voxel and hemisphere: `env` holds
    /// `2 * voxels` entries, then (glow mode) as many glow entries.
    pub fn per_voxel(gpu: &GpuScene, env: &[[f32; 4]], settings: &AoSettings) -> Result<AoRenderer, RenderError> {
        let entries = 2 * gpu.scene.volume.voxel_count();
        let expected = entries * if settings.mode.has_glow() { 2 } else { 1 };
        if env.len() != expected {
            return Err(RenderError::Invalid(format!("ao: {} lookup entries for {expected}", env.len())));
        }
        let usage = vk::BufferUsageFlags::STORAGE_BUFFER;
        let mut uploads = Uploads::new(gpu.ctx);
        let env = uploads.buffer("ao environment per voxel", env, usage)?;
        let placeholder_ids = uploads.buffer("ao cluster ids placeholder", &[0u32], usage)?;
        uploads.finish()?;
        Ok(AoRenderer {
            mode: settings.mode,
            lookup: Lookup::PerVoxel { env, placeholder_ids },
            params: params(settings, entries as u32),
        })
    }

    /// Recomputes the lookup from the scene's transfer LUT as it is now (after
    /// a transfer-function change): no preprocessing, one dispatch.
    pub fn update_environment(&self, gpu: &GpuScene, profiler: &mut Profiler) -> Result<(), RenderError> {
        match &self.lookup {
            Lookup::Clustered { environment, .. } => environment.update(gpu.ctx, profiler),
            Lookup::PerVoxel { .. } => Ok(()),
        }
    }

    /// The clustered lookup as last computed (`None` for a per-voxel one).
    pub fn environment(&self) -> Option<&GpuEnvironment> {
        match &self.lookup {
            Lookup::Clustered { environment, .. } => Some(environment),
            Lookup::PerVoxel { .. } => None,
        }
    }

    /// Renders one frame of `gpu` (the scene it was created for): [`Self::record`]
    /// and the read-back.
    pub fn frame(&self, gpu: &GpuScene, size: (u32, u32), profiler: &mut Profiler) -> Result<FrameResult, RenderError> {
        render_recorded(gpu, |rec| self.record(gpu, size, rec, profiler))
    }

    /// Records one frame into `rec` (see [`RecordedFrame`]); the renderer's
    /// cluster ids, codebook and lookup are only read, and must outlive it.
    pub fn record(
        &self,
        gpu: &GpuScene,
        (width, height): (u32, u32),
        rec: &mut Recorder,
        profiler: &mut Profiler,
    ) -> Result<RecordedFrame, RenderError> {
        let ctx = gpu.ctx;
        let scene = gpu.scene;
        let chunks = ViewChunks::for_render(scene, PASS, iterations_per_sample(scene))?;
        let frame = frame_params(scene, width, height, gpu.lut_size, MarchSteps::render(scene));
        let frame = Buffer::with_data(ctx, "frame params", &[frame], vk::BufferUsageFlags::STORAGE_BUFFER)?;
        let ao = Buffer::with_data(ctx, "ao params", &[self.params], vk::BufferUsageFlags::STORAGE_BUFFER)?;
        let (ids, env, source) = match &self.lookup {
            Lookup::Clustered { ids, environment } => (ids, &environment.env, 0),
            Lookup::PerVoxel { env, placeholder_ids } => (placeholder_ids, env, 1),
        };
        let pipeline = ComputePipeline::new(
            ctx,
            &ComputePipelineDesc {
                name: PASS,
                shader: &shader::INTERFACE,
                specialization: &[(0, self.mode.shader_value()), (1, source)],
                max_sets: 2,
            },
        )?;
        let shared = [
            (shader::FRAME_BUFFER, Resource::StorageBuffer(&frame)),
            (shader::VOLUME_TEX, Resource::SampledImage(&gpu.volume, &gpu.sampler)),
            (shader::TRANSFER_LUT, Resource::StorageBuffer(&gpu.lut)),
            (shader::LIGHTS, Resource::StorageBuffer(&gpu.lights)),
            (shader::CLUSTER_IDS, Resource::StorageBuffer(ids)),
            (shader::ENVIRONMENT, Resource::StorageBuffer(env)),
            (shader::AO_BUFFER, Resource::StorageBuffer(&ao)),
        ];
        let march = ChunkedMarch { name: PASS, chunks, size: (width, height), sync: ChunkSync::Barrier };
        let mut recorded =
            march.record(gpu, pipeline, &shared, [shader::OUT_IMAGE, shader::STATE_IN], rec, profiler)?;
        recorded.keep_alive.push(Box::new(frame));
        recorded.keep_alive.push(Box::new(ao));
        Ok(recorded)
    }
}

fn params(settings: &AoSettings, entries: u32) -> AoParams {
    AoParams { entries, isovalue: settings.isovalue, phase_g: settings.phase_g, glow_max: settings.glow_max }
}

/// Loop iterations one view sample costs: the sample and the loop over the
/// lights (one more than it runs on llvmpipe, as for Blinn-Phong).
fn iterations_per_sample(scene: &Scene) -> u64 {
    1 + scene.lights.len() as u64 + 1
}

/// What a clustered frame allocates: the cluster ids, the codebook, the lookup
/// (with the glow block only in glow mode), the parameters, the output and
/// the view-chunk state.
pub fn resources(scene: &Scene, settings: &AoSettings, width: u32, height: u32) -> Vec<ResourceNeed> {
    let bins = settings.bins() as u32;
    let mut needs = vec![ResourceNeed::of::<u32>("ao cluster ids", scene.volume.voxel_count())];
    needs.extend(environment::resources(settings.clusters, bins, settings.mode));
    needs.extend([
        ResourceNeed::of::<FrameParams>("frame params", 1),
        ResourceNeed::of::<AoParams>("ao params", 1),
        ResourceNeed::output_image("ao output", width, height),
    ]);
    if let Ok(chunks) = ViewChunks::for_render(scene, PASS, iterations_per_sample(scene)) {
        needs.push(chunks.state_resource("ao view chunk state", width, height));
    }
    needs
}
