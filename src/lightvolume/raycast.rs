//! The light volume's ray cast (glsl/lightvolume_raycast.comp): one dispatch,
//! front to back with the discretization of the baselines, the source term
//! lit by the illumination volume.

use super::illumination::IlluminationVolume;
use crate::render::{GpuScene, OutputImage, RenderError};
use crate::shaders::lightvolume_raycast as shader;
use crate::vk::descriptors::Resource;
use crate::vk::pipeline::{ComputePipeline, ComputePipelineDesc};
use crate::vk::{Buffer, Recorder};
use ash::vk;

pub struct RayCast {
    pipeline: ComputePipeline,
    set: vk::DescriptorSet,
}

impl RayCast {
    pub fn new(
        gpu: &GpuScene,
        frame: &Buffer,
        illumination: &IlluminationVolume,
        output: &OutputImage,
    ) -> Result<RayCast, RenderError> {
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
        Ok(RayCast { pipeline, set })
    }

    pub fn record(&self, rec: &mut Recorder, width: u32, height: u32) {
        rec.bind(&self.pipeline, self.set);
        rec.dispatch(width.div_ceil(8), height.div_ceil(8), 1);
    }
}
