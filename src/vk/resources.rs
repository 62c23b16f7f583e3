//! Buffers, images and samplers, each freeing itself in `Drop`.

use super::context::Context;
use super::error::{VkError, VkResultExt};
use super::memory::GpuMemory;
use ash::vk;
use bytemuck::Pod;
use gpu_allocator::vulkan::Allocation;
use gpu_allocator::MemoryLocation;
use std::sync::Arc;

pub struct Buffer {
    pub raw: vk::Buffer,
    pub size: u64,
    /// Counted in `gpu_memory_bytes` (false for staging and readback buffers).
    tracked: bool,
    allocation: Option<Allocation>,
    memory: Arc<GpuMemory>,
}

impl Buffer {
    /// A buffer the renderer keeps: counted in `gpu_memory_bytes`.
    pub fn new(
        ctx: &Context,
        name: &str,
        size: u64,
        usage: vk::BufferUsageFlags,
        location: MemoryLocation,
    ) -> Result<Buffer, VkError> {
        Buffer::create(ctx, name, size, usage, location, true)
    }

    /// A host-visible buffer that only lives around one transfer (not counted).
    pub fn staging(
        ctx: &Context,
        name: &str,
        size: u64,
        usage: vk::BufferUsageFlags,
        location: MemoryLocation,
    ) -> Result<Buffer, VkError> {
        Buffer::create(ctx, name, size, usage, location, false)
    }

    fn create(
        ctx: &Context,
        name: &str,
        size: u64,
        usage: vk::BufferUsageFlags,
        location: MemoryLocation,
        tracked: bool,
    ) -> Result<Buffer, VkError> {
        let info =
            vk::BufferCreateInfo::default().size(size.max(4)).usage(usage).sharing_mode(vk::SharingMode::EXCLUSIVE);
        // SAFETY: valid device and create info.
        let raw = unsafe { ctx.device.create_buffer(&info, None) }.call("vkCreateBuffer")?;
        // SAFETY: raw was just created on this device.
        let requirements = unsafe { ctx.device.get_buffer_memory_requirements(raw) };
        let allocation = match ctx.memory.allocate(name, requirements, location, true, tracked) {
            Ok(a) => a,
            Err(e) => {
                // SAFETY: the buffer is unused and unbound.
                unsafe { ctx.device.destroy_buffer(raw, None) };
                return Err(e);
            }
        };
        let buffer = Buffer { raw, size, tracked, allocation: Some(allocation), memory: ctx.memory.clone() };
        let a = buffer.allocation.as_ref().expect("just set");
        // SAFETY: the allocation satisfies the buffer's requirements and is unbound.
        unsafe { ctx.device.bind_buffer_memory(raw, a.memory(), a.offset()) }.call("vkBindBufferMemory")?;
        ctx.set_name(raw, name);
        Ok(buffer)
    }

    /// A host-visible buffer holding `data`.
    pub fn with_data<T: Pod>(
        ctx: &Context,
        name: &str,
        data: &[T],
        usage: vk::BufferUsageFlags,
    ) -> Result<Buffer, VkError> {
        let bytes: &[u8] = bytemuck::cast_slice(data);
        let mut b = Buffer::new(ctx, name, bytes.len() as u64, usage, MemoryLocation::CpuToGpu)?;
        b.write_bytes(0, bytes)?;
        Ok(b)
    }

    pub fn write_bytes(&mut self, offset: usize, bytes: &[u8]) -> Result<(), VkError> {
        let slice = self.allocation.as_mut().and_then(|a| a.mapped_slice_mut()).ok_or_else(|| VkError::Allocation {
            name: "buffer write".into(),
            message: "buffer is not host visible".into(),
        })?;
        let end = offset + bytes.len();
        if end > slice.len() {
            return Err(VkError::Allocation {
                name: "buffer write".into(),
                message: format!("write of {end} bytes past {} bytes", slice.len()),
            });
        }
        slice[offset..end].copy_from_slice(bytes);
        Ok(())
    }

    pub fn write<T: Pod>(&mut self, data: &[T]) -> Result<(), VkError> {
        self.write_bytes(0, bytemuck::cast_slice(data))
    }

    /// Reads `count` values of `T` from a host-visible buffer.
    pub fn read<T: Pod>(&self, count: usize) -> Result<Vec<T>, VkError> {
        let slice = self.allocation.as_ref().and_then(|a| a.mapped_slice()).ok_or_else(|| VkError::Allocation {
            name: "buffer read".into(),
            message: "buffer is not host visible".into(),
        })?;
        let bytes = count * std::mem::size_of::<T>();
        if bytes > slice.len() {
            return Err(VkError::Allocation {
                name: "buffer read".into(),
                message: format!("read of {bytes} bytes past {} bytes", slice.len()),
            });
        }
        let mut out = vec![T::zeroed(); count];
        bytemuck::cast_slice_mut::<T, u8>(&mut out).copy_from_slice(&slice[..bytes]);
        Ok(out)
    }
    /// The first `count` values of `T` of a host-visible buffer, in place: no
    /// copy, for large read-backs. No pending GPU work may write the buffer
    /// while the slice lives (the caller waited for the submission).
    pub fn mapped<T: Pod>(&self, count: usize) -> Result<&[T], VkError> {
        let error = |message: String| VkError::Allocation { name: "buffer read".into(), message };
        let slice = self
            .allocation
            .as_ref()
            .and_then(|a| a.mapped_slice())
            .ok_or_else(|| error("buffer is not host visible".into()))?;
        let bytes = count * std::mem::size_of::<T>();
        if bytes > slice.len() {
            return Err(error(format!("read of {bytes} bytes past {} bytes", slice.len())));
        }
        bytemuck::try_cast_slice(&slice[..bytes]).map_err(|e| error(format!("mapped memory: {e}")))
    }
}

impl Drop for Buffer {
    fn drop(&mut self) {
        // SAFETY: callers drop resources only after the GPU work using them completed
        // (every submission waits on its fence).
        unsafe { self.memory.device.destroy_buffer(self.raw, None) };
        if let Some(a) = self.allocation.take() {
            self.memory.free(a, self.tracked);
        }
    }
}

#[derive(Clone, Copy, Debug)]
pub struct ImageDesc {
    pub image_type: vk::ImageType,
    pub format: vk::Format,
    pub extent: vk::Extent3D,
    pub usage: vk::ImageUsageFlags,
}

pub struct Image {
    pub raw: vk::Image,
    pub view: vk::ImageView,
    pub desc: ImageDesc,
    allocation: Option<Allocation>,
    memory: Arc<GpuMemory>,
}

impl Image {
    pub fn new(ctx: &Context, name: &str, desc: ImageDesc) -> Result<Image, VkError> {
        let info = vk::ImageCreateInfo::default()
            .image_type(desc.image_type)
            .format(desc.format)
            .extent(desc.extent)
            .mip_levels(1)
            .array_layers(1)
            .samples(vk::SampleCountFlags::TYPE_1)
            .tiling(vk::ImageTiling::OPTIMAL)
            .usage(desc.usage)
            .sharing_mode(vk::SharingMode::EXCLUSIVE)
            .initial_layout(vk::ImageLayout::UNDEFINED);
        // SAFETY: valid device and create info.
        let raw = unsafe { ctx.device.create_image(&info, None) }.call("vkCreateImage")?;
        ctx.counters.image_created();
        // SAFETY: raw was just created on this device.
        let requirements = unsafe { ctx.device.get_image_memory_requirements(raw) };
        let allocation = match ctx.memory.allocate(name, requirements, MemoryLocation::GpuOnly, false, true) {
            Ok(a) => a,
            Err(e) => {
                // SAFETY: the image is unused and unbound.
                unsafe { ctx.device.destroy_image(raw, None) };
                return Err(e);
            }
        };
        // SAFETY: the allocation satisfies the image's requirements and is unbound.
        if let Err(e) = unsafe { ctx.device.bind_image_memory(raw, allocation.memory(), allocation.offset()) }
            .call("vkBindImageMemory")
        {
            // SAFETY: the image is unused.
            unsafe { ctx.device.destroy_image(raw, None) };
            ctx.memory.free(allocation, true);
            return Err(e);
        }
        let view_type = match desc.image_type {
            vk::ImageType::TYPE_1D => vk::ImageViewType::TYPE_1D,
            vk::ImageType::TYPE_3D => vk::ImageViewType::TYPE_3D,
            _ => vk::ImageViewType::TYPE_2D,
        };
        let view_info = vk::ImageViewCreateInfo::default()
            .image(raw)
            .view_type(view_type)
            .format(desc.format)
            .subresource_range(color_range());
        // SAFETY: the image is bound to memory and the view matches its type and format.
        let view = match unsafe { ctx.device.create_image_view(&view_info, None) }.call("vkCreateImageView") {
            Ok(v) => v,
            Err(e) => {
                // SAFETY: the image is unused.
                unsafe { ctx.device.destroy_image(raw, None) };
                ctx.memory.free(allocation, true);
                return Err(e);
            }
        };
        ctx.set_name(raw, name);
        ctx.set_name(view, name);
        Ok(Image { raw, view, desc, allocation: Some(allocation), memory: ctx.memory.clone() })
    }

    /// A 2D storage image (compute shaders' buffers, caches, outputs); `extra`
    /// adds usages such as TRANSFER_SRC for readback or TRANSFER_DST for clears.
    pub fn storage_2d(
        ctx: &Context,
        name: &str,
        format: vk::Format,
        width: u32,
        height: u32,
        extra: vk::ImageUsageFlags,
    ) -> Result<Image, VkError> {
        let desc = ImageDesc {
            image_type: vk::ImageType::TYPE_2D,
            format,
            extent: vk::Extent3D { width, height, depth: 1 },
            usage: vk::ImageUsageFlags::STORAGE | extra,
        };
        Image::new(ctx, name, desc)
    }

    pub fn extent(&self) -> vk::Extent3D {
        self.desc.extent
    }
}

impl Drop for Image {
    fn drop(&mut self) {
        // SAFETY: resources are dropped only after the GPU work using them completed.
        unsafe {
            self.memory.device.destroy_image_view(self.view, None);
            self.memory.device.destroy_image(self.raw, None);
        }
        if let Some(a) = self.allocation.take() {
            self.memory.free(a, true);
        }
    }
}

pub fn color_range() -> vk::ImageSubresourceRange {
    vk::ImageSubresourceRange::default().aspect_mask(vk::ImageAspectFlags::COLOR).level_count(1).layer_count(1)
}

pub fn color_layers() -> vk::ImageSubresourceLayers {
    vk::ImageSubresourceLayers::default().aspect_mask(vk::ImageAspectFlags::COLOR).layer_count(1)
}

/// Linear filtering, clamp to edge, normalized coordinates.
pub struct Sampler {
    pub raw: vk::Sampler,
    memory: Arc<GpuMemory>,
}

impl Sampler {
    pub fn linear_clamp(ctx: &Context, name: &str) -> Result<Sampler, VkError> {
        let info = vk::SamplerCreateInfo::default()
            .mag_filter(vk::Filter::LINEAR)
            .min_filter(vk::Filter::LINEAR)
            .mipmap_mode(vk::SamplerMipmapMode::NEAREST)
            .address_mode_u(vk::SamplerAddressMode::CLAMP_TO_EDGE)
            .address_mode_v(vk::SamplerAddressMode::CLAMP_TO_EDGE)
            .address_mode_w(vk::SamplerAddressMode::CLAMP_TO_EDGE)
            .max_lod(0.0);
        // SAFETY: valid device and create info.
        let raw = unsafe { ctx.device.create_sampler(&info, None) }.call("vkCreateSampler")?;
        ctx.set_name(raw, name);
        Ok(Sampler { raw, memory: ctx.memory.clone() })
    }
}

impl Drop for Sampler {
    fn drop(&mut self) {
        // SAFETY: dropped only after the GPU work using it completed.
        unsafe { self.memory.device.destroy_sampler(self.raw, None) };
    }
}
