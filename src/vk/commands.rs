//! Command recording: a [`Recorder`] wraps one command buffer in the recording
//! state; [`submit_and_wait`] owns begin, record, end, submit and the fence.

use super::barriers::{Access, Barrier};
use super::context::Context;
use super::error::{VkError, VkResultExt};
use super::finished_frame::FinishedFrame;
use super::limits::{Limit, LimitExceeded, Need};
use super::pipeline::ComputePipeline;
use super::resources::{color_layers, Buffer, Image};
use super::wait_report::{wait_for_fence, WaitReport};
use ash::vk;
use bytemuck::Pod;
use std::cell::Cell;
use std::ffi::CString;
use std::time::Duration;

pub struct Recorder<'a> {
    pub ctx: &'a Context,
    pub cb: vk::CommandBuffer,
    /// Barriers recorded so far (tests and reports count them).
    pub barrier_count: u32,
    pub dispatch_count: u32,
    /// Submissions so far, and what orders them: see `split_submission`.
    pub submissions: u32,
    pool: vk::CommandPool,
    timeline: Option<vk::Semaphore>,
    /// Debug labels open now: a split closes them in the old command buffer and
    /// reopens them in the new one (labels do not span command buffers well).
    open_labels: Vec<String>,
    /// The first dispatch over `maxComputeWorkGroupCount`: not recorded, and
    /// the submission refused ([`Recorder::check_limits`]).
    over_limit: Option<LimitExceeded>,
    /// Transfer commands (copies, clears, fills) and executed secondaries so
    /// far, and whether the last command was one: the profiler writes a scope's
    /// timestamps at the compute stage only around compute work.
    transfers: Cell<u32>,
    last_was_transfer: Cell<bool>,
    /// What a discard of an image (`discard_for_compute`, `clear_for_compute`)
    /// waits for: nothing where every image a frame discards is its own
    /// (`Access::NONE`), any earlier access where the images are kept from
    /// frames still in flight (`Access::ANY`, the viewer's `FrameImages`).
    pub discard_after: Access,
}

impl<'a> Recorder<'a> {
    /// A recorder for `cb` (already begun), allocated from `pool`.
    fn fresh(ctx: &'a Context, cb: vk::CommandBuffer, pool: vk::CommandPool) -> Self {
        Recorder {
            ctx,
            cb,
            barrier_count: 0,
            dispatch_count: 0,
            submissions: 0,
            pool,
            timeline: None,
            open_labels: Vec::new(),
            over_limit: None,
            transfers: Cell::new(0),
            last_was_transfer: Cell::new(false),
            discard_after: Access::NONE,
        }
    }

    /// A recorder for `cb`, begun by a caller that ends and submits it itself
    /// with its own semaphores and fence (the viewer's frames in flight). Such a
    /// command buffer cannot be split into several submissions.
    pub fn for_command_buffer(ctx: &'a Context, cb: vk::CommandBuffer) -> Self {
        Recorder::fresh(ctx, cb, vk::CommandPool::null())
    }

    pub fn device(&self) -> &ash::Device {
        &self.ctx.device
    }

    pub fn begin_label(&mut self, name: &str) {
        self.open_labels.push(name.to_string());
        self.raw_begin_label(name);
    }

    fn raw_begin_label(&self, name: &str) {
        if let Some(du) = &self.ctx.debug_utils {
            let Ok(name) = CString::new(name) else { return };
            let label = vk::DebugUtilsLabelEXT::default().label_name(&name);
            // SAFETY: cb is recording; labels have no effect on execution.
            unsafe { du.cmd_begin_debug_utils_label(self.cb, &label) };
        }
    }

    pub fn end_label(&mut self) {
        self.open_labels.pop();
        self.raw_end_label();
    }

    fn raw_end_label(&self) {
        if let Some(du) = &self.ctx.debug_utils {
            // SAFETY: paired with begin_label by the profiler's scopes.
            unsafe { du.cmd_end_debug_utils_label(self.cb) };
        }
    }

    fn insert_label(&self, name: &str) {
        if let Some(du) = &self.ctx.debug_utils {
            let Ok(name) = CString::new(name) else { return };
            let label = vk::DebugUtilsLabelEXT::default().label_name(&name);
            // SAFETY: cb is recording; labels have no effect on execution.
            unsafe { du.cmd_insert_debug_utils_label(self.cb, &label) };
        }
    }

    /// Records `barrier`, labelled with its name.
    pub fn barrier(&mut self, barrier: &Barrier) {
        self.insert_label(barrier.name);
        barrier.record(&self.ctx.device, self.cb);
        self.barrier_count += 1;
    }

    /// Ends the command buffer recorded so far, submits it, and goes on in a new
    /// one. Consecutive submissions are ordered by a timeline semaphore (signal
    /// value n after all commands, wait for it before any command of the next):
    /// a full execution and memory dependency at queue-submission granularity.
    /// The new command buffer starts with nothing bound: bind again before use.
    pub fn split_submission(&mut self) -> Result<(), VkError> {
        if self.pool == vk::CommandPool::null() {
            return Err(VkError::Presentation("a command buffer submitted by its caller cannot be split".into()));
        }
        self.check_limits()?;
        let device = &self.ctx.device;
        let timeline = match self.timeline {
            Some(t) => t,
            None => {
                let mut kind = vk::SemaphoreTypeCreateInfo::default().semaphore_type(vk::SemaphoreType::TIMELINE);
                let info = vk::SemaphoreCreateInfo::default().push_next(&mut kind);
                // SAFETY: valid device; the semaphore is destroyed after the last wait.
                let t = unsafe { device.create_semaphore(&info, None) }.call("vkCreateSemaphore")?;
                self.timeline = Some(t);
                t
            }
        };
        for _ in &self.open_labels {
            self.raw_end_label();
        }
        // SAFETY: cb is recording.
        unsafe { device.end_command_buffer(self.cb) }.call("vkEndCommandBuffer")?;
        submit_part(self.ctx, self.cb, timeline, self.submissions, vk::Fence::null())?;
        self.submissions += 1;
        self.cb = begin_command_buffer(self.ctx, self.pool, "frame (continued)")?;
        for name in &self.open_labels {
            self.raw_begin_label(name);
        }
        Ok(())
    }

    /// Executes secondary command buffer `index` of `secondary` (recorded once,
    /// replayed every frame).
    pub fn execute(&mut self, secondary: &SecondaryCommands, index: usize) {
        self.note_transfer();
        // SAFETY: the secondary was recorded for this device and is executable; it
        // is not in use by another submission (every frame waits on its fence).
        unsafe { self.ctx.device.cmd_execute_commands(self.cb, &[secondary.buffers[index]]) };
        self.dispatch_count += secondary.dispatches[index];
        self.barrier_count += secondary.barriers[index];
    }

    /// First half of a split barrier: signals `event` once the work before it has
    /// done what `barrier`'s source side names.
    pub fn set_event(&mut self, event: vk::Event, barrier: &Barrier) {
        self.insert_label(barrier.name);
        // SAFETY: cb is recording; the event belongs to this device.
        barrier.with_dependency(|dep| unsafe { self.ctx.device.cmd_set_event2(self.cb, event, dep) });
    }

    /// Second half: waits for `event` with the same dependency it was set with.
    pub fn wait_event(&mut self, event: vk::Event, barrier: &Barrier) {
        self.insert_label(barrier.name);
        // SAFETY: cb is recording; the event was set earlier in this submission with
        // an identical dependency.
        barrier.with_dependency(|dep| unsafe {
            self.ctx.device.cmd_wait_events2(self.cb, &[event], std::slice::from_ref(dep))
        });
        self.barrier_count += 1;
    }

    /// Binds a compute pipeline and its descriptor set. On lavapipe each bind
    /// costs far more than a dispatch (about 0.7 ms for the pipeline against
    /// 0.08 ms for a dispatch, measured by tools/dispatch_probe.rs): bind once
    /// and switch only the set where a sweep needs it.
    pub fn bind(&self, pipeline: &ComputePipeline, set: vk::DescriptorSet) {
        self.bind_pipeline(pipeline);
        self.bind_set(pipeline, set);
    }

    pub fn bind_pipeline(&self, pipeline: &ComputePipeline) {
        // SAFETY: the pipeline belongs to this device; cb is recording.
        unsafe { self.ctx.device.cmd_bind_pipeline(self.cb, vk::PipelineBindPoint::COMPUTE, pipeline.raw) };
    }

    /// Binds set 1 (one side of a ping-pong pair), leaving set 0 bound.
    pub fn bind_set1(&self, pipeline: &ComputePipeline, set: vk::DescriptorSet) {
        self.bind_set_at(pipeline, 1, set);
    }

    pub fn bind_set(&self, pipeline: &ComputePipeline, set: vk::DescriptorSet) {
        self.bind_set_at(pipeline, 0, set);
    }

    fn bind_set_at(&self, pipeline: &ComputePipeline, index: u32, set: vk::DescriptorSet) {
        // SAFETY: the set was allocated with this pipeline's layout of set
        // `index` (create_set, create_set1); cb is recording.
        unsafe {
            self.ctx.device.cmd_bind_descriptor_sets(
                self.cb,
                vk::PipelineBindPoint::COMPUTE,
                pipeline.layout,
                index,
                &[set],
                &[],
            )
        };
    }

    /// Push constants: the shader's push block mirrored by a `Pod` struct.
    pub fn push<T: Pod>(&self, pipeline: &ComputePipeline, value: &T) {
        let bytes = bytemuck::bytes_of(value);
        // A programming error, not an input: the push struct of another shader.
        assert_eq!(
            bytes.len() as u32,
            pipeline.push_constant_bytes,
            "push constants of {} bytes for shader {}",
            bytes.len(),
            pipeline.shader
        );
        // SAFETY: the layout declares a compute push-constant range covering `bytes`
        // (checked when the pipeline was created).
        unsafe {
            self.ctx.device.cmd_push_constants(self.cb, pipeline.layout, vk::ShaderStageFlags::COMPUTE, 0, bytes)
        };
    }

    pub fn dispatch(&mut self, x: u32, y: u32, z: u32) {
        let counts = [x.max(1), y.max(1), z.max(1)];
        let max = self.ctx.limits.max_compute_work_group_count;
        if let Some(axis) = (0..3).find(|&a| counts[a] > max[a]) {
            // Recording it would be invalid usage; the submission is refused instead.
            if self.over_limit.is_none() {
                let pass = self.open_labels.last().cloned().unwrap_or_else(|| "a dispatch".into());
                self.over_limit = Some(LimitExceeded {
                    device: self.ctx.info.name.clone(),
                    need: Need::new(
                        Limit::WorkGroupCount(axis),
                        counts[axis] as u64,
                        format!("pass {pass}"),
                        "the image size or the technique's cache or slice sizes",
                    ),
                    available: max[axis] as u64,
                });
            }
            return;
        }
        // SAFETY: a compute pipeline and its descriptor set are bound by the caller.
        unsafe { self.ctx.device.cmd_dispatch(self.cb, counts[0], counts[1], counts[2]) };
        self.dispatch_count += 1;
        self.last_was_transfer.set(false);
    }

    /// Counts a command that is not a dispatch (a copy, clear, fill or executed
    /// secondary); callers that record such commands on `cb` themselves call it
    /// so that profiler scopes around them wait for them.
    pub fn note_transfer(&self) {
        self.transfers.set(self.transfers.get() + 1);
        self.last_was_transfer.set(true);
    }

    /// Transfer commands recorded so far ([`Recorder::note_transfer`]).
    pub fn transfers(&self) -> u32 {
        self.transfers.get()
    }

    /// Whether the last command recorded was a transfer rather than a dispatch.
    pub fn last_was_transfer(&self) -> bool {
        self.last_was_transfer.get()
    }

    /// Err where a dispatch recorded so far was over a device limit: checked
    /// before every submission, so nothing runs. A caller that submits the
    /// command buffer itself ([`Recorder::for_command_buffer`]) calls it first.
    pub fn check_limits(&self) -> Result<(), VkError> {
        match &self.over_limit {
            Some(e) => Err(VkError::Limit(e.clone())),
            None => Ok(()),
        }
    }

    pub fn copy_buffer_to_image(&self, src: &Buffer, dst: &Image) {
        self.note_transfer();
        let region = [vk::BufferImageCopy::default().image_subresource(color_layers()).image_extent(dst.extent())];
        // SAFETY: dst is in TRANSFER_DST_OPTIMAL (the caller's barrier) and src holds
        // at least extent * texel size bytes.
        unsafe {
            self.ctx.device.cmd_copy_buffer_to_image(
                self.cb,
                src.raw,
                dst.raw,
                vk::ImageLayout::TRANSFER_DST_OPTIMAL,
                &region,
            )
        };
    }

    pub fn copy_image_to_buffer(&self, src: &Image, layout: vk::ImageLayout, dst: &Buffer) {
        self.note_transfer();
        let region = [vk::BufferImageCopy::default().image_subresource(color_layers()).image_extent(src.extent())];
        // SAFETY: src is in `layout` (GENERAL or TRANSFER_SRC) and dst is large enough.
        unsafe { self.ctx.device.cmd_copy_image_to_buffer(self.cb, src.raw, layout, dst.raw, &region) };
    }

    /// Discards `image`, clears it to `rgba` and hands it to compute shaders in
    /// GENERAL layout: barrier `discard_to_clear`, the clear, barrier
    /// `clear_to_compute` (the caller names both for what they protect).
    pub fn clear_for_compute(
        &mut self,
        image: &Image,
        rgba: [f32; 4],
        discard_to_clear: &'static str,
        clear_to_compute: &'static str,
    ) {
        self.barrier(&Barrier::image(
            discard_to_clear,
            image,
            self.discard_after,
            Access::CLEAR_WRITE,
            vk::ImageLayout::UNDEFINED,
            vk::ImageLayout::TRANSFER_DST_OPTIMAL,
        ));
        self.clear_color_image(image, rgba);
        self.barrier(&Barrier::image(
            clear_to_compute,
            image,
            Access::CLEAR_WRITE,
            Access::COMPUTE_READ_WRITE,
            vk::ImageLayout::TRANSFER_DST_OPTIMAL,
            vk::ImageLayout::GENERAL,
        ));
    }

    /// Hands images whose old contents do not matter to compute shaders: one
    /// image barrier each, UNDEFINED -> GENERAL, named `name` by the caller.
    pub fn discard_for_compute(&mut self, name: &'static str, images: &[&Image]) {
        for image in images {
            self.barrier(&Barrier::image(
                name,
                image,
                self.discard_after,
                Access::COMPUTE_READ_WRITE,
                vk::ImageLayout::UNDEFINED,
                vk::ImageLayout::GENERAL,
            ));
        }
    }

    /// Copies an image that compute shaders wrote (GENERAL) into a host-visible
    /// buffer: barrier `write_to_copy`, the copy, barrier `copy_to_host`. The
    /// image is left in TRANSFER_SRC_OPTIMAL (the frame is done with it).
    pub fn readback_image(
        &mut self,
        image: &Image,
        readback: &Buffer,
        write_to_copy: &'static str,
        copy_to_host: &'static str,
    ) {
        self.readback_image_then(image, readback, write_to_copy, None, copy_to_host);
    }

    /// Like `readback_image` for an image that stays in use: after the copy,
    /// barrier `copy_to_compute` returns it to GENERAL for compute shaders.
    pub fn readback_image_for_reuse(
        &mut self,
        image: &Image,
        readback: &Buffer,
        [write_to_copy, copy_to_compute, copy_to_host]: [&'static str; 3],
    ) {
        self.readback_image_then(image, readback, write_to_copy, Some(copy_to_compute), copy_to_host);
    }

    fn readback_image_then(
        &mut self,
        image: &Image,
        readback: &Buffer,
        write_to_copy: &'static str,
        copy_to_compute: Option<&'static str>,
        copy_to_host: &'static str,
    ) {
        let (general, source) = (vk::ImageLayout::GENERAL, vk::ImageLayout::TRANSFER_SRC_OPTIMAL);
        self.barrier(&Barrier::image(
            write_to_copy,
            image,
            Access::COMPUTE_WRITE,
            Access::TRANSFER_READ,
            general,
            source,
        ));
        self.copy_image_to_buffer(image, source, readback);
        if let Some(name) = copy_to_compute {
            self.barrier(&Barrier::image(
                name,
                image,
                Access::TRANSFER_READ,
                Access::COMPUTE_READ_WRITE,
                source,
                general,
            ));
        }
        self.barrier(&Barrier::memory(copy_to_host, Access::TRANSFER_WRITE, Access::HOST_READ));
    }

    /// Clears a colour image that is in TRANSFER_DST_OPTIMAL.
    pub fn clear_color_image(&self, image: &Image, rgba: [f32; 4]) {
        self.note_transfer();
        let value = vk::ClearColorValue { float32: rgba };
        let range = [super::resources::color_range()];
        // SAFETY: the image is in TRANSFER_DST_OPTIMAL (the caller's barrier) and
        // was created with TRANSFER_DST usage.
        unsafe {
            self.ctx.device.cmd_clear_color_image(
                self.cb,
                image.raw,
                vk::ImageLayout::TRANSFER_DST_OPTIMAL,
                &value,
                &range,
            )
        };
    }

    /// Copies the whole of `src` to the start of `dst` (at least as large).
    pub fn copy_buffer(&self, src: &Buffer, dst: &Buffer) {
        self.note_transfer();
        let region = [vk::BufferCopy::default().size(src.size.min(dst.size))];
        // SAFETY: src has TRANSFER_SRC and dst TRANSFER_DST usage; the region lies in both.
        unsafe { self.ctx.device.cmd_copy_buffer(self.cb, src.raw, dst.raw, &region) };
    }

    pub fn fill_buffer(&self, dst: &Buffer, value: u32) {
        self.note_transfer();
        // SAFETY: dst was created with TRANSFER_DST usage.
        unsafe { self.ctx.device.cmd_fill_buffer(self.cb, dst.raw, 0, vk::WHOLE_SIZE, value) };
    }
}

/// Records one primary command buffer with `record` (or several, where it calls
/// `Recorder::split_submission`), submits it and waits for it.
pub fn submit_and_wait<R>(
    ctx: &Context,
    name: &str,
    record: impl FnOnce(&mut Recorder) -> Result<R, VkError>,
) -> Result<R, VkError> {
    submit_and_wait_or(ctx, name, record)
}

/// [`submit_and_wait`] for a `record` with errors of its own (a technique's
/// frame, which prepares its resources as it records): on an error nothing is
/// submitted.
pub fn submit_and_wait_or<R, E: From<VkError>>(
    ctx: &Context,
    name: &str,
    record: impl FnOnce(&mut Recorder) -> Result<R, E>,
) -> Result<R, E> {
    let device = &ctx.device;
    let pool_info = vk::CommandPoolCreateInfo::default()
        .queue_family_index(ctx.queue_family)
        .flags(vk::CommandPoolCreateFlags::TRANSIENT);
    // SAFETY: valid device and queue family.
    let pool = unsafe { device.create_command_pool(&pool_info, None) }.call("vkCreateCommandPool")?;
    let mut guard = PoolGuard { device, pool, timeline: None };
    let cb = begin_command_buffer(ctx, pool, name)?;
    let mut rec = Recorder::fresh(ctx, cb, pool);
    rec.begin_label(name);
    let result = record(&mut rec);
    guard.timeline = rec.timeline;
    let result = result?;
    rec.check_limits()?;
    rec.end_label();
    // SAFETY: rec.cb is recording.
    unsafe { device.end_command_buffer(rec.cb) }.call("vkEndCommandBuffer")?;
    // SAFETY: valid device.
    let fence = unsafe { device.create_fence(&vk::FenceCreateInfo::default(), None) }.call("vkCreateFence")?;
    let submitted = match rec.timeline {
        Some(t) => submit_part(ctx, rec.cb, t, rec.submissions, fence),
        None => {
            let cbs = [vk::CommandBufferSubmitInfo::default().command_buffer(rec.cb)];
            let submit = [vk::SubmitInfo2::default().command_buffer_infos(&cbs)];
            // SAFETY: cb is executable; the queue is used from this thread only.
            unsafe { device.queue_submit2(ctx.queue, &submit, fence) }.call("vkQueueSubmit2")
        }
    };
    // SAFETY: we wait on the fence before the pool (and its command buffers) is destroyed.
    let report =
        WaitReport { name, elapsed: Duration::ZERO, dispatches: rec.dispatch_count, barriers: rec.barrier_count };
    if let Err(e) = submitted.and_then(|_| wait_for_fence(ctx, fence, report)) {
        // SAFETY: the submission failed or its wait did (the device is lost):
        // the fence is unused now. The guard destroys the pool.
        unsafe { device.destroy_fence(fence, None) };
        return Err(e.into());
    }
    // Not destroyed yet: the validation layer may still hold the frame's
    // command buffer (vk/finished_frame.rs).
    ctx.finished_frame.keep(guard.finish(fence));
    Ok(result)
}

fn begin_command_buffer(ctx: &Context, pool: vk::CommandPool, name: &str) -> Result<vk::CommandBuffer, VkError> {
    let alloc = vk::CommandBufferAllocateInfo::default()
        .command_pool(pool)
        .level(vk::CommandBufferLevel::PRIMARY)
        .command_buffer_count(1);
    // SAFETY: pool is valid and used from this thread only.
    let cb = unsafe { ctx.device.allocate_command_buffers(&alloc) }.call("vkAllocateCommandBuffers")?[0];
    ctx.set_name(cb, name);
    let begin = vk::CommandBufferBeginInfo::default().flags(vk::CommandBufferUsageFlags::ONE_TIME_SUBMIT);
    // SAFETY: cb is freshly allocated, in the initial state.
    unsafe { ctx.device.begin_command_buffer(cb, &begin) }.call("vkBeginCommandBuffer")?;
    Ok(cb)
}

/// Submits part `index` of a split frame: waits for timeline value `index` (none
/// for the first part) and signals `index + 1`.
fn submit_part(
    ctx: &Context,
    cb: vk::CommandBuffer,
    timeline: vk::Semaphore,
    index: u32,
    fence: vk::Fence,
) -> Result<(), VkError> {
    let waits = [vk::SemaphoreSubmitInfo::default()
        .semaphore(timeline)
        .value(index as u64)
        .stage_mask(vk::PipelineStageFlags2::ALL_COMMANDS)];
    let signals = [vk::SemaphoreSubmitInfo::default()
        .semaphore(timeline)
        .value(index as u64 + 1)
        .stage_mask(vk::PipelineStageFlags2::ALL_COMMANDS)];
    let cbs = [vk::CommandBufferSubmitInfo::default().command_buffer(cb)];
    let mut submit = vk::SubmitInfo2::default().command_buffer_infos(&cbs).signal_semaphore_infos(&signals);
    if index > 0 {
        submit = submit.wait_semaphore_infos(&waits);
    }
    // SAFETY: cb is executable; the queue is used from this thread only; the pool and
    // semaphore outlive the submission (the frame waits on its fence before both go).
    unsafe { ctx.device.queue_submit2(ctx.queue, &[submit], fence) }.call("vkQueueSubmit2")
}

struct PoolGuard<'a> {
    device: &'a ash::Device,
    pool: vk::CommandPool,
    timeline: Option<vk::Semaphore>,
}

impl PoolGuard<'_> {
    /// The frame's objects once `fence` has signalled, handed on undestroyed.
    fn finish(self, fence: vk::Fence) -> FinishedFrame {
        let frame = FinishedFrame { pool: self.pool, fence, timeline: self.timeline };
        // The guard owns nothing but these handles: forgetting it skips only
        // its destruction of them.
        std::mem::forget(self);
        frame
    }
}

impl Drop for PoolGuard<'_> {
    fn drop(&mut self) {
        // SAFETY: the pool's command buffers finished executing (or never ran): a
        // failed wait makes the device lost, where destruction is still allowed.
        unsafe {
            // A failed split leaves submitted parts in flight: wait for the queue first.
            if self.timeline.is_some() {
                let _ = self.device.device_wait_idle();
            }
            self.device.destroy_command_pool(self.pool, None);
            if let Some(t) = self.timeline {
                self.device.destroy_semaphore(t, None);
            }
        };
    }
}

/// Secondary command buffers recorded once and replayed by `Recorder::execute`.
pub struct SecondaryCommands {
    pool: vk::CommandPool,
    pub buffers: Vec<vk::CommandBuffer>,
    pub dispatches: Vec<u32>,
    pub barriers: Vec<u32>,
    device: ash::Device,
}

impl SecondaryCommands {
    /// Records `count` secondaries; `record(i, rec)` fills the i-th. A secondary
    /// inherits no state: it binds what it uses.
    pub fn record(
        ctx: &Context,
        name: &str,
        count: usize,
        mut record: impl FnMut(usize, &mut Recorder) -> Result<(), VkError>,
    ) -> Result<SecondaryCommands, VkError> {
        let device = &ctx.device;
        let pool_info = vk::CommandPoolCreateInfo::default().queue_family_index(ctx.queue_family);
        // SAFETY: valid device and queue family.
        let pool = unsafe { device.create_command_pool(&pool_info, None) }.call("vkCreateCommandPool")?;
        let mut out = SecondaryCommands {
            pool,
            buffers: Vec::new(),
            dispatches: Vec::new(),
            barriers: Vec::new(),
            device: device.clone(),
        };
        if count == 0 {
            return Ok(out);
        }
        let alloc = vk::CommandBufferAllocateInfo::default()
            .command_pool(pool)
            .level(vk::CommandBufferLevel::SECONDARY)
            .command_buffer_count(count as u32);
        // SAFETY: pool is valid; `out` frees the pool (and the buffers) on drop.
        out.buffers = unsafe { device.allocate_command_buffers(&alloc) }.call("vkAllocateCommandBuffers")?;
        for (i, &cb) in out.buffers.clone().iter().enumerate() {
            ctx.set_name(cb, &format!("{name} {i}"));
            let inheritance = vk::CommandBufferInheritanceInfo::default();
            let begin = vk::CommandBufferBeginInfo::default().inheritance_info(&inheritance);
            // SAFETY: cb is freshly allocated, in the initial state.
            unsafe { device.begin_command_buffer(cb, &begin) }.call("vkBeginCommandBuffer")?;
            let mut rec = Recorder::fresh(ctx, cb, pool);
            record(i, &mut rec)?;
            // SAFETY: cb is recording.
            unsafe { device.end_command_buffer(cb) }.call("vkEndCommandBuffer")?;
            out.dispatches.push(rec.dispatch_count);
            out.barriers.push(rec.barrier_count);
        }
        Ok(out)
    }
}

impl Drop for SecondaryCommands {
    fn drop(&mut self) {
        // Freed one by one before the pool goes: the Khronos validation layer
        // 1.3.239 (Debian 12's) forgets a secondary only when it is freed; one
        // destroyed with its pool stays in a process-wide list that every later
        // vkDestroyCommandPool scans (docs/testing.md).
        // SAFETY: dropped after the frames that executed the secondaries
        // completed; the buffers were allocated from this pool.
        unsafe {
            if !self.buffers.is_empty() {
                self.device.free_command_buffers(self.pool, &self.buffers);
            }
            self.device.destroy_command_pool(self.pool, None)
        };
    }
}
