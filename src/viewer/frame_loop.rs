//! The frame loop: events, script steps and mouse edits; the technique's frame
//! (through the same code as `render`); then a frame slot: wait for its fence,
//! acquire a swapchain image, record and submit the present pass, present.
//! The swapchain is recreated when the window's size changes or presentation
//! reports it out of date or suboptimal; a minimized window renders nothing.

use super::controls;
use super::error::ViewerError;
use super::frames::{FramesInFlight, Upload, FRAMES_IN_FLIGHT};
use super::live_scene::{Change, LiveScene, SceneSource};
use super::present_pass::{self, PresentTarget, ACQUIRE_WAIT_STAGE};
use super::report::{FrameRecord, ViewerReport};
use super::script::{Action, Script};
use super::ui::{PanelView, PassHistory, Ui, UiEdit};
use super::window::{self, WindowEvents};
use crate::render::{self, GpuScene, RenderOutput, Technique, VolumeTexels};
use crate::scene::Light;
use crate::vk::error::VkResultExt;
use crate::vk::swapchain::present_mode_name;
use crate::vk::{Buffer, Context, ContextOptions, Profiler, Recorder, Surface, Swapchain, VkError};
use ash::vk;
use gpu_allocator::MemoryLocation;
use std::ffi::CStr;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};
use winit::dpi::PhysicalSize;
use winit::event_loop::EventLoop;
use winit::keyboard::KeyCode;

/// Scopes per frame the technique's profiler holds.
const PROFILER_CAPACITY: u32 = 16_384;

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
    // Declared before the context: the window outlives the surface made from it.
    let mut events = WindowEvents::new(&format!("sweeplab view: {}", options.technique), width, height);
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
    let result =
        frame_loop(ctx, &surface, &mut frames, &mut swapchain, &mut ui, live, event_loop, events, options, &mut report);
    // Fences cover the submissions; presents are covered by nothing but the
    // queue, so it is waited for once here before the swapchain goes.
    let waited = frames.wait_all().and_then(|_| queue_idle(ctx));
    result?;
    waited?;
    resolve_present_profiles(&mut frames, &mut report)?;
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
    report: &mut ViewerReport,
) -> Result<(), ViewerError> {
    let mut profiler = Profiler::new(ctx, PROFILER_CAPACITY)?;
    let mut frame_index = 0u64;
    let mut script_done_for: Option<u64> = None;
    let mut recreate = true;
    let mut last_present = Instant::now();
    let mut technique = options.technique;
    let mut enabled: Vec<bool> = vec![true; live.scene.lights.len()];
    let mut ui_edits: Vec<UiEdit> = Vec::new();
    let mut message: Option<String> = None;
    let mut history = PassHistory::default();
    'scene: loop {
        enabled.resize(live.scene.lights.len(), true);
        // Switched-off lights are left out of the uploaded scene.
        let mut scene = live.scene.clone();
        scene.lights = scene.lights.iter().zip(&enabled).filter(|(_, &on)| on).map(|(l, _)| *l).collect();
        let gpu = GpuScene::upload_with(ctx, &scene, options.texels)?;
        let mut session = render::session(&gpu, technique)?;
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
                    }
                }
            }
            for edit in ui_edits.drain(..) {
                match edit {
                    UiEdit::Technique(t) => {
                        technique = t;
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
                }
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
                resolve_present_profiles(frames, report)?;
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
            let started = Instant::now();
            let output =
                render::profiled_frame(&gpu, technique, w, h, &mut profiler, |p| session.frame(&lights, w, h, p))?;
            let render_ms = started.elapsed().as_secs_f64() * 1e3;
            if let (Some(panel), Some(state)) = (ui.as_mut(), events.egui.as_mut()) {
                if panel.has_pending_frees() {
                    // Textures egui let go of may be in a frame in flight.
                    frames.wait_all()?;
                    panel.free_textures()?;
                }
                let window = events.window.as_ref().ok_or_else(|| ViewerError::Window("no window".into()))?;
                let input = state.take_egui_input(window);
                let last = report.frames.last();
                let view = PanelView {
                    technique,
                    scene: &live.scene,
                    enabled: &enabled,
                    last,
                    history: &history,
                    ui_cpu_ms: panel.cpu_ms,
                    ui_gpu_ms: report.frames.iter().rev().find_map(|f| f.ui_gpu_ms),
                    message: message.as_deref(),
                };
                let (edits, platform) = panel.build(input, &view)?;
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
            let presented = present(ctx, frames, sc, &output, !shots.is_empty(), ui.as_mut(), report)?;
            let Some((should_recreate, screenshot)) = presented else {
                recreate = true;
                continue;
            };
            recreate |= should_recreate;
            let now = Instant::now();
            report.frames.push(FrameRecord {
                index: frame_index,
                width: w,
                height: h,
                frame_ms: (now - last_present).as_secs_f64() * 1e3,
                render_ms,
                gpu_ms: output.profile.gpu_ms_total,
                present_gpu_ms: None,
                ui_gpu_ms: None,
                ui_cpu_ms: ui.as_ref().map_or(0.0, |u| u.cpu_ms),
                dispatches: output.dispatches,
                barriers: output.barriers,
                passes: output.profile.passes.iter().map(|p| p.path.clone()).collect(),
                decision: session.last_decision(),
                swapchain_recreated: recreated,
            });
            last_present = now;
            if let Some(record) = report.frames.last() {
                let pass_ms: Vec<(String, f64)> =
                    output.profile.passes.iter().map(|p| (p.path.clone(), p.gpu_ms)).collect();
                history.push(record, &pass_ms);
            }
            if let Some(pixels) = screenshot {
                for path in &shots {
                    write_png(path, &pixels, w, h, sc.format)?;
                    report.screenshots.push(path.display().to_string());
                }
            }
            if keys.contains(&'P') {
                write_profile(&options.out_dir, frame_index, &output)?;
            }
            frame_index += 1;
        }
    }
    Ok(())
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

/// Whether to recreate the swapchain, and the screenshot's bytes if asked for.
type Presented = (bool, Option<Vec<u8>>);

/// One frame slot: wait for its fence, acquire, upload, blit, submit, present.
/// `None`: the swapchain was out of date before anything was submitted.
/// Otherwise whether to recreate it, and the screenshot's bytes if asked for.
fn present(
    ctx: &Context,
    frames: &mut FramesInFlight,
    sc: &Swapchain,
    output: &RenderOutput,
    screenshot: bool,
    ui: Option<&mut Ui>,
    report: &mut ViewerReport,
) -> Result<Option<Presented>, ViewerError> {
    let device = &ctx.device;
    let slot = frames.next_slot()?;
    if let Some(i) = slot.profile_pending.take() {
        // Its fence was just waited: the timestamps are there.
        let p = slot.profiler.resolve(0)?;
        if let Some(r) = report.frames.get_mut(i as usize) {
            r.present_gpu_ms = Some(p.pass_ms("present_blit"));
            r.ui_gpu_ms = p.passes.iter().any(|s| s.name == "ui").then(|| p.pass_ms("ui"));
        }
    }
    let record_index = report.frames.len();
    let Some((image_index, suboptimal)) = sc.acquire(slot.image_acquired)? else {
        return Ok(None);
    };
    let (w, h) = (output.image.width, output.image.height);
    if slot.upload.as_ref().is_none_or(|u| (u.width, u.height) != (w, h)) {
        // The slot's last use of the old one finished (its fence).
        slot.upload = Some(Upload::new(ctx, w, h)?);
    }
    let upload = slot.upload.as_mut().ok_or_else(|| ViewerError::Window("no upload".into()))?;
    let rgba: Vec<[f32; 4]> = output.image.pixels.iter().map(|p| [p[0], p[1], p[2], 1.0]).collect();
    upload.staging.write(&rgba)?;
    let shot = if screenshot {
        Some(Buffer::staging(
            ctx,
            "screenshot readback",
            sc.extent.width as u64 * sc.extent.height as u64 * 4,
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
    {
        let mut rec = Recorder::for_command_buffer(ctx, slot.cb);
        let i = image_index as usize;
        let target = PresentTarget { image: sc.images[i], view: sc.views[i], extent: sc.extent };
        present_pass::record(&mut rec, &mut slot.profiler, &upload.image, &upload.staging, &target, shot.as_ref(), ui)?;
    }
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
    slot.profile_pending = Some(record_index as u64);
    let stale = sc.present(image_index)?;
    let pixels = match &shot {
        Some(buffer) => {
            // SAFETY: the fence belongs to this device; only this frame waits on it.
            unsafe { device.wait_for_fences(&[slot.done], true, u64::MAX) }.call("vkWaitForFences")?;
            Some(buffer.read::<u8>(sc.extent.width as usize * sc.extent.height as usize * 4)?)
        }
        None => None,
    };
    Ok(Some((suboptimal || stale, pixels)))
}

/// Present-pass GPU times of slots whose fences were waited (all, at the end).
fn resolve_present_profiles(frames: &mut FramesInFlight, report: &mut ViewerReport) -> Result<(), ViewerError> {
    frames.wait_all()?;
    for slot in &mut frames.slots {
        if let Some(i) = slot.profile_pending.take() {
            let p = slot.profiler.resolve(0)?;
            if let Some(r) = report.frames.get_mut(i as usize) {
                r.present_gpu_ms = Some(p.pass_ms("present_blit"));
                r.ui_gpu_ms = p.passes.iter().any(|s| s.name == "ui").then(|| p.pass_ms("ui"));
            }
        }
    }
    Ok(())
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

fn write_profile(dir: &Path, frame: u64, output: &RenderOutput) -> Result<(), ViewerError> {
    for (name, value) in [
        (format!("sweeplab-view-{frame}-profile.json"), output.profile.to_json()),
        (format!("sweeplab-view-{frame}-trace.json"), output.profile.chrome_trace()),
    ] {
        let path = dir.join(name);
        let text = serde_json::to_string_pretty(&value).unwrap_or_default();
        std::fs::write(&path, text)
            .map_err(|e| ViewerError::Write { path: path.display().to_string(), message: e.to_string() })?;
        eprintln!("wrote {}", path.display());
    }
    Ok(())
}
