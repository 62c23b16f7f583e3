//! Reduced-resolution previews while the user drags: a technique whose full
//! frame takes longer than [`PREVIEW_ABOVE_MS`] (IPSVI at 256x256 on lavapipe:
//! seconds) would make every mouse move wait that long. While the camera,
//! a light or a setting is being dragged, the viewer renders the same
//! technique at 1/`scale` of the image's sides instead, with the resolution
//! its settings tie to the image scaled alike (IPSVI's illumination cache,
//! half-angle slicing's light buffer), and the blit stretches it over the
//! image; [`SETTLE`] after the last such input it renders the full frame.
//!
//! The scale follows what the frames cost: from the full frame's GPU time at
//! first (a frame costs about its pixels, so the sides shrink by the square
//! root of the ratio to [`BUDGET_MS`]), then from each preview's own (IPSVI
//! costs more than its pixels: its lines run one after another).

use crate::scene::Scene;
use crate::techniques::half_angle::HalfAngleSettings;
use crate::techniques::ipsvi::IpsviSettings;
use std::time::{Duration, Instant};

/// A full frame slower than this (GPU time) is previewed while dragging.
pub const PREVIEW_ABOVE_MS: f64 = 250.0;
/// What a preview frame aims at: two of them (the one in flight when an input
/// comes, and the one that shows it) answer within 0.5 s.
pub const BUDGET_MS: f64 = 200.0;
/// Full quality once the input has been still this long.
pub const SETTLE: Duration = Duration::from_millis(350);
/// The coarsest preview: 1/16 of the sides.
pub const MAX_SCALE: u32 = 16;
/// Cache and light buffers are never smaller than their settings allow.
const MIN_BUFFER: u32 = 16;

/// Whether the viewer previews while dragging.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PreviewMode {
    /// Previews where a full frame is slow.
    On,
    /// Every frame at full quality (measurements, image comparisons).
    Off,
}

/// The preview's state: the last input that asks for one and what frames cost.
#[derive(Debug)]
pub struct Preview {
    mode: PreviewMode,
    last_input: Option<Instant>,
    /// GPU time of the last full frame, ms.
    full_ms: Option<f64>,
    /// The sides' divisor of the next preview (at least 2 once previewing).
    scale: u32,
}

impl Preview {
    pub fn new(mode: PreviewMode) -> Preview {
        Preview { mode, last_input: None, full_ms: None, scale: 1 }
    }

    /// A drag moved the camera, a light or a setting.
    pub fn input(&mut self, now: Instant) {
        self.last_input = Some(now);
    }

    /// The sides' divisor the next frame renders at: 1 (full quality) unless
    /// previews are on, an input came within [`SETTLE`] and a full frame is
    /// slower than [`PREVIEW_ABOVE_MS`].
    pub fn scale_at(&self, now: Instant) -> u32 {
        let dragging = self.last_input.is_some_and(|t| now.duration_since(t) < SETTLE);
        let slow = self.full_ms.is_some_and(|ms| ms > PREVIEW_ABOVE_MS);
        if self.mode == PreviewMode::On && dragging && slow {
            self.scale.max(2)
        } else {
            1
        }
    }

    /// When the input will have settled (the full frame is due), if a preview
    /// is showing now.
    pub fn settles_at(&self) -> Option<Instant> {
        self.last_input.map(|t| t + SETTLE)
    }

    /// A frame rendered at `scale` took `gpu_ms`: a preview over twice the
    /// budget or under a quarter of it halves or doubles the next one's sides
    /// (only then: each new size creates its images anew). Scales are powers
    /// of two, so every preview's images are of one kind (power-of-two sides
    /// where the full frame's are): lavapipe compiles a shader at its first
    /// dispatch, for a key that holds the images' state, and the one preview
    /// warmed up ([`warm_up`]) should stand for every scale (docs/viewer.md).
    pub fn measured(&mut self, scale: u32, gpu_ms: f64) {
        if !(gpu_ms.is_finite() && gpu_ms > 0.0) {
            return;
        }
        let ratio = (gpu_ms / BUDGET_MS).sqrt();
        if scale == 1 {
            self.full_ms = Some(gpu_ms);
            // A fresh start from the full frame's cost.
            self.scale = (ratio.ceil() as u32).next_power_of_two().clamp(2, MAX_SCALE);
        } else if scale == self.scale && ratio > 2f64.sqrt() {
            self.scale = (scale * 2).min(MAX_SCALE);
        } else if scale == self.scale && ratio < 0.5 {
            self.scale = (scale / 2).max(2);
        }
    }

    /// The scale a drag starting now would preview at, where one would (the
    /// viewer renders it once while idle: [`warm_up`]).
    pub fn next_preview_scale(&self) -> Option<u32> {
        let slow = self.full_ms.is_some_and(|ms| ms > PREVIEW_ABOVE_MS);
        (self.mode == PreviewMode::On && slow).then_some(self.scale.max(2))
    }
}

/// Renders one preview of `scene` at 1/`scale` of `size` and drops it, so the
/// first drag's preview finds its pipelines created and compiled for its
/// images' kind (IPSVI on lavapipe: 1-2 s otherwise, in the drag's first
/// frame). Its own images: the frame on screen is left as it is.
pub fn warm_up(
    ctx: &crate::vk::Context,
    scene: &Scene,
    volume: &crate::render::UploadedVolume,
    technique: crate::techniques::Technique,
    scale: u32,
    size: (u32, u32),
) -> Result<(), super::error::ViewerError> {
    let preview = preview_scene(scene, scale);
    let gpu = crate::render::GpuScene::on_volume(ctx, &preview, volume, crate::render::FrameImages::kept())?;
    let (width, height) = reduced(size, scale);
    let mut profiler = crate::vk::Profiler::new(ctx, super::frames::PROFILER_CAPACITY)?;
    crate::techniques::render(&gpu, technique, width, height, &mut profiler)?;
    Ok(())
}

/// `(width, height)` at 1/`scale` of the sides, at least 1 pixel each.
pub fn reduced(size: (u32, u32), scale: u32) -> (u32, u32) {
    let s = scale.max(1);
    ((size.0 / s).max(1), (size.1 / s).max(1))
}

/// `scene` for a preview at 1/`scale` of the image's sides: the resolutions
/// tied to the image shrink alike, so a cache texel covers the pixels it
/// covers at full size.
pub fn preview_scene(scene: &Scene, scale: u32) -> Scene {
    let mut preview = scene.clone();
    let shrink = |texels: u32| (texels / scale.max(1)).max(MIN_BUFFER).min(texels);
    let ipsvi = preview.settings.get_mut::<IpsviSettings>();
    // `cache_size = 0` resolved at the scene's image size (the window's
    // first; a resized window keeps it), shrunk alike.
    let full = ipsvi.sized_for(scene, scene.render.width, scene.render.height).cache_size;
    ipsvi.cache_size = shrink(full);
    let half_angle = preview.settings.get_mut::<HalfAngleSettings>();
    half_angle.light_buffer_size = shrink(half_angle.light_buffer_size);
    preview
}

#[cfg(test)]
mod tests {
    use super::*;

    const MS: Duration = Duration::from_millis(1);

    #[test]
    fn a_slow_frame_is_previewed_while_dragging_and_full_once_settled() {
        let t0 = Instant::now();
        let mut p = Preview::new(PreviewMode::On);
        assert_eq!(p.scale_at(t0), 1, "nothing measured, no input");
        // A 10 s full frame: sides / ceil(sqrt(50)) = 8.
        p.measured(1, 10_000.0);
        assert_eq!(p.scale_at(t0), 1, "no input yet");
        p.input(t0);
        assert_eq!(p.scale_at(t0 + 10 * MS), 8);
        assert_eq!(p.scale_at(t0 + SETTLE + MS), 1, "settled: full quality");
        // A preview near the budget keeps its scale (a new size costs a frame).
        p.measured(8, 1.3 * BUDGET_MS);
        p.measured(8, 0.3 * BUDGET_MS);
        assert_eq!(p.scale_at(t0), 8);
        // One far slower than the budget shrinks the next, at most by 2.
        p.measured(8, 3200.0);
        assert_eq!(p.scale_at(t0), 16);
        p.measured(16, 40.0);
        assert_eq!(p.scale_at(t0), 8, "one five times as fast as the budget grows it back");
        // A preview at a scale no longer current says nothing of the next one.
        p.measured(3, 5000.0);
        assert_eq!(p.scale_at(t0), 8);
    }

    #[test]
    fn the_scale_a_drag_would_take_is_known_before_it_and_a_power_of_two() {
        let mut p = Preview::new(PreviewMode::On);
        assert_eq!(p.next_preview_scale(), None, "nothing measured");
        // sqrt(6 s / 0.2 s) = 5.5: 8, not 6.
        p.measured(1, 6000.0);
        assert_eq!(p.next_preview_scale(), Some(8));
        p.measured(1, PREVIEW_ABOVE_MS * 0.9);
        assert_eq!(p.next_preview_scale(), None, "a fast full frame needs no preview");
        let mut off = Preview::new(PreviewMode::Off);
        off.measured(1, 6000.0);
        assert_eq!(off.next_preview_scale(), None);
    }

    #[test]
    fn a_fast_frame_or_previews_off_is_always_full_quality() {
        let t0 = Instant::now();
        let mut fast = Preview::new(PreviewMode::On);
        fast.measured(1, PREVIEW_ABOVE_MS * 0.9);
        fast.input(t0);
        assert_eq!(fast.scale_at(t0), 1);
        let mut off = Preview::new(PreviewMode::Off);
        off.measured(1, 10_000.0);
        off.input(t0);
        assert_eq!(off.scale_at(t0), 1);
    }

    #[test]
    fn a_preview_scene_shrinks_the_resolutions_tied_to_the_image() {
        let scene = crate::techniques::default_scene(&["volume.size=8".to_string()]).unwrap();
        let (width, height) = (scene.render.width, scene.render.height);
        let full = scene.settings.get::<IpsviSettings>().sized_for(&scene, width, height).cache_size;
        assert!(full >= 256, "cache_size = 0 resolves to {full}");
        let p = preview_scene(&scene, 4);
        assert_eq!(p.settings.get::<IpsviSettings>().cache_size, full / 4);
        assert_eq!(p.settings.get::<HalfAngleSettings>().light_buffer_size, 256 / 4);
        assert_eq!(preview_scene(&scene, 64).settings.get::<IpsviSettings>().cache_size, MIN_BUFFER);
        assert_eq!(reduced((256, 200), 8), (32, 25));
        assert_eq!(reduced((5, 5), 16), (1, 1));
    }
}
