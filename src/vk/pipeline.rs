//! Compute pipelines from embedded SPIR-V, with specialization constants (shader
//! variants) and push constants, and their descriptor-set layouts: set 0, and
//! for a ping-pong shader a small set 1 of the pair's images, bound per block
//! ({in = a, out = b} or {in = b, out = a}). Each is
//! compiled once per context ([`super::pipeline_store`]) through the context's
//! pipeline cache ([`super::pipeline_cache`]); each ComputePipeline has its own
//! descriptor pool.

use super::context::Context;
use super::descriptors::{DescriptorAllocator, Resource};
use super::error::{VkError, VkResultExt};
use super::interface::{Binding, ShaderInterface};
use super::limits::{Limit, LimitExceeded, Need};
use super::pipeline_store::{PipelineKey, PipelineObjects};
use ash::vk;
use std::io::Cursor;
use std::sync::Arc;

pub struct ComputePipelineDesc<'a> {
    /// Debug name, also the pass name by convention.
    pub name: &'a str,
    /// The shader (`crate::shaders::<stem>::INTERFACE`): its SPIR-V, bindings
    /// and push-constant size, all reflected by build.rs.
    pub shader: &'a ShaderInterface,
    /// (constant_id, 32-bit value): booleans as 0/1, floats via `f32::to_bits`.
    pub specialization: &'a [(u32, u32)],
    /// How many descriptor sets this pipeline will need.
    pub max_sets: u32,
}

pub struct ComputePipeline {
    pub raw: vk::Pipeline,
    pub layout: vk::PipelineLayout,
    pub set_layout: vk::DescriptorSetLayout,
    /// Set 1's layout, null where the shader has no set 1.
    pub set1_layout: vk::DescriptorSetLayout,
    pub shader: &'static str,
    pub bindings: &'static [Binding],
    pub set1_bindings: &'static [Binding],
    pub push_constant_bytes: u32,
    pub descriptors: DescriptorAllocator,
    /// The two set-1 sets of a ping-pong shader (one per side).
    set1_descriptors: Option<DescriptorAllocator>,
    /// Shared with the context's store ([`super::pipeline_store`]); dropped
    /// after the GPU work using it completed, like every ComputePipeline.
    _objects: Arc<PipelineObjects>,
    _keep_alive: Arc<super::memory::GpuMemory>,
}

impl ComputePipeline {
    /// The pipeline of a shader compiled once.
    pub fn new(ctx: &Context, desc: &ComputePipelineDesc) -> Result<ComputePipeline, VkError> {
        match desc.shader.builds {
            [spirv] => ComputePipeline::create(ctx, desc, spirv),
            builds => Err(VkError::Shader {
                shader: desc.shader.name,
                problem: format!(
                    "has {} builds, a ping-pong pair: create its pipelines with parity_pair",
                    builds.len()
                ),
            }),
        }
    }

    fn create(ctx: &Context, desc: &ComputePipelineDesc, spirv: &[u8]) -> Result<ComputePipeline, VkError> {
        let shader = desc.shader;
        if shader.push_constant_bytes > ctx.limits.max_push_constants_size {
            let need = Need::new(
                Limit::PushConstants,
                shader.push_constant_bytes as u64,
                format!("shader {}", shader.name),
                "none (the shader's push-constant block)",
            );
            return Err(VkError::Limit(LimitExceeded {
                device: ctx.info.name.clone(),
                need,
                available: ctx.limits.max_push_constants_size as u64,
            }));
        }
        // The pipeline's own constants, then the context's shared ones it does
        // not set itself (constant ids must be unique).
        let mut constants = desc.specialization.to_vec();
        for (id, value) in ctx.shared_specialization() {
            if !constants.iter().any(|(own, _)| *own == id) {
                constants.push((id, value));
            }
        }
        let key = PipelineKey { spirv: spirv.as_ptr() as usize, name: desc.name.to_string(), constants };
        let (objects, created) = ctx.pipelines.get_or_create(key.clone(), || create_objects(ctx, desc, spirv, &key))?;
        if created {
            ctx.counters.pipeline_created();
        } else {
            ctx.counters.pipeline_reused();
        }
        let descriptors = DescriptorAllocator::new(ctx, shader.bindings, desc.max_sets.max(1))?;
        let set1_descriptors = match shader.set1 {
            [] => None,
            set1 => Some(DescriptorAllocator::new(ctx, set1, 2 * desc.max_sets.max(1))?),
        };
        Ok(ComputePipeline {
            raw: objects.raw,
            layout: objects.layout,
            set_layout: objects.set_layout,
            set1_layout: objects.set1_layout,
            shader: shader.name,
            bindings: shader.bindings,
            set1_bindings: shader.set1,
            push_constant_bytes: shader.push_constant_bytes,
            descriptors,
            set1_descriptors,
            _objects: objects,
            _keep_alive: ctx.memory.clone(),
        })
    }

    /// Allocates a descriptor set of this pipeline's layout and writes each
    /// resource into the binding it names; every binding of the shader needs one.
    pub fn create_set(&mut self, resources: &[(Binding, Resource)]) -> Result<vk::DescriptorSet, VkError> {
        self.descriptors.create_set(self.shader, self.set_layout, self.bindings, resources)
    }

    /// Allocates a set-1 set (one side of the ping-pong pair) and writes each
    /// resource into the binding it names; every set-1 binding needs one.
    pub fn create_set1(&mut self, resources: &[(Binding, Resource)]) -> Result<vk::DescriptorSet, VkError> {
        match &mut self.set1_descriptors {
            Some(d) => d.create_set(self.shader, self.set1_layout, self.set1_bindings, resources),
            None => Err(VkError::Shader { shader: self.shader, problem: "has no set 1".into() }),
        }
    }
}

/// The two builds of a ping-pong shader (build.rs `BINDING_VARIANTS`): index 0
/// reads side a of its pair and writes b, index 1 the opposite. Their layouts are
/// identical (the union of both builds' bindings), so one descriptor set
/// (allocated from index 0) serves both and a block switches sides by binding
/// the other pipeline.
pub fn parity_pair(ctx: &Context, desc: &ComputePipelineDesc) -> Result<[ComputePipeline; 2], VkError> {
    match desc.shader.builds {
        [read_a, read_b] => {
            Ok([ComputePipeline::create(ctx, desc, read_a)?, ComputePipeline::create(ctx, desc, read_b)?])
        }
        builds => Err(VkError::Shader {
            shader: desc.shader.name,
            problem: format!("has {} build(s), not the two of a ping-pong pair", builds.len()),
        }),
    }
}

/// One compute-stage descriptor of each binding, for a set layout.
pub fn layout_bindings(bindings: &[Binding]) -> Vec<vk::DescriptorSetLayoutBinding<'static>> {
    bindings
        .iter()
        .map(|b| {
            vk::DescriptorSetLayoutBinding::default()
                .binding(b.index)
                .descriptor_type(b.kind.vk_type())
                .descriptor_count(1)
                .stage_flags(vk::ShaderStageFlags::COMPUTE)
        })
        .collect()
}

/// A compute pipeline of `spirv` on `layout` with `constants` (id, value)
/// specialized; the shader module lives only for the call, and nothing leaks
/// where the creation fails.
pub fn specialized_pipeline(
    ctx: &Context,
    spirv: &[u8],
    layout: vk::PipelineLayout,
    constants: &[(u32, u32)],
) -> Result<vk::Pipeline, VkError> {
    let device = &ctx.device;
    let words = ash::util::read_spv(&mut Cursor::new(spirv))
        .map_err(|_| VkError::Call { call: "read_spv", result: vk::Result::ERROR_INVALID_SHADER_NV })?;
    let module_info = vk::ShaderModuleCreateInfo::default().code(&words);
    // SAFETY: words is valid SPIR-V compiled by build.rs.
    let module = unsafe { device.create_shader_module(&module_info, None) }.call("vkCreateShaderModule")?;
    let entries: Vec<vk::SpecializationMapEntry> = constants
        .iter()
        .enumerate()
        .map(|(i, (id, _))| vk::SpecializationMapEntry { constant_id: *id, offset: (i * 4) as u32, size: 4 })
        .collect();
    let data: Vec<u8> = constants.iter().flat_map(|(_, v)| v.to_ne_bytes()).collect();
    let spec = vk::SpecializationInfo::default().map_entries(&entries).data(&data);
    let stage = vk::PipelineShaderStageCreateInfo::default()
        .stage(vk::ShaderStageFlags::COMPUTE)
        .module(module)
        .name(c"main")
        .specialization_info(&spec);
    let info = [vk::ComputePipelineCreateInfo::default().stage(stage).layout(layout)];
    // SAFETY: module and layout are valid; the shader matches the layout.
    let created = unsafe { device.create_compute_pipelines(ctx.pipeline_cache.raw, &info, None) };
    // SAFETY: the module is no longer needed once pipelines are created.
    unsafe { device.destroy_shader_module(module, None) };
    match created {
        Ok(pipelines) => Ok(pipelines[0]),
        Err((pipelines, result)) => {
            // SAFETY: nothing uses a handle the failed call returned (null
            // where it created none; destroying null is a no-op).
            for p in pipelines {
                unsafe { device.destroy_pipeline(p, None) };
            }
            Err(VkError::Call { call: "vkCreateComputePipelines", result })
        }
    }
}

/// Compiles `spirv` with `key`'s constants into a pipeline and its layouts,
/// through the context's pipeline cache.
fn create_objects(
    ctx: &Context,
    desc: &ComputePipelineDesc,
    spirv: &[u8],
    key: &PipelineKey,
) -> Result<PipelineObjects, VkError> {
    let device = &ctx.device;
    let shader = desc.shader;
    let layout_of = |bindings: &[Binding]| {
        let layout_bindings = layout_bindings(bindings);
        let set_layout_info = vk::DescriptorSetLayoutCreateInfo::default().bindings(&layout_bindings);
        // SAFETY: valid device and create info.
        unsafe { device.create_descriptor_set_layout(&set_layout_info, None) }.call("vkCreateDescriptorSetLayout")
    };
    let set_layout = layout_of(shader.bindings)?;
    let set1_layout = match shader.set1 {
        [] => vk::DescriptorSetLayout::null(),
        set1 => layout_of(set1)
            // SAFETY (in the closure): the set layout was just created and is unused.
            .inspect_err(|_| unsafe { device.destroy_descriptor_set_layout(set_layout, None) })?,
    };
    let ranges = [vk::PushConstantRange::default()
        .stage_flags(vk::ShaderStageFlags::COMPUTE)
        .offset(0)
        .size(shader.push_constant_bytes.max(4))];
    let both = [set_layout, set1_layout];
    let set_layouts = if shader.set1.is_empty() { &both[..1] } else { &both[..] };
    let mut layout_info = vk::PipelineLayoutCreateInfo::default().set_layouts(set_layouts);
    if shader.push_constant_bytes > 0 {
        layout_info = layout_info.push_constant_ranges(&ranges);
    }
    // SAFETY: valid device and create info.
    let layout = unsafe { device.create_pipeline_layout(&layout_info, None) }
        .call("vkCreatePipelineLayout")
        // SAFETY (in the closure): the set layouts were just created and are
        // unused (destroying a null set-1 layout is a no-op).
        .inspect_err(|_| unsafe {
            device.destroy_descriptor_set_layout(set_layout, None);
            device.destroy_descriptor_set_layout(set1_layout, None);
        })?;
    let raw = specialized_pipeline(ctx, spirv, layout, &key.constants)
        // SAFETY (in the closure): nothing uses the layouts yet.
        .inspect_err(|_| unsafe {
            device.destroy_pipeline_layout(layout, None);
            device.destroy_descriptor_set_layout(set_layout, None);
            device.destroy_descriptor_set_layout(set1_layout, None);
        })?;
    ctx.set_name(raw, desc.name);
    Ok(PipelineObjects { raw, layout, set_layout, set1_layout, device: device.clone() })
}
