//! Merged sweeps' colour (`ipsvi.merge_sweeps`): each sweep accumulates into
//! its own rows, and `ipsvi_sweep_sum` adds them to the output.

use crate::render::{GpuScene, OutputImage, RenderError};
use crate::shaders::ipsvi_sweep_sum;
use crate::vk::descriptors::Resource;
use crate::vk::pipeline::{ComputePipeline, ComputePipelineDesc};
use crate::vk::Image;
use ash::vk;
use std::sync::Arc;

/// Merged sweeps: each sweep's colour in its own rows (sweeps of one step may
/// shade the same pixel in one dispatch), added to the output by `ipsvi_sweep_sum`.
pub struct MergedOutput {
    pub slots: u32,
    pub accumulation: Arc<Image>,
    pub sum: ComputePipeline,
    pub sum_set: vk::DescriptorSet,
}

impl MergedOutput {
    pub fn new(gpu: &GpuScene, output: &OutputImage, slots: u32) -> Result<MergedOutput, RenderError> {
        let accumulation = gpu.frame_images.storage_2d(
            gpu.ctx,
            "ipsvi sweep accumulation",
            vk::Format::R32G32B32A32_SFLOAT,
            (output.width, output.height * slots),
            vk::ImageUsageFlags::TRANSFER_DST,
        )?;
        let mut sum = ComputePipeline::new(
            gpu.ctx,
            &ComputePipelineDesc {
                name: "ipsvi_sweep_sum",
                shader: &ipsvi_sweep_sum::INTERFACE,
                specialization: &[],
                max_sets: 1,
            },
        )?;
        let sum_set = sum.create_set(&[
            (ipsvi_sweep_sum::ACCUMULATION, Resource::StorageImage(&accumulation)),
            (ipsvi_sweep_sum::OUT_IMAGE, Resource::StorageImage(&output.image)),
        ])?;
        Ok(MergedOutput { slots, accumulation, sum, sum_set })
    }
}
