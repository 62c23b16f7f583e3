//! Descriptor pools and sets for the one set each compute pipeline uses.

use super::context::Context;
use super::error::{VkError, VkResultExt};
use super::resources::{Buffer, Image, Sampler};
use ash::vk;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BindingKind {
    /// `image2D` / `image3D` in GENERAL layout.
    StorageImage,
    /// `sampler3D` etc.: combined image sampler in SHADER_READ_ONLY_OPTIMAL.
    SampledImage,
    StorageBuffer,
    UniformBuffer,
}

impl BindingKind {
    pub fn vk_type(self) -> vk::DescriptorType {
        match self {
            BindingKind::StorageImage => vk::DescriptorType::STORAGE_IMAGE,
            BindingKind::SampledImage => vk::DescriptorType::COMBINED_IMAGE_SAMPLER,
            BindingKind::StorageBuffer => vk::DescriptorType::STORAGE_BUFFER,
            BindingKind::UniformBuffer => vk::DescriptorType::UNIFORM_BUFFER,
        }
    }
}

/// What goes into one binding.
#[derive(Clone, Copy)]
pub enum Resource<'a> {
    StorageImage(&'a Image),
    SampledImage(&'a Image, &'a Sampler),
    StorageBuffer(&'a Buffer),
    UniformBuffer(&'a Buffer),
}

pub struct DescriptorAllocator {
    pool: vk::DescriptorPool,
    device: ash::Device,
}

impl DescriptorAllocator {
    pub fn new(ctx: &Context, bindings: &[BindingKind], max_sets: u32) -> Result<Self, VkError> {
        let mut sizes: Vec<vk::DescriptorPoolSize> = Vec::new();
        for kind in bindings {
            let ty = kind.vk_type();
            match sizes.iter_mut().find(|s| s.ty == ty) {
                Some(s) => s.descriptor_count += max_sets,
                None => sizes.push(vk::DescriptorPoolSize { ty, descriptor_count: max_sets }),
            }
        }
        if sizes.is_empty() {
            sizes.push(vk::DescriptorPoolSize { ty: vk::DescriptorType::STORAGE_BUFFER, descriptor_count: 1 });
        }
        let info = vk::DescriptorPoolCreateInfo::default().max_sets(max_sets).pool_sizes(&sizes);
        // SAFETY: valid device and create info.
        let pool = unsafe { ctx.device.create_descriptor_pool(&info, None) }.call("vkCreateDescriptorPool")?;
        Ok(DescriptorAllocator { pool, device: ctx.device.clone() })
    }

    pub fn create_set(
        &mut self,
        layout: vk::DescriptorSetLayout,
        kinds: &[BindingKind],
        resources: &[Resource],
    ) -> Result<vk::DescriptorSet, VkError> {
        if kinds.len() != resources.len() {
            return Err(VkError::Call {
                call: "create_set: resource count does not match the layout",
                result: vk::Result::ERROR_UNKNOWN,
            });
        }
        let layouts = [layout];
        let alloc = vk::DescriptorSetAllocateInfo::default().descriptor_pool(self.pool).set_layouts(&layouts);
        // SAFETY: the pool was sized for max_sets sets of this layout.
        let set = unsafe { self.device.allocate_descriptor_sets(&alloc) }.call("vkAllocateDescriptorSets")?[0];
        let mut image_infos = Vec::with_capacity(resources.len());
        let mut buffer_infos = Vec::with_capacity(resources.len());
        for (kind, res) in kinds.iter().zip(resources) {
            let ok = matches!(
                (kind, res),
                (BindingKind::StorageImage, Resource::StorageImage(_))
                    | (BindingKind::SampledImage, Resource::SampledImage(..))
                    | (BindingKind::StorageBuffer, Resource::StorageBuffer(_))
                    | (BindingKind::UniformBuffer, Resource::UniformBuffer(_))
            );
            if !ok {
                return Err(VkError::Call {
                    call: "create_set: resource kind does not match the layout",
                    result: vk::Result::ERROR_UNKNOWN,
                });
            }
            match res {
                Resource::StorageImage(img) => image_infos.push([vk::DescriptorImageInfo::default()
                    .image_view(img.view)
                    .image_layout(vk::ImageLayout::GENERAL)]),
                Resource::SampledImage(img, s) => image_infos.push([vk::DescriptorImageInfo::default()
                    .image_view(img.view)
                    .sampler(s.raw)
                    .image_layout(vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL)]),
                Resource::StorageBuffer(b) | Resource::UniformBuffer(b) => {
                    buffer_infos.push([vk::DescriptorBufferInfo::default().buffer(b.raw).range(vk::WHOLE_SIZE)])
                }
            }
        }
        let (mut ii, mut bi) = (0, 0);
        let writes: Vec<vk::WriteDescriptorSet> = kinds
            .iter()
            .enumerate()
            .map(|(i, kind)| {
                let w = vk::WriteDescriptorSet::default()
                    .dst_set(set)
                    .dst_binding(i as u32)
                    .descriptor_type(kind.vk_type());
                match kind {
                    BindingKind::StorageImage | BindingKind::SampledImage => {
                        ii += 1;
                        w.image_info(&image_infos[ii - 1])
                    }
                    _ => {
                        bi += 1;
                        w.buffer_info(&buffer_infos[bi - 1])
                    }
                }
            })
            .collect();
        // SAFETY: every write points into image_infos/buffer_infos, alive for the call.
        unsafe { self.device.update_descriptor_sets(&writes, &[]) };
        Ok(set)
    }
}

impl Drop for DescriptorAllocator {
    fn drop(&mut self) {
        // SAFETY: sets from this pool are no longer used by pending GPU work.
        unsafe { self.device.destroy_descriptor_pool(self.pool, None) };
    }
}
