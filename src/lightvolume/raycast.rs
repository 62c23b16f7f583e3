//! The light volume's ray cast (glsl/lightvolume_raycast.comp): one dispatch
//! per chunk of view samples ([`ViewChunks`]), front to back with the discretization of the baselines, the source term
//! lit by the illumination volume.

use super::illumination::IlluminationVolume;
use crate::render::view_chunks::ViewChunks;
use crate::render::{GpuScene, OutputImage, RenderError};
use crate::shaders::lightvolume_raycast as shader;
use crate::vk::descriptors::Resource;
use crate::vk::pipeline::{ComputePipeline, ComputePipelineDesc};
use crate::vk::{Buffer, Recorder};
use ash::vk;

pub struct RayCast {
    pipeline: ComputePipeline,
    set: vk::DescriptorSet,
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
                max_sets: 1,
            },
        )?;
        let set = pipeline.create_set(&[
            (shader::FRAME, Resource::UniformBuffer(frame)),
            (shader::VOLUME_TEX, Resource::SampledImage(&gpu.volume, &gpu.sampler)),
            (shader::TRANSFER_LUT, Resource::StorageBuffer(&gpu.lut)),
            (shader::ILLUMINATION, Resource::StorageImage(&illumination.image)),
            (shader::OUT_IMAGE, Resource::StorageImage(&output.image)),
        ])?;
        Ok(RayCast { pipeline, set, chunks })
    }

    pub fn record(&self, rec: &mut Recorder, width: u32, height: u32) {
        rec.bind(&self.pipeline, self.set);
        self.chunks.record(rec, &self.pipeline, width, height);
    }
}
