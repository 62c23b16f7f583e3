//! The control panel (egui, drawn by egui-ash-renderer into the swapchain
//! image after the blit): technique, its settings, transfer-function presets,
//! lights, and the live profiler (a rolling plot and a table of the per-pass
//! GPU times, frame time, dispatches and barriers, the light volume's
//! decision). The panel only proposes edits ([`UiEdit`]); the frame loop
//! applies them through the same checks as `--set`.

use super::report::FrameRecord;
use super::settings_panel::SettingsPanel;
use super::tf_editor::TfEditor;
use crate::plural::count;
use crate::scene::presets::PRESET_NAMES;
use crate::scene::{Light, LightKind, Scene};
use crate::techniques::Technique;
use crate::vk::error::VkResultExt;
use crate::vk::{Context, VkError};
use ash::vk;
use egui_ash_renderer::{DynamicRendering, Options, Renderer};
use std::collections::{BTreeMap, VecDeque};
use std::time::Instant;

/// Frames the rolling plots keep.
const HISTORY: usize = 120;

/// What the user asked for in the panel this frame.
#[derive(Clone, Debug, PartialEq)]
pub enum UiEdit {
    Technique(Technique),
    /// A scene edit as `--set` takes it.
    Set(String),
    Lights(Vec<Light>),
    Toggle(usize, bool),
    Key(char),
    /// The light Ctrl and the left button drag in the view.
    SelectLight(usize),
}

/// Per-pass GPU times of the last frames, for the plots and the table.
#[derive(Default)]
pub struct PassHistory {
    pub passes: BTreeMap<String, VecDeque<f64>>,
    pub frame_ms: VecDeque<f64>,
}

impl PassHistory {
    pub fn push(&mut self, record: &FrameRecord, pass_ms: &[(String, f64)]) {
        for (path, ms) in pass_ms {
            let h = self.passes.entry(path.clone()).or_default();
            h.push_back(*ms);
            if h.len() > HISTORY {
                h.pop_front();
            }
        }
        // Passes of another technique fade out of the table once idle.
        self.passes.retain(|p, _| pass_ms.iter().any(|(q, _)| q == p));
        self.frame_ms.push_back(record.frame_ms);
        if self.frame_ms.len() > HISTORY {
            self.frame_ms.pop_front();
        }
    }
}

/// What the panel shows and edits.
pub struct PanelView<'a> {
    pub technique: Technique,
    pub scene: &'a Scene,
    pub enabled: &'a [bool],
    pub last: Option<&'a FrameRecord>,
    pub history: &'a PassHistory,
    pub ui_cpu_ms: f64,
    pub ui_gpu_ms: Option<f64>,
    pub message: Option<&'a str>,
    /// The volume's histogram (counts per bin), under the transfer function.
    pub histogram: &'a [u64],
    /// The light Ctrl and the left button drag in the view.
    pub selected_light: usize,
}

pub struct Ui {
    pub egui: egui::Context,
    renderer: Renderer,
    upload_pool: vk::CommandPool,
    device: ash::Device,
    queue: vk::Queue,
    primitives: Vec<egui::ClippedPrimitive>,
    pixels_per_point: f32,
    /// Textures egui let go of, freed once no frame in flight can use them.
    pending_free: Vec<egui::TextureId>,
    /// Texture writes waiting until no frame in flight reads them.
    pending_set: Vec<(egui::TextureId, egui::epaint::ImageDelta)>,
    /// Host time of the last panel (layout and tessellation).
    pub cpu_ms: f64,
    /// The last panel's content height in window pixels.
    pub content_px: u32,
    /// The last panel asked to be drawn again at once (an animation).
    pub wants_repaint: bool,
    state: PanelState,
}

/// What the panel's editors keep between frames.
#[derive(Default)]
struct PanelState {
    tf_editor: TfEditor,
    settings: SettingsPanel,
    tab: Tab,
}

/// The panel's pages: one shows at a time under the frame's figures, so the
/// panel fits a window as tall as the tallest page (about 640 px with IPSVI's
/// settings open) rather than all of them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
enum Tab {
    #[default]
    Technique,
    Scene,
    Profiler,
}

impl Tab {
    const ALL: [Tab; 3] = [Tab::Technique, Tab::Scene, Tab::Profiler];

    fn label(self) -> &'static str {
        match self {
            Tab::Technique => "Technique",
            Tab::Scene => "Transfer & lights",
            Tab::Profiler => "Profiler",
        }
    }
}

impl Ui {
    pub fn new(ctx: &Context, format: vk::Format, frames_in_flight: usize) -> Result<Ui, VkError> {
        let renderer = Renderer::with_default_allocator(
            &ctx.instance,
            ctx.physical_device,
            ctx.device.clone(),
            DynamicRendering { color_attachment_format: format, depth_attachment_format: None },
            Options { in_flight_frames: frames_in_flight, srgb_framebuffer: true, ..Default::default() },
        )
        .map_err(|e| VkError::Presentation(format!("egui renderer: {e}")))?;
        let info = vk::CommandPoolCreateInfo::default()
            .queue_family_index(ctx.queue_family)
            .flags(vk::CommandPoolCreateFlags::RESET_COMMAND_BUFFER);
        // SAFETY: valid device and queue family; destroyed in Drop.
        let upload_pool = unsafe { ctx.device.create_command_pool(&info, None) }.call("vkCreateCommandPool")?;
        Ok(Ui {
            egui: egui::Context::default(),
            renderer,
            upload_pool,
            device: ctx.device.clone(),
            queue: ctx.queue,
            primitives: Vec::new(),
            pixels_per_point: 1.0,
            pending_free: Vec::new(),
            pending_set: Vec::new(),
            cpu_ms: 0.0,
            content_px: 0,
            wants_repaint: false,
            state: PanelState::default(),
        })
    }

    /// Lays the panel out for `input`; new or changed textures (the font atlas)
    /// wait in [`Self::has_pending_uploads`] until [`Self::upload_textures`].
    pub fn build(
        &mut self,
        input: egui::RawInput,
        view: &PanelView,
    ) -> Result<(Vec<UiEdit>, egui::PlatformOutput), VkError> {
        let started = Instant::now();
        let mut edits = Vec::new();
        let state = &mut self.state;
        let mut height = 0.0;
        let output = self.egui.run(input, |ctx| height = panel(ctx, view, state, &mut edits));
        self.content_px = (height * output.pixels_per_point).ceil() as u32;
        // egui asks for the next frame at once while something animates.
        self.wants_repaint =
            output.viewport_output.get(&egui::ViewportId::ROOT).is_some_and(|v| v.repaint_delay.is_zero());
        self.pixels_per_point = output.pixels_per_point;
        self.primitives = self.egui.tessellate(output.shapes, output.pixels_per_point);
        self.pending_set.extend(output.textures_delta.set);
        self.pending_free.extend(output.textures_delta.free);
        self.cpu_ms = started.elapsed().as_secs_f64() * 1e3;
        Ok((edits, output.platform_output))
    }

    /// Texture writes egui asked for: the font atlas may be updated in place,
    /// and the other frame in flight may still be sampling it, so the caller
    /// waits for every frame in flight before [`Self::upload_textures`].
    pub fn has_pending_uploads(&self) -> bool {
        !self.pending_set.is_empty()
    }

    /// Writes the pending textures (egui-ash-renderer's own submission, which
    /// it waits for); no frame in flight may read them (the caller waited).
    pub fn upload_textures(&mut self) -> Result<(), VkError> {
        let set = std::mem::take(&mut self.pending_set);
        self.renderer
            .set_textures(self.queue, self.upload_pool, &set)
            .map_err(|e| VkError::Presentation(format!("egui textures: {e}")))
    }

    /// Textures to free once every frame in flight is done (the caller waits).
    pub fn has_pending_frees(&self) -> bool {
        !self.pending_free.is_empty()
    }

    pub fn free_textures(&mut self) -> Result<(), VkError> {
        let ids = std::mem::take(&mut self.pending_free);
        self.renderer.free_textures(&ids).map_err(|e| VkError::Presentation(format!("egui textures: {e}")))
    }

    /// Draws the panel; the caller has begun rendering into the target.
    pub fn draw(&mut self, cb: vk::CommandBuffer, extent: vk::Extent2D) -> Result<(), VkError> {
        self.renderer
            .cmd_draw(cb, extent, self.pixels_per_point, &self.primitives)
            .map_err(|e| VkError::Presentation(format!("egui draw: {e}")))
    }
}

impl Drop for Ui {
    fn drop(&mut self) {
        // SAFETY: the viewer waits for every frame in flight before dropping the UI.
        unsafe { self.device.destroy_command_pool(self.upload_pool, None) };
    }
}

/// Width of the control panel, in points: fixed, so the image beside it is laid
/// out before the panel runs.
pub const PANEL_WIDTH: f32 = 260.0;

/// The panel's content height, in points, for `view`: its tallest page, laid
/// out off-screen (no GPU), so that the first window can be made tall enough.
pub fn panel_height(view: &PanelView) -> f32 {
    let ctx = egui::Context::default();
    let screen = egui::Rect::from_min_size(egui::Pos2::ZERO, egui::vec2(PANEL_WIDTH + 64.0, 16_384.0));
    let input = egui::RawInput { screen_rect: Some(screen), ..Default::default() };
    let mut tallest: f32 = 0.0;
    for tab in Tab::ALL {
        let mut state = PanelState { tab, ..Default::default() };
        let mut height = 0.0;
        // The first pass loads the fonts; the second lays out with them.
        for _ in 0..2 {
            let _ = ctx.run(input.clone(), |ctx| height = panel(ctx, view, &mut state, &mut Vec::new()));
        }
        tallest = tallest.max(height);
    }
    tallest
}

/// Lays the panel out; returns its content's height in points.
fn panel(ctx: &egui::Context, view: &PanelView, state: &mut PanelState, edits: &mut Vec<UiEdit>) -> f32 {
    let shown = egui::SidePanel::left("controls").exact_width(PANEL_WIDTH).resizable(false).show(ctx, |ui| {
        let scroll = egui::ScrollArea::vertical().show(ui, |ui| {
            frame_summary(ui, view, edits);
            if let Some(m) = view.message {
                ui.colored_label(egui::Color32::LIGHT_RED, m);
            }
            ui.horizontal(|ui| {
                for tab in Tab::ALL {
                    ui.selectable_value(&mut state.tab, tab, tab.label());
                }
            });
            ui.separator();
            match state.tab {
                Tab::Technique => technique_section(ui, view, &mut state.settings, edits),
                Tab::Scene => {
                    transfer_section(ui, view, &mut state.tf_editor, edits);
                    ui.separator();
                    lights_section(ui, view, edits);
                }
                Tab::Profiler => profiler_section(ui, view),
            }
        });
        scroll.content_size.y
    });
    shown.inner
}

fn technique_section(ui: &mut egui::Ui, view: &PanelView, settings: &mut SettingsPanel, edits: &mut Vec<UiEdit>) {
    let mut chosen = view.technique;
    egui::ComboBox::from_label("technique").selected_text(chosen.name()).show_ui(ui, |ui| {
        for t in Technique::all() {
            ui.selectable_value(&mut chosen, t, t.name());
        }
    });
    if chosen != view.technique {
        edits.push(UiEdit::Technique(chosen));
    }
    let open = view.technique.settings_table();
    settings.show(ui, view.scene, open, edits);
}

fn transfer_section(ui: &mut egui::Ui, view: &PanelView, tf_editor: &mut TfEditor, edits: &mut Vec<UiEdit>) {
    ui.heading("Transfer function");
    ui.label("drag a point (scalar, opacity); double-click adds one");
    tf_editor.show(ui, &view.scene.transfer.points, view.histogram, edits);
    ui.horizontal_wrapped(|ui| {
        ui.label("preset");
        for name in PRESET_NAMES {
            if ui.small_button(name).clicked() {
                edits.push(UiEdit::Set(format!("transfer={{preset=\"{name}\"}}")));
            }
        }
    });
}

fn lights_section(ui: &mut egui::Ui, view: &PanelView, edits: &mut Vec<UiEdit>) {
    ui.heading("Lights");
    ui.label("Ctrl + drag in the view moves the selected light (turns a directional one)");
    let mut lights = view.scene.lights.clone();
    let mut changed = false;
    let mut remove = None;
    for (i, light) in lights.iter_mut().enumerate() {
        ui.push_id(i, |ui| {
            ui.horizontal(|ui| {
                let mut on = view.enabled.get(i).copied().unwrap_or(true);
                if ui.radio(view.selected_light == i, "").on_hover_text("drag this light").clicked() {
                    edits.push(UiEdit::SelectLight(i));
                }
                if ui.checkbox(&mut on, format!("light {i}")).changed() {
                    edits.push(UiEdit::Toggle(i, on));
                }
                let mut rgb = light.color.to_array();
                changed |= ui.color_edit_button_rgb(&mut rgb).changed();
                light.color = rgb.into();
                if ui.small_button("remove").clicked() {
                    remove = Some(i);
                }
            });
            changed |= ui.add(egui::Slider::new(&mut light.intensity, 0.0..=10.0).text("intensity")).changed();
            let (label, v) = match &mut light.kind {
                LightKind::Directional { direction } => ("direction", direction),
                LightKind::Point { position } => ("position", position),
                LightKind::Spot { position, .. } => ("position", position),
            };
            ui.horizontal(|ui| {
                ui.label(label);
                for c in [&mut v.x, &mut v.y, &mut v.z] {
                    changed |= ui.add(egui::DragValue::new(c).speed(0.02).range(-5.0..=5.0)).changed();
                }
            });
        });
    }
    if let Some(i) = remove {
        lights.remove(i);
        changed = true;
    }
    if ui.button("add light").clicked() {
        lights.push(Light {
            kind: LightKind::Directional { direction: glam::Vec3::new(-1.0, -1.0, -1.0) },
            color: glam::Vec3::ONE,
            intensity: 1.0,
            falloff: crate::scene::Falloff::None,
        });
        changed = true;
    }
    if changed {
        edits.push(UiEdit::Lights(lights));
    }
}

/// Always on top of the panel: the last frame's figures, a preview's size,
/// and the screenshot and profile buttons.
fn frame_summary(ui: &mut egui::Ui, view: &PanelView, edits: &mut Vec<UiEdit>) {
    if let Some(f) = view.last {
        ui.label(format!("frame {:.2} ms   technique GPU {:.2} ms", f.frame_ms, f.gpu_ms));
        ui.label(format!(
            "{}, {} per frame",
            count(f.dispatches, "dispatch", "dispatches"),
            count(f.barriers, "barrier", "barriers")
        ));
        if let Some(d) = &f.decision {
            ui.label(d);
        }
        if f.preview_scale > 1 {
            ui.label(format!(
                "preview while dragging: {}x{} (1/{} of the sides); full quality when still",
                f.image_width, f.image_height, f.preview_scale
            ));
        }
    }
    ui.horizontal(|ui| {
        if ui.button("screenshot (S)").clicked() {
            edits.push(UiEdit::Key('S'));
        }
        if ui.button("profile (P)").clicked() {
            edits.push(UiEdit::Key('P'));
        }
    });
}

fn profiler_section(ui: &mut egui::Ui, view: &PanelView) {
    ui.label(format!(
        "UI: {:.2} ms host, {} GPU",
        view.ui_cpu_ms,
        view.ui_gpu_ms.map_or("-".to_string(), |ms| format!("{ms:.3} ms"))
    ));
    plot(ui, "frame ms", &view.history.frame_ms);
    egui::Grid::new("passes").striped(true).show(ui, |ui| {
        ui.label("pass");
        ui.label("last ms");
        ui.label("mean ms");
        ui.end_row();
        for (path, h) in &view.history.passes {
            let mean = h.iter().sum::<f64>() / h.len().max(1) as f64;
            ui.label(path.rsplit('/').next().unwrap_or(path));
            ui.label(format!("{:.3}", h.back().copied().unwrap_or(0.0)));
            ui.label(format!("{mean:.3}"));
            ui.end_row();
        }
    });
    for (path, h) in view.history.passes.iter().filter(|(p, _)| !p.contains('/')) {
        plot(ui, path, h);
    }
}

/// A rolling line plot of `values` with its largest value as the scale.
fn plot(ui: &mut egui::Ui, label: &str, values: &VecDeque<f64>) {
    let top = values.iter().copied().fold(0.0, f64::max).max(1e-6);
    ui.label(format!("{label} (max {top:.2})"));
    let (rect, _) = ui.allocate_exact_size(egui::vec2(ui.available_width(), 40.0), egui::Sense::hover());
    let painter = ui.painter_at(rect);
    painter.rect_filled(rect, 2.0, egui::Color32::from_gray(30));
    let n = values.len().max(2) as f32 - 1.0;
    let points: Vec<egui::Pos2> = values
        .iter()
        .enumerate()
        .map(|(i, &v)| {
            egui::pos2(rect.left() + rect.width() * i as f32 / n, rect.bottom() - rect.height() * (v / top) as f32)
        })
        .collect();
    painter.add(egui::Shape::line(points, egui::Stroke::new(1.0, egui::Color32::LIGHT_GREEN)));
}
