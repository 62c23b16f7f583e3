//! What the viewer measured, frame by frame: the technique's passes and GPU
//! time, the present pass, the wall-clock frame time, and the light volume's
//! update decision. The GPU figures are filled in once the frame's slot
//! fence was waited. Written as JSON by `--log-json`.

use crate::vk::creation_counts::CreationCounts;
use serde::Serialize;

#[derive(Clone, Debug, Default, Serialize)]
pub struct FrameRecord {
    pub index: u64,
    /// The window's size.
    pub width: u32,
    pub height: u32,
    /// The size the technique rendered at: the image's, or a preview's.
    pub image_width: u32,
    pub image_height: u32,
    /// The image's sides over the preview's: 1 for a full-quality frame.
    pub preview_scale: u32,
    /// Nothing rendered: the last frame shown again under a redrawn panel.
    pub reshown: bool,
    /// The control panel's content height in window pixels (none without it).
    pub panel_height: Option<f64>,
    /// Wall clock from the previous frame's present to this one's.
    pub frame_ms: f64,
    /// When it was handed to presentation, ms since 1970 (to line frames up
    /// with input sent from outside, e.g. `tools/viewer_drag_measure.sh`).
    pub presented_unix_ms: f64,
    /// Wall clock of the technique's frame on the host: its recording (for a
    /// technique that renders by its own submission: record, submit, wait, read).
    pub render_ms: f64,
    /// The technique's GPU time (sum of its root scopes).
    pub gpu_ms: f64,
    /// GPU time of `present_blit`; filled in once the slot's fence is waited.
    pub present_gpu_ms: Option<f64>,
    /// GPU time of the control panel's draw (`ui`), filled in like `present_gpu_ms`.
    pub ui_gpu_ms: Option<f64>,
    /// Host time of the panel's layout and tessellation.
    pub ui_cpu_ms: f64,
    pub dispatches: u32,
    pub barriers: u32,
    /// The frame's profile scopes, by path: the technique's, then the
    /// viewer's (`frame_upload` where the frame was uploaded, `present_blit`, `ui`).
    pub passes: Vec<String>,
    /// Secondary command buffers recorded for this frame (IPSVI `secondary`:
    /// its sweeps, once per session and size; the light volume: new passes);
    /// the frame replayed the others it executed.
    pub secondaries_recorded: usize,
    /// The light volume's update and its reason.
    pub decision: Option<String>,
    /// The swapchain was recreated before this frame.
    pub swapchain_recreated: bool,
    /// Pipelines, descriptor pools and images the context created since the
    /// previous frame's record (the first: since the context began): an
    /// unchanged frame creates no pipeline and no pool.
    pub created: CreationCounts,
}

#[derive(Clone, Debug, Default, Serialize)]
pub struct ViewerReport {
    pub technique: String,
    pub device: String,
    pub present_mode: String,
    pub frames: Vec<FrameRecord>,
    pub screenshots: Vec<String>,
}

impl ViewerReport {
    /// Mean of `f` over the frames after the first `skip` (warm-up).
    pub fn mean(&self, skip: usize, f: impl Fn(&FrameRecord) -> Option<f64>) -> Option<f64> {
        let v: Vec<f64> = self.frames.iter().skip(skip).filter_map(f).collect();
        (!v.is_empty()).then(|| v.iter().sum::<f64>() / v.len() as f64)
    }
}
