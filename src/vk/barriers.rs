//! Synchronization2 barriers, written where they matter and named for the hazard
//! they prevent (`accum_write_to_next_chunk_read`). The name goes into the command
//! buffer as a debug label, so RenderDoc shows the same words as the code.

use super::resources::{color_range, Buffer, Image};
use ash::vk;

/// One side of a dependency: pipeline stages and the memory accesses in them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Access {
    pub stage: vk::PipelineStageFlags2,
    pub access: vk::AccessFlags2,
}

impl Access {
    pub const NONE: Access = Access { stage: vk::PipelineStageFlags2::NONE, access: vk::AccessFlags2::NONE };
    pub const COMPUTE_READ: Access = Access {
        stage: vk::PipelineStageFlags2::COMPUTE_SHADER,
        access: vk::AccessFlags2::from_raw(
            vk::AccessFlags2::SHADER_STORAGE_READ.as_raw()
                | vk::AccessFlags2::SHADER_SAMPLED_READ.as_raw()
                | vk::AccessFlags2::UNIFORM_READ.as_raw(),
        ),
    };
    pub const COMPUTE_WRITE: Access =
        Access { stage: vk::PipelineStageFlags2::COMPUTE_SHADER, access: vk::AccessFlags2::SHADER_STORAGE_WRITE };
    pub const COMPUTE_READ_WRITE: Access = Access {
        stage: vk::PipelineStageFlags2::COMPUTE_SHADER,
        access: vk::AccessFlags2::from_raw(
            Access::COMPUTE_READ.access.as_raw() | vk::AccessFlags2::SHADER_STORAGE_WRITE.as_raw(),
        ),
    };
    pub const TRANSFER_READ: Access =
        Access { stage: vk::PipelineStageFlags2::COPY, access: vk::AccessFlags2::TRANSFER_READ };
    pub const TRANSFER_WRITE: Access =
        Access { stage: vk::PipelineStageFlags2::COPY, access: vk::AccessFlags2::TRANSFER_WRITE };
    /// Around `vkCmdFillBuffer` and `vkCmdClearColorImage`: ALL_TRANSFER, not
    /// CLEAR (the validation layer version we run with reports a false hazard).
    pub const CLEAR_WRITE: Access =
        Access { stage: vk::PipelineStageFlags2::ALL_TRANSFER, access: vk::AccessFlags2::TRANSFER_WRITE };
    pub const HOST_READ: Access = Access { stage: vk::PipelineStageFlags2::HOST, access: vk::AccessFlags2::HOST_READ };
    /// A sampled read in a compute shader of an image in
    /// SHADER_READ_ONLY_OPTIMAL (the volume): SHADER_READ, the access that
    /// layout expects (best practices' ImageBarrierAccessLayout).
    pub const COMPUTE_SAMPLED_READ: Access =
        Access { stage: vk::PipelineStageFlags2::COMPUTE_SHADER, access: vk::AccessFlags2::SHADER_READ };
    /// Any access the engine makes to its resources (compute shaders and
    /// transfers, the viewer's blit included): for resources kept from one
    /// submission to the next, where the earlier frame's last use varies. Not
    /// ALL_COMMANDS, which drains every stage on a GPU (best practices'
    /// pipeline-stage-flags).
    pub const ANY: Access = Access {
        stage: vk::PipelineStageFlags2::from_raw(
            vk::PipelineStageFlags2::COMPUTE_SHADER.as_raw() | vk::PipelineStageFlags2::ALL_TRANSFER.as_raw(),
        ),
        access: vk::AccessFlags2::from_raw(
            vk::AccessFlags2::SHADER_READ.as_raw()
                | vk::AccessFlags2::SHADER_WRITE.as_raw()
                | vk::AccessFlags2::UNIFORM_READ.as_raw()
                | vk::AccessFlags2::TRANSFER_READ.as_raw()
                | vk::AccessFlags2::TRANSFER_WRITE.as_raw(),
        ),
    };
}

/// Images an image barrier set holds: IPSVI's cache pairs, its output and its
/// merged-sweep accumulation.
pub const MAX_IMAGES: usize = 16;
/// Buffers it holds beside them.
pub const MAX_BUFFERS: usize = 2;

/// A barrier about to be recorded: a global memory barrier or an image barrier
/// (possibly with a layout transition).
#[derive(Clone, Copy, Debug)]
pub struct Barrier {
    pub name: &'static str,
    pub(crate) kind: BarrierKind,
}

#[derive(Clone, Copy, Debug)]
pub(crate) enum BarrierKind {
    Memory {
        src: Access,
        dst: Access,
    },
    Image {
        image: vk::Image,
        src: Access,
        dst: Access,
        old_layout: vk::ImageLayout,
        new_layout: vk::ImageLayout,
    },
    /// Up to [`MAX_IMAGES`] images in GENERAL layout, no transition, and up
    /// to [`MAX_BUFFERS`] whole buffers (null: none).
    Images {
        images: [vk::Image; MAX_IMAGES],
        count: usize,
        buffers: [vk::Buffer; MAX_BUFFERS],
        src: Access,
        dst: Access,
    },
}

impl Barrier {
    /// Global memory barrier: every write of `src` made visible to `dst`.
    pub fn memory(name: &'static str, src: Access, dst: Access) -> Barrier {
        Barrier { name, kind: BarrierKind::Memory { src, dst } }
    }

    /// Image barrier on the whole (single-level) colour image.
    pub fn image(
        name: &'static str,
        image: &Image,
        src: Access,
        dst: Access,
        old_layout: vk::ImageLayout,
        new_layout: vk::ImageLayout,
    ) -> Barrier {
        Barrier { name, kind: BarrierKind::Image { image: image.raw, src, dst, old_layout, new_layout } }
    }

    /// Image barrier on a colour image the caller does not own as an [`Image`]
    /// (a swapchain image).
    pub fn raw_image(
        name: &'static str,
        image: vk::Image,
        src: Access,
        dst: Access,
        old_layout: vk::ImageLayout,
        new_layout: vk::ImageLayout,
    ) -> Barrier {
        Barrier { name, kind: BarrierKind::Image { image, src, dst, old_layout, new_layout } }
    }

    /// Image barriers narrowed to `images` (GENERAL layout, at most [`MAX_IMAGES`]).
    pub fn images(name: &'static str, images: &[&Image], src: Access, dst: Access) -> Barrier {
        Barrier::images_and_buffers(name, images, &[], src, dst)
    }

    /// [`Barrier::images`] plus buffer barriers on the whole of each of
    /// `buffers` (at most [`MAX_BUFFERS`]). More images or buffers than fit
    /// are a bug of the caller: it panics rather than leave one unprotected.
    pub fn images_and_buffers(
        name: &'static str,
        images: &[&Image],
        buffers: &[&Buffer],
        src: Access,
        dst: Access,
    ) -> Barrier {
        assert!(images.len() <= MAX_IMAGES && buffers.len() <= MAX_BUFFERS, "barrier {name}: too many resources");
        let mut raw = [vk::Image::null(); MAX_IMAGES];
        for (r, i) in raw.iter_mut().zip(images) {
            *r = i.raw;
        }
        let mut raw_buffers = [vk::Buffer::null(); MAX_BUFFERS];
        for (r, b) in raw_buffers.iter_mut().zip(buffers) {
            *r = b.raw;
        }
        Barrier { name, kind: BarrierKind::Images { images: raw, count: images.len(), buffers: raw_buffers, src, dst } }
    }

    /// Calls `f` with this barrier as a `vk::DependencyInfo` (for barriers and events).
    pub(crate) fn with_dependency<R>(&self, f: impl FnOnce(&vk::DependencyInfo) -> R) -> R {
        let image_barrier = |image, src: Access, dst: Access, old, new| {
            vk::ImageMemoryBarrier2::default()
                .src_stage_mask(src.stage)
                .src_access_mask(src.access)
                .dst_stage_mask(dst.stage)
                .dst_access_mask(dst.access)
                .old_layout(old)
                .new_layout(new)
                .src_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
                .dst_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
                .image(image)
                .subresource_range(color_range())
        };
        match self.kind {
            BarrierKind::Memory { src, dst } => {
                let b = [vk::MemoryBarrier2::default()
                    .src_stage_mask(src.stage)
                    .src_access_mask(src.access)
                    .dst_stage_mask(dst.stage)
                    .dst_access_mask(dst.access)];
                f(&vk::DependencyInfo::default().memory_barriers(&b))
            }
            BarrierKind::Image { image, src, dst, old_layout, new_layout } => {
                let b = [image_barrier(image, src, dst, old_layout, new_layout)];
                f(&vk::DependencyInfo::default().image_memory_barriers(&b))
            }
            BarrierKind::Images { images, count, buffers, src, dst } => {
                let general = vk::ImageLayout::GENERAL;
                let b: Vec<vk::ImageMemoryBarrier2> =
                    images[..count].iter().map(|&i| image_barrier(i, src, dst, general, general)).collect();
                let buffers: Vec<vk::BufferMemoryBarrier2> = buffers
                    .iter()
                    .filter(|&&buffer| buffer != vk::Buffer::null())
                    .map(|&buffer| {
                        vk::BufferMemoryBarrier2::default()
                            .src_stage_mask(src.stage)
                            .src_access_mask(src.access)
                            .dst_stage_mask(dst.stage)
                            .dst_access_mask(dst.access)
                            .src_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
                            .dst_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
                            .buffer(buffer)
                            .offset(0)
                            .size(vk::WHOLE_SIZE)
                    })
                    .collect();
                f(&vk::DependencyInfo::default().image_memory_barriers(&b).buffer_memory_barriers(&buffers))
            }
        }
    }

    pub(crate) fn record(&self, device: &ash::Device, cb: vk::CommandBuffer) {
        // SAFETY: cb is in the recording state (Recorder owns it).
        self.with_dependency(|dep| unsafe { device.cmd_pipeline_barrier2(cb, dep) });
    }
}
