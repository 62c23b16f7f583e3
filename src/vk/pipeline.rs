//! Compute pipelines from embedded SPIR-V, with specialization constants (shader
//! variants) and push constants, and their one descriptor-set layout.

use super::context::Context;
use super::descriptors::{BindingKind, DescriptorAllocator};
use super::error::{VkError, VkResultExt};
use ash::vk;
use std::io::Cursor;
use std::sync::Arc;

pub struct ComputePipelineDesc<'a> {
    /// Debug name, also the pass name by convention.
    pub name: &'a str,
    pub spirv: &'a [u8],
    /// Bindings of descriptor set 0, in binding order.
    pub bindings: &'a [BindingKind],
    pub push_constant_bytes: u32,
    /// (constant_id, 32-bit value): booleans as 0/1, floats via `f32::to_bits`.
    pub specialization: &'a [(u32, u32)],
    /// How many descriptor sets this pipeline will need.
    pub max_sets: u32,
}

pub struct ComputePipeline {
    pub raw: vk::Pipeline,
    pub layout: vk::PipelineLayout,
    pub set_layout: vk::DescriptorSetLayout,
    pub bindings: Vec<BindingKind>,
    pub push_constant_bytes: u32,
    pub descriptors: DescriptorAllocator,
    device: ash::Device,
    _keep_alive: Arc<super::memory::GpuMemory>,
}

impl ComputePipeline {
    pub fn new(ctx: &Context, desc: &ComputePipelineDesc) -> Result<ComputePipeline, VkError> {
        let device = &ctx.device;
        let words = ash::util::read_spv(&mut Cursor::new(desc.spirv))
            .map_err(|_| VkError::Call { call: "read_spv", result: vk::Result::ERROR_INVALID_SHADER_NV })?;
        let module_info = vk::ShaderModuleCreateInfo::default().code(&words);
        // SAFETY: words is valid SPIR-V compiled by build.rs.
        let module = unsafe { device.create_shader_module(&module_info, None) }.call("vkCreateShaderModule")?;

        let layout_bindings: Vec<vk::DescriptorSetLayoutBinding> = desc
            .bindings
            .iter()
            .enumerate()
            .map(|(i, k)| {
                vk::DescriptorSetLayoutBinding::default()
                    .binding(i as u32)
                    .descriptor_type(k.vk_type())
                    .descriptor_count(1)
                    .stage_flags(vk::ShaderStageFlags::COMPUTE)
            })
            .collect();
        let set_layout_info = vk::DescriptorSetLayoutCreateInfo::default().bindings(&layout_bindings);
        // SAFETY: valid device and create info.
        let set_layout = unsafe { device.create_descriptor_set_layout(&set_layout_info, None) }
            .call("vkCreateDescriptorSetLayout")?;
        let ranges = [vk::PushConstantRange::default()
            .stage_flags(vk::ShaderStageFlags::COMPUTE)
            .offset(0)
            .size(desc.push_constant_bytes.max(4))];
        let set_layouts = [set_layout];
        let mut layout_info = vk::PipelineLayoutCreateInfo::default().set_layouts(&set_layouts);
        if desc.push_constant_bytes > 0 {
            layout_info = layout_info.push_constant_ranges(&ranges);
        }
        // SAFETY: valid device and create info.
        let layout = unsafe { device.create_pipeline_layout(&layout_info, None) }.call("vkCreatePipelineLayout")?;

        let entries: Vec<vk::SpecializationMapEntry> = desc
            .specialization
            .iter()
            .enumerate()
            .map(|(i, (id, _))| vk::SpecializationMapEntry { constant_id: *id, offset: (i * 4) as u32, size: 4 })
            .collect();
        let data: Vec<u8> = desc.specialization.iter().flat_map(|(_, v)| v.to_ne_bytes()).collect();
        let spec = vk::SpecializationInfo::default().map_entries(&entries).data(&data);
        let stage = vk::PipelineShaderStageCreateInfo::default()
            .stage(vk::ShaderStageFlags::COMPUTE)
            .module(module)
            .name(c"main")
            .specialization_info(&spec);
        let info = [vk::ComputePipelineCreateInfo::default().stage(stage).layout(layout)];
        // SAFETY: module and layout are valid; the shader matches the layout.
        let created = unsafe { device.create_compute_pipelines(vk::PipelineCache::null(), &info, None) };
        // SAFETY: the module is no longer needed once pipelines are created.
        unsafe { device.destroy_shader_module(module, None) };
        let raw = created.map_err(|(_, r)| VkError::Call { call: "vkCreateComputePipelines", result: r })?[0];
        ctx.set_name(raw, desc.name);
        let descriptors = DescriptorAllocator::new(ctx, desc.bindings, desc.max_sets.max(1))?;
        Ok(ComputePipeline {
            raw,
            layout,
            set_layout,
            bindings: desc.bindings.to_vec(),
            push_constant_bytes: desc.push_constant_bytes,
            descriptors,
            device: device.clone(),
            _keep_alive: ctx.memory.clone(),
        })
    }

    /// Allocates a descriptor set of this pipeline's layout and writes `resources`.
    pub fn create_set(&mut self, resources: &[super::descriptors::Resource]) -> Result<vk::DescriptorSet, VkError> {
        self.descriptors.create_set(self.set_layout, &self.bindings, resources)
    }
}

impl Drop for ComputePipeline {
    fn drop(&mut self) {
        // SAFETY: pipelines are dropped after the GPU work using them completed.
        unsafe {
            self.device.destroy_pipeline(self.raw, None);
            self.device.destroy_pipeline_layout(self.layout, None);
            self.device.destroy_descriptor_set_layout(self.set_layout, None);
        }
    }
}

/// The two builds of a ping-pong shader (build.rs `BINDING_VARIANTS`): index 0
/// reads side a of its pair and writes b, index 1 the opposite. Their layouts are
/// identical, so one descriptor set (allocated from index 0) serves both and a
/// block switches sides by binding the other pipeline. `desc.spirv` is unused.
pub fn parity_pair(
    ctx: &Context,
    desc: &ComputePipelineDesc,
    read_a: &[u8],
    read_b: &[u8],
) -> Result<[ComputePipeline; 2], VkError> {
    Ok([
        ComputePipeline::new(ctx, &ComputePipelineDesc { spirv: read_a, ..*desc })?,
        ComputePipeline::new(ctx, &ComputePipelineDesc { spirv: read_b, ..*desc })?,
    ])
}
