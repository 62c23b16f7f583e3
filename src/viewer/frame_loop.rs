//! The frame loop: events, script steps and mouse edits; then a frame slot:
//! wait for its fence, acquire a swapchain image, record the technique's frame
//! (the same recording as `render`), the hand-off barrier and the present pass
//! into the slot's command buffer, submit once, present.
//! The swapchain is recreated when the window's size changes or presentation
//! reports it out of date or suboptimal; a minimized window renders nothing.

use super::controls;
use super::error::ViewerError;
use super::frames::{FrameSlot, FramesInFlight, InFlight, Upload, FRAMES_IN_FLIGHT, PROFILER_CAPACITY};
use super::live_scene::{Change, LiveScene, SceneSource};
use super::present_pass::{
    self, PresentTarget, ACQUIRE_WAIT_STAGE, BLIT_SCOPE, BLIT_SOURCE_LAYOUT, UI_SCOPE, UPLOAD_SCOPE,
};
use super::report::{FrameRecord, ViewerReport};
use super::script::{Action, Script};
use super::tf_editor;
use super::ui::{PanelView, PassHistory, Ui, UiEdit, PANEL_WIDTH};
use super::window::{self, WindowEvents};
use crate::render::{FrameImages, FrameSession, GpuScene, UploadedVolume, VolumeTexels};
use crate::scene::Light;
use crate::techniques::{self, Technique};
use crate::vk::error::VkResultExt;
use crate::vk::swapchain::present_mode_name;
use crate::vk::{Buffer, Context, ContextOptions, ProfileReport, Profiler, Recorder, Surface, Swapchain, VkError};
use ash::vk;
use gpu_allocator::MemoryLocation;
use std::ffi::CStr;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};
use winit::dpi::PhysicalSize;
use winit::event_loop::EventLoop;
use winit::keyboard::KeyCode;

#[derive(Clone, Debug)]
pub struct ViewerOptions {
    pub technique: Technique,
    pub context: ContextOptions,
    pub texels: VolumeTexels,
    pub present_mode: vk::PresentModeKHR,
    /// Stop after this many presented frames.
    pub frames: Option<u64>,
    /// Write the last presented image here (with `frames`).
    pub screenshot: Option<PathBuf>,
    pub script: Script,
    /// Where `S` (screenshot) and `P` (profile and trace) write.
    pub out_dir: PathBuf,
    /// The control panel (off: the frame alone, e.g. to compare screenshots).
    pub ui: bool,
    /// Start with the panel hidden (`H` or Tab shows it); the image takes the
    /// whole window.
    pub hide_panel: bool,
    /// The barrier between the technique's frame and the present pass; off
    /// only to prove that validation reports its absence (a test).
    pub handoff_barrier: bool,
}

/// Opens the window and runs frames until it is closed or `frames` are done.
/// Returns the per-frame report and the validation messages.
pub fn run(
    source: SceneSource,
    overrides: &[String],
    options: &ViewerOptions,
) -> Result<(ViewerReport, Vec<String>), ViewerError> {
    let mut live = LiveScene::load(source, overrides)?;
    let mut event_loop = window::event_loop()?;
    let (width, height) = (live.scene.render.width, live.scene.render.height);
    // The image beside the panel at the scene's size: the window holds both.
    let panel = if options.ui && !options.hide_panel { PANEL_WIDTH as u32 } else { 0 };
    // Declared before the context: the window outlives the surface made from it.
    let mut events = WindowEvents::new(&format!("sweeplab view: {}", options.technique), width + panel, height);
    events.open(&mut event_loop)?;
    let (display, _) = events.handles()?;
    let names =
        ash_window::enumerate_required_extensions(display).call("vkEnumerateInstanceExtensionProperties (surface)")?;
    // SAFETY: ash_window returns pointers to static NUL-terminated extension names.
    let names: Vec<&CStr> = names.iter().map(|&p| unsafe { CStr::from_ptr(p) }).collect();
    let ctx = Context::for_window(&options.context.clone().with_env(), &names)?;
    eprintln!("{}", ctx.summary());
    let report = frames_on(&ctx, &mut live, &mut event_loop, &mut events, options)?;
    Ok((report, ctx.take_validation_messages()))
}

fn frames_on(
    ctx: &Context,
    live: &mut LiveScene,
    event_loop: &mut EventLoop<()>,
    events: &mut WindowEvents,
    options: &ViewerOptions,
) -> Result<ViewerReport, ViewerError> {
    let (display, window) = events.handles()?;
    let surface = Surface::new(ctx, display, window)?;
    let mut frames = FramesInFlight::new(ctx)?;
    let mut swapchain: Option<Swapchain> = None;
    let mut ui: Option<Ui> = None;
    let mut report = ViewerReport {
        technique: options.technique.to_string(),
        device: ctx.info.name.clone(),
        present_mode: present_mode_name(options.present_mode),
        ..Default::default()
    };
    let mut log = FrameLog { report: &mut report, history: PassHistory::default(), out_dir: options.out_dir.clone() };
    let result =
        frame_loop(ctx, &surface, &mut frames, &mut swapchain, &mut ui, live, event_loop, events, options, &mut log);
    // Fences cover the submissions; presents are covered by nothing but the
    // queue, so it is waited for once here before the swapchain goes.
    let waited = frames.wait_all().and_then(|_| queue_idle(ctx));
    result?;
    waited?;
    resolve_all(&mut frames, &mut log)?;
    events.egui = None;
    drop(ui);
    drop(swapchain);
    Ok(report)
}

#[allow(clippy::too_many_arguments)]
fn frame_loop<'c>(
    ctx: &'c Context,
    surface: &Surface<'c>,
    frames: &mut FramesInFlight<'c>,
    swapchain: &mut Option<Swapchain<'c>>,
    ui: &mut Option<Ui>,
    live: &mut LiveScene,
    event_loop: &mut EventLoop<()>,
    events: &mut WindowEvents,
    options: &ViewerOptions,
    log: &mut FrameLog,
) -> Result<(), ViewerError> {
    let mut host_profiler = Profiler::new(ctx, PROFILER_CAPACITY)?;
    let mut frame_index = 0u64;
    let mut script_done_for: Option<u64> = None;
    let mut recreate = true;
    let mut last_present = Instant::now();
    let mut technique = options.technique;
    let mut panel_shown = !options.hide_panel;
    let mut enabled: Vec<bool> = vec![true; live.scene.lights.len()];
    let mut ui_edits: Vec<UiEdit> = Vec::new();
    let mut message: Option<String> = None;
    // The light Ctrl and the left button drag (chosen in the panel).
    let mut selected_light = 0usize;
    // The volume is loaded once and kept across edits.
    let histogram = live.scene.volume.histogram(tf_editor::HISTOGRAM_BINS);
    // What the context created between two frame records.
    let mut counted = ctx.creation_counts();
    // Uploaded once: every edit keeps the volume (`LiveScene`). The frames'
    // images are kept across frames and edits, re-created where their size
    // or format changes (a resize, a setting).
    let volume = UploadedVolume::upload(ctx, &live.scene, options.texels)?;
    let frame_images = FrameImages::kept();
    'scene: loop {
        enabled.resize(live.scene.lights.len(), true);
        // Switched-off lights are left out of the uploaded scene.
        let mut scene = live.scene.clone();
        scene.lights = scene.lights.iter().zip(&enabled).filter(|(_, &on)| on).map(|(l, _)| *l).collect();
        let gpu = GpuScene::on_volume(ctx, &scene, &volume, frame_images.clone())?;
        let mut session = techniques::session(&gpu, technique)?;
        // Dropped first when the scene is left (edited, closed, or an error):
        // frames in flight use the scene's and the session's resources.
        let _in_flight_done = QueueIdleOnDrop(ctx);
        loop {
            if !events.pump(event_loop, Duration::ZERO)? || events.close_requested {
                break 'scene;
            }
            if options.frames.is_some_and(|n| frame_index >= n) {
                break 'scene;
            }
            let mut keys: Vec<char> = events
                .keys
                .drain(..)
                .filter_map(|k| match k {
                    KeyCode::KeyS => Some('S'),
                    KeyCode::KeyP => Some('P'),
                    KeyCode::KeyH | KeyCode::Tab => Some('H'),
                    _ => None,
                })
                .collect();
            let mut rebuild = false;
            if script_done_for != Some(frame_index) {
                script_done_for = Some(frame_index);
                for action in options.script.at(frame_index) {
                    match action {
                        Action::Set(edit) => {
                            let change = live.set(edit)?;
                            rebuild |= change == Change::Scene || !session.follows_lights();
                        }
                        Action::Resize(w, h) => resize_window(event_loop, events, *w, *h)?,
                        Action::Key(c) => keys.push(*c),
                        Action::TfPoint { index, value, alpha } => {
                            let points = &live.scene.transfer.points;
                            let moved = tf_editor::move_point(points, *index, *value, *alpha).ok_or_else(|| {
                                ViewerError::Script(format!(
                                    "frame {frame_index}: tf-point {index}: the transfer function has {} points",
                                    points.len()
                                ))
                            })?;
                            live.set(&tf_editor::set_edit(&moved))?;
                            rebuild = true;
                        }
                        Action::DragLight { index, dx, dy } => {
                            if !drag_light(live, *index, (*dx, *dy), events.size()?.1) {
                                let n = live.scene.lights.len();
                                let m = format!("frame {frame_index}: drag-light {index}: the scene has {n} lights");
                                return Err(ViewerError::Script(m));
                            }
                            rebuild |= !session.follows_lights();
                        }
                        // As the mouse would: through `mouse_camera` below.
                        Action::Orbit(dx, dy) => {
                            events.orbit = (events.orbit.0 + *dx as f64, events.orbit.1 + *dy as f64);
                        }
                        Action::Zoom(lines) => events.zoom += lines,
                    }
                }
            }
            for edit in ui_edits.drain(..) {
                match edit {
                    UiEdit::Technique(t) => {
                        technique = t;
                        // The old technique's images would only take memory.
                        frame_images.release_all();
                        rebuild = true;
                    }
                    UiEdit::Set(set) => match live.set(&set) {
                        Ok(change) => rebuild |= change == Change::Scene || !session.follows_lights(),
                        // The panel offers valid values only; say so rather than stop.
                        Err(e) => message = Some(e.to_string()),
                    },
                    UiEdit::Lights(lights) => {
                        live.set_lights(lights);
                        rebuild |= !session.follows_lights();
                    }
                    UiEdit::Toggle(i, on) => {
                        if let Some(e) = enabled.get_mut(i) {
                            *e = on;
                        }
                        rebuild |= !session.follows_lights();
                    }
                    UiEdit::Key(c) => keys.push(c),
                    UiEdit::SelectLight(i) => selected_light = i,
                }
            }
            let (dx, dy) = std::mem::take(&mut events.light_drag);
            if (dx, dy) != (0.0, 0.0) && drag_light(live, selected_light, (dx as f32, dy as f32), events.size()?.1) {
                rebuild |= !session.follows_lights();
            }
            enabled.resize(live.scene.lights.len(), true);
            if let Some(camera) = mouse_camera(live, events) {
                live.set_camera(camera);
                rebuild = true;
            }
            if rebuild {
                continue 'scene;
            }
            let (ww, wh) = events.size()?;
            if ww == 0 || wh == 0 {
                // Minimized: nothing to present to; wait for events instead.
                events.pump(event_loop, Duration::from_millis(50))?;
                continue;
            }
            let recreated = recreate
                || events.resized
                || swapchain.as_ref().is_none_or(|s| (s.extent.width, s.extent.height) != (ww, wh));
            if recreated {
                frames.wait_all()?;
                // Presents of the old swapchain hold its semaphores; the queue
                // is waited for here only, never in a frame.
                queue_idle(ctx)?;
                resolve_all(frames, log)?;
                let next = Swapchain::new(
                    surface,
                    vk::Extent2D { width: ww, height: wh },
                    options.present_mode,
                    swapchain.as_ref(),
                )?;
                if options.ui && ui.is_none() {
                    let panel = Ui::new(ctx, next.format, FRAMES_IN_FLIGHT)?;
                    let window = events.window()?;
                    let state = egui_winit::State::new(
                        panel.egui.clone(),
                        egui::ViewportId::ROOT,
                        window,
                        Some(window.scale_factor() as f32),
                        None,
                        None,
                    );
                    events.egui = Some(state);
                    *ui = Some(panel);
                }
                *swapchain = Some(next);
                recreate = false;
                events.resized = false;
            }
            let sc = swapchain.as_ref().ok_or_else(|| ViewerError::Window("no swapchain".into()))?;
            let (w, h) = (sc.extent.width, sc.extent.height);
            if w == 0 || h == 0 {
                continue;
            }

            let lights: Vec<Option<Light>> =
                live.scene.lights.iter().zip(&enabled).map(|(l, &on)| on.then_some(*l)).collect();
            technique.check(gpu.scene)?;
            if keys.contains(&'H') {
                panel_shown = !panel_shown;
            }
            // The panel's width in window pixels; the image is drawn beside it.
            let panel_px = match ui.is_some() && panel_shown {
                true => ((PANEL_WIDTH as f64 * events.window()?.scale_factor()).round() as u32).min(w - 1),
                false => 0,
            };
            if let (Some(panel), Some(state), true) = (ui.as_mut(), events.egui.as_mut(), panel_shown) {
                if panel.has_pending_frees() {
                    // Textures egui let go of may be in a frame in flight.
                    frames.wait_all()?;
                    panel.free_textures()?;
                }
                let window = events.window.as_ref().ok_or_else(|| ViewerError::Window("no window".into()))?;
                let input = state.take_egui_input(window);
                let frames_so_far = &log.report.frames;
                let view = PanelView {
                    technique,
                    scene: &live.scene,
                    enabled: &enabled,
                    // The last frame whose profile is in (its fence was waited).
                    last: frames_so_far.iter().rev().find(|f| f.present_gpu_ms.is_some()),
                    history: &log.history,
                    ui_cpu_ms: panel.cpu_ms,
                    ui_gpu_ms: frames_so_far.iter().rev().find_map(|f| f.ui_gpu_ms),
                    message: message.as_deref(),
                    histogram: &histogram,
                    selected_light,
                };
                let (edits, platform) = panel.build(input, &view)?;
                if panel.has_pending_uploads() {
                    // The font atlas is written in place: the other frame in
                    // flight may still sample it (rare: the first frames and
                    // new glyphs).
                    frames.wait_all()?;
                    panel.upload_textures()?;
                }
                state.handle_platform_output(window, platform);
                ui_edits = edits;
            }

            let last = options.frames.is_some_and(|n| frame_index + 1 == n);
            let mut shots: Vec<PathBuf> = Vec::new();
            if last {
                shots.extend(options.screenshot.clone());
            }
            if keys.contains(&'S') {
                shots.push(options.out_dir.join(format!("sweeplab-view-{frame_index}.png")));
            }
            let source = FrameSource { gpu: &gpu, technique, lights: &lights, host_profiler: &mut host_profiler };
            let wants = Wants { screenshot: !shots.is_empty(), profile: keys.contains(&'P') };
            let shown_ui = ui.as_mut().filter(|_| panel_shown);
            let presented =
                present(ctx, frames, sc, session.as_mut(), source, wants, options, (shown_ui, panel_px), log)?;
            let Some(submitted) = presented else {
                recreate = true;
                continue;
            };
            recreate |= submitted.recreate;
            let now = Instant::now();
            let counts = ctx.creation_counts();
            let created = counts.since(&counted);
            counted = counts;
            let technique_profile = submitted.uploaded_profile.as_ref();
            log.report.frames.push(FrameRecord {
                index: frame_index,
                width: w,
                height: h,
                frame_ms: (now - last_present).as_secs_f64() * 1e3,
                render_ms: submitted.render_ms,
                gpu_ms: technique_profile.map_or(0.0, |p| p.gpu_ms_total),
                present_gpu_ms: None,
                ui_gpu_ms: None,
                ui_cpu_ms: ui.as_ref().map_or(0.0, |u| u.cpu_ms),
                dispatches: submitted.dispatches,
                barriers: submitted.barriers,
                passes: technique_profile.map_or(Vec::new(), |p| p.passes.iter().map(|p| p.path.clone()).collect()),
                secondaries_recorded: session.secondaries_recorded(),
                decision: session.last_decision(),
                swapchain_recreated: recreated,
                created,
            });
            last_present = now;
            if let Some(pixels) = submitted.pixels {
                for path in &shots {
                    write_png(path, &pixels, w, h, sc.format)?;
                    log.report.screenshots.push(path.display().to_string());
                }
            }
            frame_index += 1;
        }
    }
    Ok(())
}

/// Drags light `index` of the live scene by `delta` pixels in a window
/// `height` pixels high; false if there is no such light.
fn drag_light(live: &mut LiveScene, index: usize, delta: (f32, f32), height: u32) -> bool {
    let mut lights = live.scene.lights.clone();
    let Some(light) = lights.get_mut(index) else {
        return false;
    };
    *light = controls::drag_light(*light, live.scene.camera, delta.0, delta.1, height);
    live.set_lights(lights);
    true
}

/// The camera after the mouse's drags and wheel since the last frame, if any.
fn mouse_camera(live: &LiveScene, events: &mut WindowEvents) -> Option<crate::scene::Camera> {
    let (orbit, pan, zoom) = (events.orbit, events.pan, events.zoom);
    if orbit == (0.0, 0.0) && pan == (0.0, 0.0) && zoom == 0.0 {
        return None;
    }
    events.orbit = (0.0, 0.0);
    events.pan = (0.0, 0.0);
    events.zoom = 0.0;
    let height = events.size().map(|s| s.1).unwrap_or(1);
    let mut c = live.scene.camera;
    c = controls::orbit(c, orbit.0 as f32, orbit.1 as f32);
    c = controls::pan(c, pan.0 as f32, pan.1 as f32, height);
    c = controls::zoom(c, zoom);
    Some(c)
}

/// Asks for a new window size and pumps until the window has it (or a second passed).
fn resize_window(event_loop: &mut EventLoop<()>, events: &mut WindowEvents, w: u32, h: u32) -> Result<(), ViewerError> {
    let _ = events.window()?.request_inner_size(PhysicalSize::new(w, h));
    for _ in 0..100 {
        if events.size()? == (w, h) {
            return Ok(());
        }
        events.pump(event_loop, Duration::from_millis(10))?;
    }
    Err(ViewerError::Window(format!("the window did not take the size {w}x{h}")))
}

/// What the technique's frame is made of.
struct FrameSource<'a, 's> {
    gpu: &'a GpuScene<'s>,
    technique: Technique,
    lights: &'a [Option<Light>],
    /// Profiles a technique's frame rendered by its own submission (uploaded).
    host_profiler: &'a mut Profiler,
}

/// What this frame is asked for besides presentation.
#[derive(Clone, Copy)]
struct Wants {
    screenshot: bool,
    profile: bool,
}

/// A submitted and presented frame.
struct Submitted {
    /// Whether to recreate the swapchain.
    recreate: bool,
    /// The screenshot's bytes, if asked for.
    pixels: Option<Vec<u8>>,
    /// Host time of the technique's frame (recording; for an uploaded frame
    /// also its submission, wait and read-back).
    render_ms: f64,
    dispatches: u32,
    barriers: u32,
    /// The profile of a frame rendered by its own submission and uploaded.
    uploaded_profile: Option<ProfileReport>,
}

/// The viewer's measurements: the report, the panel's history, and where `P`
/// writes.
pub struct FrameLog<'r> {
    pub report: &'r mut ViewerReport,
    pub history: PassHistory,
    pub out_dir: PathBuf,
}

/// One frame slot: wait for its fence (and resolve its last frame), acquire;
/// record the technique's frame, the hand-off barrier and the present pass
/// into the slot's command buffer; one submission; present. A technique that
/// cannot record there renders by its own submission and is uploaded.
/// `None`: the swapchain was out of date before anything was recorded.
#[allow(clippy::too_many_arguments)]
fn present(
    ctx: &Context,
    frames: &mut FramesInFlight,
    sc: &Swapchain,
    session: &mut dyn FrameSession,
    source: FrameSource,
    wants: Wants,
    options: &ViewerOptions,
    (ui, panel_px): (Option<&mut Ui>, u32),
    log: &mut FrameLog,
) -> Result<Option<Submitted>, ViewerError> {
    let device = &ctx.device;
    if session.reuses_gpu_resources() {
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
    // The technique renders the area beside the panel; the screenshot is the window.
    let (iw, ih) = (w - panel_px, h);
    let recorded = session.record(source.lights, &mut rec, iw, ih, &mut slot.profiler)?;
    let (frame, uploaded_profile, dispatches, barriers, linear_layout) = match recorded {
        Some(frame) => {
            let layout = present_pass::record_handoff(&mut rec, &frame.output.image, options.handoff_barrier);
            let (d, b) = (frame.dispatches, frame.barriers);
            (Some(frame), None, d, b, layout)
        }
        None => {
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
    let linear = match (&frame, &slot.upload) {
        (Some(f), _) => &f.output.image,
        (None, Some(u)) => &u.image,
        (None, None) => return Err(ViewerError::Window("no frame to present".into())),
    };
    let i = image_index as usize;
    let target = PresentTarget { image: sc.images[i], view: sc.views[i], extent: sc.extent };
    present_pass::record(&mut rec, &mut slot.profiler, (linear, linear_layout, panel_px), &target, shot.as_ref(), ui)?;
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
    slot.in_flight = Some(InFlight { record: record_index, frame, write_profile: wants.profile });
    let stale = sc.present(image_index)?;
    let pixels = match &shot {
        Some(buffer) => {
            // SAFETY: the fence belongs to this device; only this frame waits on it.
            unsafe { device.wait_for_fences(&[slot.done], true, u64::MAX) }.call("vkWaitForFences")?;
            Some(buffer.read::<u8>(w as usize * h as usize * 4)?)
        }
        None => None,
    };
    Ok(Some(Submitted { recreate: suboptimal || stale, pixels, render_ms, dispatches, barriers, uploaded_profile }))
}

/// Completes the record of the slot's last frame from its profile (its fence
/// was waited): the technique's passes and GPU time where it was recorded into
/// the slot, the present pass and the panel; writes its profile for `P`.
fn resolve_slot(slot: &mut FrameSlot, log: &mut FrameLog) -> Result<(), ViewerError> {
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
    if done.write_profile {
        write_profile(&log.out_dir, record.index, &profile)?;
    }
    Ok(())
}

/// Resolves every slot (once all fences are waited: at the end).
fn resolve_all(frames: &mut FramesInFlight, log: &mut FrameLog) -> Result<(), ViewerError> {
    frames.wait_all()?;
    for slot in &mut frames.slots {
        resolve_slot(slot, log)?;
    }
    Ok(())
}

/// Waits for the queue when dropped (errors are left to the next call).
struct QueueIdleOnDrop<'c>(&'c Context);

impl Drop for QueueIdleOnDrop<'_> {
    fn drop(&mut self) {
        let _ = queue_idle(self.0);
    }
}

fn queue_idle(ctx: &Context) -> Result<(), VkError> {
    // SAFETY: the queue is used from this thread only.
    unsafe { ctx.device.queue_wait_idle(ctx.queue) }.call("vkQueueWaitIdle")
}

fn write_png(path: &Path, bytes: &[u8], w: u32, h: u32, format: vk::Format) -> Result<(), ViewerError> {
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
