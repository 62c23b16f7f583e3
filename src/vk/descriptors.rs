//! Descriptor pools and sets for the one set each compute pipeline uses. Sets
//! are written by binding name (`crate::shaders::<stem>::<BINDING>`), checked
//! against the shader's reflected interface.

use super::context::Context;
use super::descriptor_pool_shelf::{PoolShape, PoolShelf};
use super::error::{VkError, VkResultExt};
use super::interface::Binding;
use super::resources::{Buffer, Image, Sampler};
use ash::vk;
use std::sync::Arc;

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
    /// `range` bytes of a storage buffer from `offset` (a multiple of
    /// `minStorageBufferOffsetAlignment`), for a buffer larger than
    /// `maxStorageBufferRange` bound in windows.
    StorageBufferWindow {
        buffer: &'a Buffer,
        offset: u64,
        range: u64,
    },
    UniformBuffer(&'a Buffer),
}

impl Resource<'_> {
    pub fn kind(&self) -> BindingKind {
        match self {
            Resource::StorageImage(_) => BindingKind::StorageImage,
            Resource::SampledImage(..) => BindingKind::SampledImage,
            Resource::StorageBuffer(_) | Resource::StorageBufferWindow { .. } => BindingKind::StorageBuffer,
            Resource::UniformBuffer(_) => BindingKind::UniformBuffer,
        }
    }
}

/// Checks a set's resources, named by binding, against the shader's bindings:
/// each binding of `layout` gets exactly one resource of its kind, and nothing
/// else is given. The error names the binding.
pub fn check_set(shader: &'static str, layout: &[Binding], given: &[(Binding, BindingKind)]) -> Result<(), VkError> {
    let error = |binding: &Binding, problem: String| VkError::Binding { shader, binding: binding.name, problem };
    for (i, (binding, kind)) in given.iter().enumerate() {
        let Some(declared) = layout.iter().find(|l| l.index == binding.index) else {
            return Err(error(binding, format!("(index {}) is not declared by this shader", binding.index)));
        };
        if declared.name != binding.name {
            return Err(error(
                binding,
                format!(
                    "(index {}) is not declared by this shader: its binding {} is {}",
                    binding.index, declared.index, declared.name
                ),
            ));
        }
        if declared.kind != *kind {
            return Err(error(binding, format!("is a {:?} binding, given a {kind:?}", declared.kind)));
        }
        if given[..i].iter().any(|(b, _)| b.index == binding.index) {
            return Err(error(binding, "is given two resources".into()));
        }
    }
    match layout.iter().find(|l| !given.iter().any(|(b, _)| b.index == l.index)) {
        Some(missing) => Err(error(missing, format!("(index {}) has no resource", missing.index))),
        None => Ok(()),
    }
}

pub struct DescriptorAllocator {
    pool: vk::DescriptorPool,
    shape: PoolShape,
    shelf: Arc<PoolShelf>,
    device: ash::Device,
}

impl DescriptorAllocator {
    /// A pool for `max_sets` sets of `bindings`: a shelved one of that shape
    /// where there is one ([`super::descriptor_pool_shelf`]), else a new one.
    pub fn new(ctx: &Context, bindings: &[Binding], max_sets: u32) -> Result<Self, VkError> {
        let mut sizes: Vec<(vk::DescriptorType, u32)> = Vec::new();
        for binding in bindings {
            let ty = binding.kind.vk_type();
            match sizes.iter_mut().find(|s| s.0 == ty) {
                Some(s) => s.1 += max_sets,
                None => sizes.push((ty, max_sets)),
            }
        }
        if sizes.is_empty() {
            sizes.push((vk::DescriptorType::STORAGE_BUFFER, 1));
        }
        let shape = PoolShape { max_sets, sizes };
        let shelf = ctx.descriptor_pools.clone();
        if let Some(pool) = shelf.take(&shape) {
            return Ok(DescriptorAllocator { pool, shape, shelf, device: ctx.device.clone() });
        }
        let sizes: Vec<vk::DescriptorPoolSize> =
            shape.sizes.iter().map(|&(ty, descriptor_count)| vk::DescriptorPoolSize { ty, descriptor_count }).collect();
        let info = vk::DescriptorPoolCreateInfo::default().max_sets(max_sets).pool_sizes(&sizes);
        // SAFETY: valid device and create info.
        let pool = unsafe { ctx.device.create_descriptor_pool(&info, None) }.call("vkCreateDescriptorPool")?;
        ctx.counters.descriptor_pool_created();
        Ok(DescriptorAllocator { pool, shape, shelf, device: ctx.device.clone() })
    }

    /// Allocates a set of `layout` and writes `resources` into the bindings they
    /// name, after [`check_set`] against `bindings`.
    pub fn create_set(
        &mut self,
        shader: &'static str,
        layout: vk::DescriptorSetLayout,
        bindings: &[Binding],
        resources: &[(Binding, Resource)],
    ) -> Result<vk::DescriptorSet, VkError> {
        let kinds: Vec<(Binding, BindingKind)> = resources.iter().map(|(b, r)| (*b, r.kind())).collect();
        check_set(shader, bindings, &kinds)?;
        let layouts = [layout];
        let alloc = vk::DescriptorSetAllocateInfo::default().descriptor_pool(self.pool).set_layouts(&layouts);
        // SAFETY: the pool was sized for max_sets sets of this layout.
        let set = unsafe { self.device.allocate_descriptor_sets(&alloc) }.call("vkAllocateDescriptorSets")?[0];
        let image_infos: Vec<[vk::DescriptorImageInfo; 1]> = resources
            .iter()
            .map(|(_, res)| match res {
                Resource::StorageImage(img) => {
                    [vk::DescriptorImageInfo::default().image_view(img.view).image_layout(vk::ImageLayout::GENERAL)]
                }
                Resource::SampledImage(img, s) => [vk::DescriptorImageInfo::default()
                    .image_view(img.view)
                    .sampler(s.raw)
                    .image_layout(vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL)],
                _ => [vk::DescriptorImageInfo::default()],
            })
            .collect();
        let buffer_infos: Vec<[vk::DescriptorBufferInfo; 1]> = resources
            .iter()
            .map(|(_, res)| match res {
                Resource::StorageBuffer(b) | Resource::UniformBuffer(b) => {
                    [vk::DescriptorBufferInfo::default().buffer(b.raw).range(vk::WHOLE_SIZE)]
                }
                Resource::StorageBufferWindow { buffer, offset, range } => {
                    [vk::DescriptorBufferInfo::default().buffer(buffer.raw).offset(*offset).range(*range)]
                }
                _ => [vk::DescriptorBufferInfo::default()],
            })
            .collect();
        let writes: Vec<vk::WriteDescriptorSet> = resources
            .iter()
            .enumerate()
            .map(|(i, (binding, res))| {
                let w = vk::WriteDescriptorSet::default()
                    .dst_set(set)
                    .dst_binding(binding.index)
                    .descriptor_type(binding.kind.vk_type());
                match res {
                    Resource::StorageImage(_) | Resource::SampledImage(..) => w.image_info(&image_infos[i]),
                    Resource::StorageBuffer(_) | Resource::StorageBufferWindow { .. } | Resource::UniformBuffer(_) => {
                        w.buffer_info(&buffer_infos[i])
                    }
                }
            })
            .collect();
        // SAFETY: every write points into image_infos/buffer_infos, alive for the call,
        // and check_set matched each binding's descriptor type.
        unsafe { self.device.update_descriptor_sets(&writes, &[]) };
        Ok(set)
    }
}

impl Drop for DescriptorAllocator {
    fn drop(&mut self) {
        // Sets from this pool are no longer used by pending GPU work (an
        // allocator is dropped with its pipeline, after the work using it).
        if self.shelf.give_back(self.shape.clone(), self.pool).is_err() {
            // SAFETY: as above; a pool that failed to reset is not shelved.
            unsafe { self.device.destroy_descriptor_pool(self.pool, None) };
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const FRAME: Binding = Binding { name: "frame", index: 0, kind: BindingKind::UniformBuffer };
    const OUT_IMAGE: Binding = Binding { name: "out_image", index: 4, kind: BindingKind::StorageImage };
    const LAYOUT: [Binding; 2] = [FRAME, OUT_IMAGE];

    fn problem(given: &[(Binding, BindingKind)]) -> String {
        check_set("raycast", &LAYOUT, given).unwrap_err().to_string()
    }

    #[test]
    fn a_complete_set_of_the_right_kinds_passes() {
        check_set("raycast", &LAYOUT, &[(OUT_IMAGE, BindingKind::StorageImage), (FRAME, BindingKind::UniformBuffer)])
            .unwrap();
    }

    #[test]
    fn a_missing_binding_is_named() {
        let e = problem(&[(FRAME, BindingKind::UniformBuffer)]);
        assert_eq!(e, "shader raycast: binding out_image (index 4) has no resource");
    }

    #[test]
    fn a_resource_of_the_wrong_kind_is_named() {
        let e = problem(&[(FRAME, BindingKind::StorageBuffer), (OUT_IMAGE, BindingKind::StorageImage)]);
        assert_eq!(e, "shader raycast: binding frame is a UniformBuffer binding, given a StorageBuffer");
    }

    #[test]
    fn a_binding_of_another_shader_is_named() {
        let depths = Binding { name: "depths", index: 3, kind: BindingKind::StorageImage };
        let e = problem(&[
            (FRAME, BindingKind::UniformBuffer),
            (OUT_IMAGE, BindingKind::StorageImage),
            (depths, BindingKind::StorageImage),
        ]);
        assert_eq!(e, "shader raycast: binding depths (index 3) is not declared by this shader");
        let renamed = Binding { name: "illumination", index: 4, kind: BindingKind::StorageImage };
        let e = problem(&[(FRAME, BindingKind::UniformBuffer), (renamed, BindingKind::StorageImage)]);
        assert_eq!(
            e,
            "shader raycast: binding illumination (index 4) is not declared by this shader: its binding 4 is out_image"
        );
    }

    #[test]
    fn a_binding_given_twice_is_named() {
        let e = problem(&[
            (FRAME, BindingKind::UniformBuffer),
            (OUT_IMAGE, BindingKind::StorageImage),
            (OUT_IMAGE, BindingKind::StorageImage),
        ]);
        assert_eq!(e, "shader raycast: binding out_image is given two resources");
    }
}
