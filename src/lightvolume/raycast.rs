//! The light volume's ray cast (glsl/lightvolume_raycast.comp): one dispatch,
//! front to back with the discretization of the baselines, the source term
//! lit by the illumination volume.

use super::illumination::IlluminationVolume;
use crate::render::{GpuScene, OutputImage, RenderError};
use crate::shaders;
use crate::vk::descriptors::{BindingKind, Resource};
use crate::vk::pipeline::{ComputePipeline, ComputePipelineDesc};
use crate::vk::{Buffer, Recorder};
use ash::vk;

const BINDINGS: [BindingKind; 5] = [
    BindingKind::UniformBuffer,
    BindingKind::SampledImage,
    BindingKind::StorageBuffer,
    BindingKind::StorageImage,
    BindingKind::StorageImage,
];

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
                spirv: shaders::LIGHTVOLUME_RAYCAST,
                bindings: &BINDINGS,
                push_constant_bytes: 0,
                specialization: &[],
                max_sets: 1,
            },
        )?;
        let set = pipeline.create_set(&[
            Resource::UniformBuffer(frame),
            Resource::SampledImage(&gpu.volume, &gpu.sampler),
            Resource::StorageBuffer(&gpu.lut),
            Resource::StorageImage(&illumination.image),
            Resource::StorageImage(&output.image),
        ])?;
        Ok(RayCast { pipeline, set })
    }

    pub fn record(&self, rec: &mut Recorder, width: u32, height: u32) {
        rec.bind(&self.pipeline, self.set);
        rec.dispatch(width.div_ceil(8), height.div_ceil(8), 1);
    }
}
