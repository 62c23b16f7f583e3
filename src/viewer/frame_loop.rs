//! The frame loop: events, script steps and mouse edits; then a frame slot:
//! wait for its fence, acquire a swapchain image, record the technique's frame
//! (the same recording as `render`), the hand-off barrier and the present pass
//! into the slot's command buffer, submit once, present.
//! The swapchain is recreated when the window's size changes or presentation
//! reports it out of date or suboptimal; a minimized window renders nothing.

use super::controls;
use super::error::ViewerError;
use super::frame_submit::{
    present, queue_idle, resolve_all, resolve_finished, write_png, FrameLog, FrameSource, PresentStyle,
    QueueIdleOnDrop, Shown, Wants,
};
use super::frames::{FramesInFlight, FRAMES_IN_FLIGHT, PROFILER_CAPACITY};
use super::live_scene::{Change, LiveScene, SceneSource};
use super::present_pass;
use super::preview::{self, Preview, PreviewMode};
use super::report::{FrameRecord, ViewerReport};
use super::script::{Action, Script};
use super::tf_editor;
use super::ui::{self, PanelView, PassHistory, Ui, UiEdit, PANEL_WIDTH};
use super::window::{self, WindowEvents};
use super::window_fit::ImageArea;
use crate::render::{FrameImages, GpuScene, UploadedVolume, VolumeTexels};
use crate::scene::{Light, Scene};
use crate::techniques::lightvolume::LightVolumeSettings;
use crate::techniques::{self, Technique};
use crate::vk::error::VkResultExt;
use crate::vk::swapchain::present_mode_name;
use crate::vk::{Context, ContextOptions, Profiler, Surface, Swapchain};
use ash::vk;
use std::ffi::CStr;
use std::path::PathBuf;
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
    /// Reduced-resolution previews while dragging (`preview`).
    pub preview: PreviewMode,
}

/// How long an idle viewer waits for events before it looks again.
const IDLE_WAIT: Duration = Duration::from_millis(30);

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
    // The image beside the panel at the scene's size, and the panel's whole
    // content: the window holds both (`window_fit`).
    let panel = if options.ui && !options.hide_panel { PANEL_WIDTH as u32 } else { 0 };
    let content = if panel > 0 { first_panel_height(&live.scene, options.technique) } else { 0 };
    let (mut area, (ww, wh)) = ImageArea::new((width, height), panel, content);
    // Declared before the context: the window outlives the surface made from it.
    let mut events = WindowEvents::new(&format!("sweeplab view: {}", options.technique), ww, wh);
    events.open(&mut event_loop)?;
    // The screen may have held it smaller: still the viewer's own size.
    area.ask(events.size()?);
    let (display, _) = events.handles()?;
    let names =
        ash_window::enumerate_required_extensions(display).call("vkEnumerateInstanceExtensionProperties (surface)")?;
    // SAFETY: ash_window returns pointers to static NUL-terminated extension names.
    let names: Vec<&CStr> = names.iter().map(|&p| unsafe { CStr::from_ptr(p) }).collect();
    let ctx = Context::for_window(&options.context.clone().with_env(), &names)?;
    eprintln!("{}", ctx.summary());
    let report = frames_on(&ctx, &mut live, &mut event_loop, &mut events, &mut area, options)?;
    Ok((report, ctx.take_validation_messages()))
}

/// The panel's content height for `scene` and `technique` before any frame
/// (laid out off-screen), in pixels at a scale factor of 1.
fn first_panel_height(scene: &Scene, technique: Technique) -> u32 {
    let histogram = scene.volume.histogram(tf_editor::HISTOGRAM_BINS);
    let enabled = vec![true; scene.lights.len()];
    let history = PassHistory::default();
    // The figures on top of the panel once frames come, at their widest.
    let last = FrameRecord {
        frame_ms: 99_999.99,
        gpu_ms: 99_999.99,
        dispatches: 99_999,
        barriers: 99_999,
        decision: (technique == Technique::LightVolume).then(|| "an update decision and its reason".repeat(3)),
        preview_scale: 16,
        ..Default::default()
    };
    let view = PanelView {
        technique,
        scene,
        enabled: &enabled,
        last: Some(&last),
        history: &history,
        ui_cpu_ms: 0.0,
        ui_gpu_ms: None,
        message: None,
        histogram: &histogram,
        selected_light: 0,
    };
    ui::panel_height(&view).ceil() as u32
}

fn frames_on(
    ctx: &Context,
    live: &mut LiveScene,
    event_loop: &mut EventLoop<()>,
    events: &mut WindowEvents,
    area: &mut ImageArea,
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
    let mut log = FrameLog {
        report: &mut report,
        history: PassHistory::default(),
        out_dir: options.out_dir.clone(),
        preview: Preview::new(options.preview),
    };
    let windowing = (&mut *event_loop, &mut *events, &mut *area);
    let result = frame_loop(ctx, &surface, &mut frames, &mut swapchain, &mut ui, live, windowing, options, &mut log);
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
    (event_loop, events, area): (&mut EventLoop<()>, &mut WindowEvents, &mut ImageArea),
    options: &ViewerOptions,
    log: &mut FrameLog,
) -> Result<(), ViewerError> {
    let mut host_profiler = Profiler::new(ctx, PROFILER_CAPACITY)?;
    let style = PresentStyle { handoff_barrier: options.handoff_barrier, filter: present_pass::stretch_filter(ctx) };
    // Interactive runs wait for input once the full frame is shown; scripted
    // runs (`--frames`) render every frame they count.
    let interactive = options.frames.is_none();
    // The scene's generation and image size whose full frame is on screen,
    // and that frame (to show again under a redrawn panel).
    let mut generation = 0u64;
    let mut full_shown: Option<(u64, u32, u32)> = None;
    // The scene generation and preview scale last warmed up (`preview::warm_up`).
    let mut warmed: Option<(u64, u32)> = None;
    let mut last_shown: Option<Shown> = None;
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
        generation += 1;
        enabled.resize(live.scene.lights.len(), true);
        // Switched-off lights are left out of the uploaded scene.
        let mut scene = live.scene.clone();
        scene.lights = scene.lights.iter().zip(&enabled).filter(|(_, &on)| on).map(|(l, _)| *l).collect();
        // While a drag goes on, a preview's scene (`preview`).
        let scale = log.preview.scale_at(Instant::now());
        if scale > 1 {
            scene = preview::preview_scene(&scene, scale);
        }
        // A light volume that spreads its passes over frames is still changing.
        let converging =
            technique == Technique::LightVolume && scene.settings.get::<LightVolumeSettings>().max_passes_per_frame > 0;
        let gpu = GpuScene::on_volume(ctx, &scene, &volume, frame_images.clone())?;
        let mut session = techniques::session(&gpu, technique)?;
        // Dropped first when the scene is left (edited, closed, or an error):
        // frames in flight use the scene's and the session's resources.
        let _in_flight_done = QueueIdleOnDrop(ctx);
        loop {
            if !events.pump(event_loop, Duration::ZERO)? || events.close_requested {
                break 'scene;
            }
            // What finished frames cost reaches the preview before it decides.
            resolve_finished(ctx, frames, log)?;
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
                    KeyCode::KeyQ => Some('Q'),
                    _ => None,
                })
                .collect();
            if keys.contains(&'Q') {
                break 'scene;
            }
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
                            log.preview.input(Instant::now());
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
                            if !session.follows_lights() {
                                log.preview.input(Instant::now());
                                rebuild = true;
                            }
                        }
                        // As the mouse would: through `mouse_camera` below.
                        Action::Orbit(dx, dy) => {
                            events.orbit = (events.orbit.0 + *dx as f64, events.orbit.1 + *dy as f64);
                        }
                        Action::Zoom(lines) => events.zoom += lines,
                        Action::Wait(ms) => std::thread::sleep(Duration::from_millis(*ms)),
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
                        Ok(change) => {
                            let renders_anew = change == Change::Scene || !session.follows_lights();
                            if renders_anew {
                                // A slider or a transfer-function point being dragged.
                                log.preview.input(Instant::now());
                            }
                            rebuild |= renders_anew;
                        }
                        // The panel offers valid values only; say so rather than stop.
                        Err(e) => message = Some(e.to_string()),
                    },
                    UiEdit::Lights(lights) => {
                        live.set_lights(lights);
                        if !session.follows_lights() {
                            log.preview.input(Instant::now());
                            rebuild = true;
                        }
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
            if (dx, dy) != (0.0, 0.0)
                && drag_light(live, selected_light, (dx as f32, dy as f32), events.size()?.1)
                && !session.follows_lights()
            {
                log.preview.input(Instant::now());
                rebuild = true;
            }
            enabled.resize(live.scene.lights.len(), true);
            if let Some(camera) = mouse_camera(live, events) {
                live.set_camera(camera);
                log.preview.input(Instant::now());
                rebuild = true;
            }
            // A preview starts, or the input settled and the full frame is due.
            if rebuild || log.preview.scale_at(Instant::now()) != scale {
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
                area.window_is((ww, wh));
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
            let (iw, ih) = area.image((w, h), panel_px);
            let state_shown = (generation, iw, ih);
            // The full frame of this state is on screen: an interactive viewer
            // renders nothing more until something changes, so the next input
            // finds no long frame in flight; the panel alone is redrawn over
            // the frame shown.
            let on_screen = interactive && !converging && scale == 1 && full_shown == Some(state_shown);
            let panel_wants = events.panel_input || ui.as_ref().is_some_and(|u| u.wants_repaint);
            if on_screen && !recreated && keys.is_empty() && ui_edits.is_empty() && !panel_wants {
                resolve_finished(ctx, frames, log)?;
                // Idle: the preview a drag would start with, rendered once and dropped.
                if let Some(s) = log.preview.next_preview_scale().filter(|&s| warmed != Some((generation, s))) {
                    preview::warm_up(ctx, &scene, &volume, technique, s, (iw, ih))?;
                    warmed = Some((generation, s));
                }
                events.pump(event_loop, IDLE_WAIT)?;
                continue;
            }
            events.panel_input = false;
            let reshow = if on_screen && !keys.contains(&'P') { last_shown.clone() } else { None };
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
                    last: frames_so_far.iter().rev().find(|f| f.present_gpu_ms.is_some() && !f.reshown),
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
                // The profiler's rows came in: a window the viewer sized grows to fit.
                if let Some(taller) = area.grow_for_panel((w, h), panel.content_px, events.screen_height()) {
                    area.ask(taller);
                    let _ = window.request_inner_size(PhysicalSize::new(taller.0, taller.1));
                }
            }

            let last = options.frames.is_some_and(|n| frame_index + 1 == n);
            let mut shots: Vec<PathBuf> = Vec::new();
            if last {
                shots.extend(options.screenshot.clone());
            }
            if keys.contains(&'S') {
                let path = options.out_dir.join(format!("sweeplab-view-{frame_index}.png"));
                let path = std::path::absolute(&path).unwrap_or(path);
                message = Some(format!("screenshot: {}", path.display()));
                shots.push(path);
            }
            let reshown = reshow.is_some();
            let render = preview::reduced((iw, ih), scale);
            let source = FrameSource {
                gpu: &gpu,
                technique,
                lights: &lights,
                host_profiler: &mut host_profiler,
                render,
                shown: (iw, ih),
                reshow,
            };
            let wants = Wants { screenshot: !shots.is_empty(), profile: keys.contains(&'P') };
            let shown_ui = ui.as_mut().filter(|_| panel_shown);
            let presented =
                present(ctx, frames, sc, session.as_mut(), source, wants, style, (shown_ui, panel_px), log)?;
            let Some(submitted) = presented else {
                recreate = true;
                continue;
            };
            recreate |= submitted.recreate;
            if !reshown {
                full_shown = (scale == 1).then_some(state_shown);
                last_shown = submitted.shown.clone();
            }
            let now = Instant::now();
            let counts = ctx.creation_counts();
            let created = counts.since(&counted);
            counted = counts;
            let technique_profile = submitted.uploaded_profile.as_ref();
            log.report.frames.push(FrameRecord {
                index: frame_index,
                width: w,
                height: h,
                image_width: if reshown { iw } else { render.0 },
                image_height: if reshown { ih } else { render.1 },
                preview_scale: if reshown { 1 } else { scale },
                reshown,
                panel_height: ui.as_ref().filter(|_| panel_shown).map(|u| u.content_px as f64),
                frame_ms: (now - last_present).as_secs_f64() * 1e3,
                presented_unix_ms: std::time::SystemTime::now()
                    .duration_since(std::time::UNIX_EPOCH)
                    .map_or(0.0, |d| d.as_secs_f64() * 1e3),
                render_ms: submitted.render_ms,
                gpu_ms: technique_profile.map_or(0.0, |p| p.gpu_ms_total),
                present_gpu_ms: None,
                ui_gpu_ms: None,
                ui_cpu_ms: ui.as_ref().map_or(0.0, |u| u.cpu_ms),
                dispatches: submitted.dispatches,
                barriers: submitted.barriers,
                passes: technique_profile.map_or(Vec::new(), |p| p.passes.iter().map(|p| p.path.clone()).collect()),
                secondaries_recorded: if reshown { 0 } else { session.secondaries_recorded() },
                decision: session.last_decision(),
                swapchain_recreated: recreated,
                created,
            });
            last_present = now;
            if let Some(pixels) = submitted.pixels {
                for path in &shots {
                    write_png(path, &pixels, w, h, sc.format)?;
                    log.report.screenshots.push(path.display().to_string());
                    // Said at once: the user pressing S wants to know where it went.
                    eprintln!("screenshot: {}", path.display());
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
