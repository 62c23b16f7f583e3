//! Frames in flight: each slot has its command buffer, an "image acquired"
//! semaphore, a fence that says the slot's last submission finished, the
//! profiler of that submission (the technique's frame, the present pass and
//! the panel), what the submission uses ([`InFlight`]: the recorded frame's
//! resources), and the upload buffer and image of a technique that cannot
//! record into the slot's command buffer. The loop waits for a slot's own
//! fence before reusing it, never for the whole device.

use crate::render::{OutputImage, RecordedFrame};
use crate::vk::error::VkResultExt;
use crate::vk::resources::ImageDesc;
use crate::vk::{Buffer, Context, Image, Profiler, VkError};
use ash::vk;
use gpu_allocator::MemoryLocation;
use std::sync::Arc;

pub const FRAMES_IN_FLIGHT: usize = 2;

/// Scopes per frame a slot's profiler holds (the technique's, the present
/// pass's and the panel's).
pub const PROFILER_CAPACITY: u32 = 16_384;

/// A submitted frame, until its slot's fence says it finished.
pub struct InFlight {
    /// Its record in the report, completed from the profile once resolved.
    pub record: usize,
    /// The technique's frame recorded into the slot's command buffer; `None`:
    /// it was rendered by its own submission and uploaded, or shown again.
    pub frame: Option<RecordedFrame>,
    /// The earlier frame shown again (a panel-only redraw), kept until the blit read it.
    pub reshown: Option<Arc<OutputImage>>,
    /// Write its profile and trace once resolved (`P`).
    pub write_profile: bool,
}

/// The frame image on its way to the swapchain: RGBA32F, linear.
pub struct Upload {
    pub width: u32,
    pub height: u32,
    pub staging: Buffer,
    pub image: Image,
}

pub struct FrameSlot {
    pub cb: vk::CommandBuffer,
    pool: vk::CommandPool,
    pub image_acquired: vk::Semaphore,
    pub done: vk::Fence,
    pub upload: Option<Upload>,
    pub profiler: Profiler,
    /// The slot's last submission, until it is resolved after `done`.
    pub in_flight: Option<InFlight>,
}

pub struct FramesInFlight<'c> {
    ctx: &'c Context,
    pub slots: Vec<FrameSlot>,
    next: usize,
}

impl<'c> FramesInFlight<'c> {
    pub fn new(ctx: &'c Context) -> Result<FramesInFlight<'c>, VkError> {
        let mut frames = FramesInFlight { ctx, slots: Vec::new(), next: 0 };
        for i in 0..FRAMES_IN_FLIGHT {
            let device = &ctx.device;
            let pool_info = vk::CommandPoolCreateInfo::default()
                .queue_family_index(ctx.queue_family)
                .flags(vk::CommandPoolCreateFlags::RESET_COMMAND_BUFFER);
            // SAFETY: valid device and queue family; destroyed in Drop after the fence.
            let pool = unsafe { device.create_command_pool(&pool_info, None) }.call("vkCreateCommandPool")?;
            let alloc = vk::CommandBufferAllocateInfo::default()
                .command_pool(pool)
                .level(vk::CommandBufferLevel::PRIMARY)
                .command_buffer_count(1);
            // SAFETY: pool is valid and used from this thread only.
            let cb = unsafe { device.allocate_command_buffers(&alloc) }.call("vkAllocateCommandBuffers");
            let cb = match cb {
                Ok(cb) => cb[0],
                Err(e) => {
                    // SAFETY: the pool is unused.
                    unsafe { device.destroy_command_pool(pool, None) };
                    return Err(e);
                }
            };
            ctx.set_name(cb, &format!("viewer frame {i}"));
            // SAFETY: valid device. A signalled fence: the slot starts free.
            let image_acquired = unsafe { device.create_semaphore(&vk::SemaphoreCreateInfo::default(), None) }
                .call("vkCreateSemaphore")?;
            let done = unsafe {
                device.create_fence(&vk::FenceCreateInfo::default().flags(vk::FenceCreateFlags::SIGNALED), None)
            }
            .call("vkCreateFence")?;
            ctx.set_name(image_acquired, &format!("image acquired {i}"));
            ctx.set_name(done, &format!("frame done {i}"));
            let mut profiler = Profiler::new(ctx, PROFILER_CAPACITY)?;
            // The panel draws in the same command buffers (see the setter).
            profiler.set_flush_after_timestamps(true);
            frames.slots.push(FrameSlot { cb, pool, image_acquired, done, upload: None, profiler, in_flight: None });
        }
        Ok(frames)
    }

    /// The next slot, once its previous submission has finished (its fence).
    pub fn next_slot(&mut self) -> Result<&mut FrameSlot, VkError> {
        let index = self.next;
        self.next = (self.next + 1) % self.slots.len();
        let slot = &mut self.slots[index];
        // SAFETY: the fence belongs to this device.
        unsafe { self.ctx.device.wait_for_fences(&[slot.done], true, u64::MAX) }.call("vkWaitForFences")?;
        Ok(slot)
    }

    /// Waits for every slot's last submission (before the swapchain is
    /// recreated and at the end).
    pub fn wait_all(&self) -> Result<(), VkError> {
        let fences: Vec<vk::Fence> = self.slots.iter().map(|s| s.done).collect();
        // SAFETY: the fences belong to this device.
        unsafe { self.ctx.device.wait_for_fences(&fences, true, u64::MAX) }.call("vkWaitForFences")
    }
}

impl Upload {
    pub fn new(ctx: &Context, width: u32, height: u32) -> Result<Upload, VkError> {
        let bytes = width as u64 * height as u64 * 16;
        let staging = Buffer::new(
            ctx,
            "viewer frame upload",
            bytes,
            vk::BufferUsageFlags::TRANSFER_SRC,
            MemoryLocation::CpuToGpu,
        )?;
        let image = Image::new(
            ctx,
            "viewer frame linear",
            ImageDesc {
                image_type: vk::ImageType::TYPE_2D,
                format: vk::Format::R32G32B32A32_SFLOAT,
                extent: vk::Extent3D { width, height, depth: 1 },
                // SAMPLED only because every Image gets a view; the frame is blitted.
                usage: vk::ImageUsageFlags::TRANSFER_DST
                    | vk::ImageUsageFlags::TRANSFER_SRC
                    | vk::ImageUsageFlags::SAMPLED,
            },
        )?;
        Ok(Upload { width, height, staging, image })
    }
}

impl Drop for FramesInFlight<'_> {
    fn drop(&mut self) {
        let _ = self.wait_all();
        for s in &self.slots {
            // SAFETY: every slot's submission finished (fences waited above); a
            // failed wait means a lost device, where destruction is still allowed.
            unsafe {
                self.ctx.device.destroy_fence(s.done, None);
                self.ctx.device.destroy_semaphore(s.image_acquired, None);
                self.ctx.device.destroy_command_pool(s.pool, None);
            }
        }
    }
}
