//! The light volume's ray cast (glsl/lightvolume_raycast.comp): one dispatch
//! per chunk of view samples ([`ViewChunks`]), front to back with the discretization of the baselines, the source term
//! lit by the illumination volume.

use super::illumination::IlluminationVolume;
use crate::render::view_chunks::ChunkSync;
use crate::render::view_chunks::ViewChunks;
use crate::render::{GpuScene, OutputImage, RenderError, ResourceNeed};
use crate::scene::Scene;
use crate::shaders::lightvolume_raycast as shader;
use crate::vk::descriptors::Resource;
use crate::vk::pipeline::{ComputePipeline, ComputePipelineDesc};
use crate::vk::{Buffer, Image, Recorder};
use ash::vk;
use std::sync::Arc;

pub struct RayCast {
    pipeline: ComputePipeline,
    /// Set 0 writes the output, set 1 the chunk state image ([`ViewChunks::set_of`]).
    sets: [vk::DescriptorSet; 2],
    state: Arc<Image>,
    chunks: ViewChunks,
}

/// Loop iterations of one view sample: itself and the two 8-corner loops of
/// the trilinear illumination lookup, each counted by llvmpipe as one more
/// than it runs.
const ITERATIONS_PER_SAMPLE: u64 = 1 + 2 * 9;

impl RayCast {
    pub fn new(
        gpu: &GpuScene,
        frame: &Buffer,
        illumination: &IlluminationVolume,
        output: &OutputImage,
    ) -> Result<RayCast, RenderError> {
        let chunks = ViewChunks::for_render(gpu.scene, "lightvolume", ITERATIONS_PER_SAMPLE)?;
        let mut pipeline = ComputePipeline::new(
            gpu.ctx,
            &ComputePipelineDesc {
                name: "lightvolume_raycast",
                shader: &shader::INTERFACE,
                specialization: &[],
                max_sets: 2,
            },
        )?;
        let state = chunks.state_image(gpu, "lightvolume view chunk state", output.width, output.height)?;
        let mut sets = [vk::DescriptorSet::null(); 2];
        for (i, (write, read)) in [(&output.image, &*state), (&*state, &output.image)].into_iter().enumerate() {
            sets[i] = pipeline.create_set(&[
                (shader::FRAME_BUFFER, Resource::StorageBuffer(frame)),
                (shader::VOLUME_TEX, Resource::SampledImage(&gpu.volume, &gpu.sampler)),
                (shader::TRANSFER_LUT, Resource::StorageBuffer(&gpu.lut)),
                (shader::ILLUMINATION, Resource::StorageImage(&illumination.image)),
                (shader::OUT_IMAGE, Resource::StorageImage(write)),
                (shader::STATE_IN, Resource::StorageImage(read)),
            ])?;
        }
        Ok(RayCast { pipeline, sets, state, chunks })
    }

    /// What [`RayCast::new`] allocates beside the output.
    pub fn resources(scene: &Scene, width: u32, height: u32) -> Vec<ResourceNeed> {
        match ViewChunks::for_render(scene, "lightvolume", ITERATIONS_PER_SAMPLE) {
            Ok(chunks) => vec![chunks.state_resource("lightvolume view chunk state", width, height)],
            Err(_) => Vec::new(),
        }
    }

    /// Prepares the state image and records the chunks (the output prepared
    /// by the caller); `sync` leaves the barrier out only to prove validation
    /// reports it.
    pub fn record(&self, rec: &mut Recorder, width: u32, height: u32, sync: ChunkSync) {
        rec.discard_for_compute("view_chunk_state_discard_to_compute_access", &[&self.state]);
        self.chunks.record(rec, &self.pipeline, self.sets, (width, height), sync);
    }
}
