//! One frame slot's submission: wait for its fence (and resolve its last
//! frame), acquire a swapchain image, record the technique's frame (or take
//! the frame shown last, for a panel-only redraw), the hand-off barrier and
//! the present pass into the slot's command buffer, submit once, present;
//! and the resolution of a finished slot's profile into the frame's record.

use super::error::ViewerError;
use super::frames::{FrameSlot, FramesInFlight, InFlight, Upload};
use super::present_pass::{
    self, PresentTarget, ACQUIRE_WAIT_STAGE, BLIT_SCOPE, BLIT_SOURCE_LAYOUT, UI_SCOPE, UPLOAD_SCOPE,
};
use super::preview::Preview;
use super::report::ViewerReport;
use super::ui::{PassHistory, Ui};
use crate::render::{FrameSession, GpuScene, OutputImage};
use crate::scene::Light;
use crate::techniques::{self, Technique};
use crate::vk::error::VkResultExt;
use crate::vk::{Buffer, Context, ProfileReport, Profiler, Recorder, Swapchain, VkError};
use ash::vk;
use gpu_allocator::MemoryLocation;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

/// What the technique's frame is made of.
pub(super) struct FrameSource<'a, 's> {
    pub gpu: &'a GpuScene<'s>,
    pub technique: Technique,
    pub lights: &'a [Option<Light>],
    /// Profiles a technique's frame rendered by its own submission (uploaded).
    pub host_profiler: &'a mut Profiler,
    /// The size the technique renders at: the image's, or a preview's.
    pub render: (u32, u32),
    /// The size the image takes on the window, right of the panel.
    pub shown: (u32, u32),
    /// Show this frame again instead of rendering one (only the panel changed).
    pub reshow: Option<Shown>,
}

/// A technique's frame as the blit left it: what a panel-only redraw shows again.
#[derive(Clone)]
pub(super) struct Shown {
    pub output: Arc<OutputImage>,
    pub layout: vk::ImageLayout,
}

/// What this frame is asked for besides presentation.
#[derive(Clone, Copy)]
pub(super) struct Wants {
    pub screenshot: bool,
    pub profile: bool,
}

/// How the present pass draws.
#[derive(Clone, Copy)]
pub(super) struct PresentStyle {
    /// The barrier between the technique's frame and the present pass (off:
    /// the test that proves it load-bearing).
    pub handoff_barrier: bool,
    /// The blit's filter where it stretches a preview.
    pub filter: vk::Filter,
}

/// A submitted and presented frame.
pub(super) struct Submitted {
    /// Whether to recreate the swapchain.
    pub recreate: bool,
    /// The screenshot's bytes, if asked for.
    pub pixels: Option<Vec<u8>>,
    /// Host time of the technique's frame (recording; for an uploaded frame
    /// also its submission, wait and read-back).
    pub render_ms: f64,
    pub dispatches: u32,
    pub barriers: u32,
    /// The profile of a frame rendered by its own submission and uploaded.
    pub uploaded_profile: Option<ProfileReport>,
    /// The frame recorded into the slot, to show again (none for an uploaded one).
    pub shown: Option<Shown>,
}

/// The viewer's measurements: the report, the panel's history, the preview
/// (which learns what frames cost), and where `P` writes.
pub struct FrameLog<'r> {
    pub report: &'r mut ViewerReport,
    pub history: PassHistory,
    pub out_dir: PathBuf,
    pub preview: Preview,
}

/// One frame slot: wait for its fence (and resolve its last frame), acquire;
/// record the technique's frame, the hand-off barrier and the present pass
/// into the slot's command buffer; one submission; present. A technique that
/// cannot record there renders by its own submission and is uploaded.
/// `None`: the swapchain was out of date before anything was recorded.
#[allow(clippy::too_many_arguments)]
pub(super) fn present(
    ctx: &Context,
    frames: &mut FramesInFlight,
    sc: &Swapchain,
    session: &mut dyn FrameSession,
    source: FrameSource,
    wants: Wants,
    style: PresentStyle,
    (ui, panel_px): (Option<&mut Ui>, u32),
    log: &mut FrameLog,
) -> Result<Option<Submitted>, ViewerError> {
    let device = &ctx.device;
    if session.reuses_gpu_resources() && source.reshow.is_none() {
        // Its resources (and host-written buffers) are the previous frame's.
        frames.wait_all()?;
    }
    let slot = frames.next_slot()?;
    resolve_slot(slot, log)?;
    let record_index = log.report.frames.len();
    let Some((image_index, suboptimal)) = sc.acquire(slot.image_acquired)? else {
        return Ok(None);
    };
    let (w, h) = (sc.extent.width, sc.extent.height);
    let shot = if wants.screenshot {
        Some(Buffer::staging(
            ctx,
            "screenshot readback",
            w as u64 * h as u64 * 4,
            vk::BufferUsageFlags::TRANSFER_DST,
            MemoryLocation::GpuToCpu,
        )?)
    } else {
        None
    };
    // SAFETY: the slot's fence was waited, so its command buffer is not pending.
    unsafe { device.reset_command_buffer(slot.cb, vk::CommandBufferResetFlags::empty()) }
        .call("vkResetCommandBuffer")?;
    let begin = vk::CommandBufferBeginInfo::default().flags(vk::CommandBufferUsageFlags::ONE_TIME_SUBMIT);
    // SAFETY: the command buffer was just reset.
    unsafe { device.begin_command_buffer(slot.cb, &begin) }.call("vkBeginCommandBuffer")?;
    slot.profiler.reset();
    let mut rec = Recorder::for_command_buffer(ctx, slot.cb);
    // The technique's images are kept: the frame before may still use them.
    rec.discard_after = source.gpu.frame_images.discard_after();
    let started = Instant::now();
    let (iw, ih) = source.render;
    let recorded = match &source.reshow {
        Some(_) => None,
        None => session.record(source.lights, &mut rec, iw, ih, &mut slot.profiler)?,
    };
    let mut reshown = None;
    let (frame, uploaded_profile, dispatches, barriers, linear_layout) = match (recorded, &source.reshow) {
        (_, Some(shown)) => {
            // Read again as the last blit read it: no write between the two.
            reshown = Some(shown.output.clone());
            (None, None, 0, 0, shown.layout)
        }
        (Some(frame), None) => {
            let layout = present_pass::record_handoff(&mut rec, &frame.output.image, style.handoff_barrier);
            let (d, b) = (frame.dispatches, frame.barriers);
            (Some(frame), None, d, b, layout)
        }
        (None, None) => {
            let output = techniques::profiled_frame(source.gpu, source.technique, iw, ih, source.host_profiler, |p| {
                session.frame(source.lights, iw, ih, p)
            })?;
            if slot.upload.as_ref().is_none_or(|u| (u.width, u.height) != (iw, ih)) {
                // The slot's last use of the old one finished (its fence).
                slot.upload = Some(Upload::new(ctx, iw, ih)?);
            }
            let upload = slot.upload.as_mut().ok_or_else(|| ViewerError::Window("no upload".into()))?;
            let rgba: Vec<[f32; 4]> = output.image.pixels.iter().map(|p| [p[0], p[1], p[2], 1.0]).collect();
            upload.staging.write(&rgba)?;
            present_pass::record_upload(&mut rec, &mut slot.profiler, &upload.staging, &upload.image)?;
            (None, Some(output.profile), output.dispatches, output.barriers, BLIT_SOURCE_LAYOUT)
        }
    };
    let render_ms = started.elapsed().as_secs_f64() * 1e3;
    let shown = frame.as_ref().map(|f| Shown { output: f.output.clone(), layout: linear_layout });
    let linear = match (&frame, &reshown, &slot.upload) {
        (Some(f), _, _) => &f.output.image,
        (None, Some(output), _) => &output.image,
        (None, None, Some(u)) => &u.image,
        (None, None, None) => return Err(ViewerError::Window("no frame to present".into())),
    };
    let i = image_index as usize;
    let target = PresentTarget { image: sc.images[i], view: sc.views[i], extent: sc.extent };
    let blit = present_pass::Blit {
        source: linear,
        layout: linear_layout,
        x: panel_px,
        shown: vk::Extent2D { width: source.shown.0, height: source.shown.1 },
        filter: style.filter,
    };
    present_pass::record(&mut rec, &mut slot.profiler, &blit, &target, shot.as_ref(), ui)?;
    // SAFETY: recording began above.
    unsafe { device.end_command_buffer(slot.cb) }.call("vkEndCommandBuffer")?;
    let waits = [vk::SemaphoreSubmitInfo::default().semaphore(slot.image_acquired).stage_mask(ACQUIRE_WAIT_STAGE)];
    let signals = [vk::SemaphoreSubmitInfo::default()
        .semaphore(sc.ready_to_present[image_index as usize])
        .stage_mask(vk::PipelineStageFlags2::ALL_COMMANDS)];
    let cbs = [vk::CommandBufferSubmitInfo::default().command_buffer(slot.cb)];
    let submit = vk::SubmitInfo2::default()
        .wait_semaphore_infos(&waits)
        .command_buffer_infos(&cbs)
        .signal_semaphore_infos(&signals);
    // SAFETY: the fence is signalled with no pending work (waited above); the
    // command buffer is executable; the queue is used from this thread only.
    unsafe {
        device.reset_fences(&[slot.done]).call("vkResetFences")?;
        device.queue_submit2(ctx.queue, &[submit], slot.done).call("vkQueueSubmit2")?;
    }
    slot.in_flight = Some(InFlight { record: record_index, frame, reshown, write_profile: wants.profile });
    let stale = sc.present(image_index)?;
    let pixels = match &shot {
        Some(buffer) => {
            // SAFETY: the fence belongs to this device; only this frame waits on it.
            unsafe { device.wait_for_fences(&[slot.done], true, u64::MAX) }.call("vkWaitForFences")?;
            Some(buffer.read::<u8>(w as usize * h as usize * 4)?)
        }
        None => None,
    };
    Ok(Some(Submitted {
        recreate: suboptimal || stale,
        pixels,
        render_ms,
        dispatches,
        barriers,
        uploaded_profile,
        shown,
    }))
}

/// Completes the record of the slot's last frame from its profile (its fence
/// was waited): the technique's passes and GPU time where it was recorded into
/// the slot, the present pass and the panel; writes its profile for `P`.
pub(super) fn resolve_slot(slot: &mut FrameSlot, log: &mut FrameLog) -> Result<(), ViewerError> {
    let Some(done) = slot.in_flight.take() else {
        return Ok(());
    };
    let profile = slot.profiler.resolve(0)?;
    let Some(record) = log.report.frames.get_mut(done.record) else {
        return Ok(());
    };
    let viewer_scope = |name: &str| [UPLOAD_SCOPE, BLIT_SCOPE, UI_SCOPE].contains(&name);
    if done.frame.is_some() {
        record.gpu_ms = profile
            .scopes
            .iter()
            .filter(|s| s.parent.is_none() && !viewer_scope(&s.name))
            .map(|s| s.duration_ns * 1e-6)
            .sum();
    }
    let pass_ms: Vec<(String, f64)> = match done.frame {
        Some(_) => {
            profile.passes.iter().filter(|p| !viewer_scope(&p.name)).map(|p| (p.path.clone(), p.gpu_ms)).collect()
        }
        None => Vec::new(),
    };
    record.passes.extend(profile.passes.iter().map(|p| p.path.clone()));
    record.present_gpu_ms = Some(profile.pass_ms(BLIT_SCOPE));
    record.ui_gpu_ms = profile.passes.iter().any(|s| s.name == UI_SCOPE).then(|| profile.pass_ms(UI_SCOPE));
    if !pass_ms.is_empty() {
        log.history.push(record, &pass_ms);
    }
    if !record.reshown {
        log.preview.measured(record.preview_scale, record.gpu_ms);
    }
    if done.write_profile {
        write_profile(&log.out_dir, record.index, &profile)?;
    }
    Ok(())
}

/// Resolves every slot (once all fences are waited: at the end).
pub(super) fn resolve_all(frames: &mut FramesInFlight, log: &mut FrameLog) -> Result<(), ViewerError> {
    frames.wait_all()?;
    for slot in &mut frames.slots {
        resolve_slot(slot, log)?;
    }
    Ok(())
}

/// Resolves the slots whose submission has finished, without waiting: an
/// idle viewer shows the last frame's figures in its panel.
pub(super) fn resolve_finished(
    ctx: &Context,
    frames: &mut FramesInFlight,
    log: &mut FrameLog,
) -> Result<(), ViewerError> {
    for slot in &mut frames.slots {
        // SAFETY: the fence belongs to this device.
        let done = unsafe { ctx.device.get_fence_status(slot.done) }.call("vkGetFenceStatus")?;
        if done {
            resolve_slot(slot, log)?;
        }
    }
    Ok(())
}

/// Waits for the queue when dropped (errors are left to the next call).
pub(super) struct QueueIdleOnDrop<'c>(pub &'c Context);

impl Drop for QueueIdleOnDrop<'_> {
    fn drop(&mut self) {
        let _ = queue_idle(self.0);
    }
}

pub(super) fn queue_idle(ctx: &Context) -> Result<(), VkError> {
    // SAFETY: the queue is used from this thread only.
    unsafe { ctx.device.queue_wait_idle(ctx.queue) }.call("vkQueueWaitIdle")
}

pub(super) fn write_png(path: &Path, bytes: &[u8], w: u32, h: u32, format: vk::Format) -> Result<(), ViewerError> {
    let bgra = matches!(format, vk::Format::B8G8R8A8_SRGB | vk::Format::B8G8R8A8_UNORM);
    let rgb: Vec<u8> =
        bytes.chunks_exact(4).flat_map(|p| if bgra { [p[2], p[1], p[0]] } else { [p[0], p[1], p[2]] }).collect();
    let image = image::RgbImage::from_raw(w, h, rgb)
        .ok_or_else(|| ViewerError::Write { path: path.display().to_string(), message: "short readback".into() })?;
    image.save(path).map_err(|e| ViewerError::Write { path: path.display().to_string(), message: e.to_string() })
}

fn write_profile(dir: &Path, frame: u64, profile: &ProfileReport) -> Result<(), ViewerError> {
    for (name, value) in [
        (format!("sweeplab-view-{frame}-profile.json"), profile.to_json()),
        (format!("sweeplab-view-{frame}-trace.json"), profile.chrome_trace()),
    ] {
        let path = dir.join(name);
        let text = serde_json::to_string_pretty(&value).unwrap_or_default();
        std::fs::write(&path, text)
            .map_err(|e| ViewerError::Write { path: path.display().to_string(), message: e.to_string() })?;
        eprintln!("wrote {}", path.display());
    }
    Ok(())
}
