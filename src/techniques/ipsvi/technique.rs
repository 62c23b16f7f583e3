//! IPSVI as a [`RenderTechnique`]: settings from `[ipsvi]`, model (ii), and the
//! frame of [`super::renderer`].

use super::cache_update::CacheUpdate;
use super::gpu_params::{BlockParams, SweepParams};
use super::line_kernel::LineKernel;
use super::renderer::{render_with, scene_plans};
use super::settings::EarlyTermination;
use crate::render::frame_params::FrameParams;
use crate::render::raycast::{self, Shading};
use crate::render::{FrameResult, FrameSession, GpuScene, RenderError, RenderTechnique, ResourceNeed};
use crate::scene::settings_table::SettingsTable;
use crate::scene::{OpticalModel, Scene};
use crate::techniques::ipsvi::IpsviSettings;
use crate::vk::Profiler;

/// Image plane sweep volume illumination.
pub struct Ipsvi;

impl RenderTechnique for Ipsvi {
    fn name(&self) -> &'static str {
        "ipsvi"
    }

    fn summary(&self) -> &'static str {
        "image plane sweep volume illumination: one dispatch and barrier per line block ([ipsvi])"
    }

    /// IPSVI carries emission along its light rays.
    fn reference_model(&self, _scene: &Scene) -> OpticalModel {
        OpticalModel::EmissiveScattering
    }

    /// One transmittance per light ray.
    fn reference_chromatic(&self, _scene: &Scene) -> bool {
        false
    }

    fn resources(&self, scene: &Scene, width: u32, height: u32) -> Vec<ResourceNeed> {
        if scene.lights.is_empty() {
            return raycast::resources(scene, Shading::EmissionOnly, width, height);
        }
        let s = &scene.settings.get::<IpsviSettings>().sized_for(scene, width, height);
        let plans = scene_plans(scene, s, width, height);
        let blocks: usize = plans.iter().flat_map(|p| &p.sweeps).map(|sweep| sweep.blocks.len()).sum();
        let sweeps: usize = plans.iter().map(|p| p.sweeps.len()).sum();
        let view_samples = s.cache_update == CacheUpdate::ViewSamples;
        let claims = s.records_claims();
        // A claim-only record ahead of each sweep's first block.
        let records = if claims { blocks + sweeps } else { blocks };
        // merge_sweeps: one cache (and claim keys, colour accumulation) per sweep, stacked in rows.
        let slots = if s.merge_sweeps && sweeps > 1 { sweeps as u32 } else { 1 };
        let cache = [s.cache_size, s.cache_size * slots, 1];
        // With packed_store each pair is one rgba32ui image and the unpacked ones are 1x1
        // (and the other way round); the view-sample pairs are 1x1 in light-rays mode.
        let small = [1, slots, 1];
        let (unpacked, history) = if s.packed_store { (small, cache) } else { (cache, small) };
        let sample = if view_samples && !s.packed_store { cache } else { small };
        let packed_sample = if view_samples && s.packed_store { cache } else { small };
        let n = u64::from(s.cache_size);
        let key_bytes = if claims { 2 * 8 * n * n * u64::from(slots) } else { 16 };
        // The step table: per step and sweep (block, first workgroup) after a header; a placeholder unmerged.
        let steps = plans.iter().flat_map(|p| &p.sweeps).map(|sweep| sweep.blocks.len() + claims as usize).max();
        let step_words = if slots > 1 { 2 + 2 * steps.unwrap_or(0) * sweeps } else { 4 };
        let mut needs = vec![
            ResourceNeed::output_image("ipsvi output", width, height),
            // Illumination: RGBA16F; front: R16_UINT.
            ResourceNeed::image("ipsvi cache a", unpacked, 8),
            ResourceNeed::image("ipsvi cache b", unpacked, 8),
            ResourceNeed::image("ipsvi front a", unpacked, 2),
            ResourceNeed::image("ipsvi front b", unpacked, 2),
            ResourceNeed::image("ipsvi cache samples a", sample, 8),
            ResourceNeed::image("ipsvi cache samples b", sample, 8),
            ResourceNeed::image("ipsvi cache stamps a", sample, 4),
            ResourceNeed::image("ipsvi cache stamps b", sample, 4),
            ResourceNeed::image("ipsvi history a", history, 16),
            ResourceNeed::image("ipsvi history b", history, 16),
            ResourceNeed::image("ipsvi packed samples a", packed_sample, 16),
            ResourceNeed::image("ipsvi packed samples b", packed_sample, 16),
            ResourceNeed::buffer("ipsvi claim keys", key_bytes),
            ResourceNeed::of::<FrameParams>("frame params", 1),
            ResourceNeed::of::<[f32; 4]>("ipsvi line planes", (width + height) as usize),
            ResourceNeed::of::<SweepParams>("ipsvi sweeps", scene.lights.len()),
            ResourceNeed::of::<BlockParams>("ipsvi blocks", records),
            ResourceNeed::of::<u32>("ipsvi steps", step_words),
            ResourceNeed::buffer("ipsvi line shape", super::line_shape::ShapeCounters::bytes(records)),
        ];
        if slots > 1 {
            needs.push(ResourceNeed::image("ipsvi sweep accumulation", [width, height * slots, 1], 16));
        }
        // The segmented kernel's stops: listed where a scene asks for that
        // kernel; `auto` picks it only on a GPU, where the list is a lower
        // bound (the frame holds these bytes more).
        if s.line_kernel == LineKernel::Segmented {
            let words = if s.early_termination == EarlyTermination::Off { 1 } else { width as usize * height as usize };
            needs.push(ResourceNeed::of::<u32>("ipsvi view stops", words));
        }
        if s.early_termination == EarlyTermination::ExitPoints {
            // The pre-pass resolution: RG32F depths, R32F l_max.
            let low = [width.div_ceil(s.ert_scale), height.div_ceil(s.ert_scale), 1];
            needs.push(ResourceNeed::image("ipsvi ert depths", low, 8));
            for name in ["ipsvi lmax a", "ipsvi lmax b", "ipsvi lmax"] {
                needs.push(ResourceNeed::image(name, low, 4));
            }
        } else {
            needs.push(ResourceNeed::image("ipsvi lmax placeholder", [1, 1, 1], 4));
        }
        needs
    }

    /// The renderer kept across frames, each recorded into the caller's
    /// command buffer (`submits` excepted: [`super::session`]).
    fn session<'s>(&self, gpu: &'s GpuScene<'s>) -> Result<Option<Box<dyn FrameSession + 's>>, RenderError> {
        Ok(Some(Box::new(super::session::IpsviSession::new(gpu)?)))
    }

    fn check(&self, scene: &Scene) -> Result<(), RenderError> {
        match scene.lights.len() {
            0 => crate::render::view_chunks::check_view_step(scene, self.name()),
            _ => super::view_budget::piecewise_steps(scene).map(|_| ()),
        }
    }

    fn render(
        &self,
        gpu: &GpuScene,
        width: u32,
        height: u32,
        profiler: &mut Profiler,
    ) -> Result<FrameResult, RenderError> {
        let settings = &gpu.scene.settings.get::<IpsviSettings>();
        settings.validate()?;
        render_with(gpu, settings, width, height, profiler, settings.sync)
    }

    fn warnings(&self, scene: &Scene) -> Vec<String> {
        use crate::render::light_grid_limits::{camera_inside, stiff_medium, StiffLimit};
        let view_samples = scene.settings.get::<IpsviSettings>().cache_update == CacheUpdate::ViewSamples;
        // The view-sample cache holds light at the depths of the samples that
        // wrote it: from inside the volume those lie beside the eye.
        let inside = camera_inside(scene, "ipsvi (cache_update = \"view-samples\")").filter(|_| view_samples);
        [stiff_medium(scene, self.name(), StiffLimit::ViewStep), inside].into_iter().flatten().collect()
    }

    fn settings_note(&self, scene: &Scene) -> Option<String> {
        let (width, height) = (scene.render.width, scene.render.height);
        let set = scene.settings.get::<IpsviSettings>();
        let s = &set.sized_for(scene, width, height);
        let write = match s.write_pass_run() {
            Some(pass) => format!(", cache_write: {}, write_pass: {}", s.cache_write.name(), pass.name()),
            None => String::new(),
        };
        let fronts = match (s.piecewise, s.per_texel_fronts(scene, width, height)) {
            (false, _) => "",
            (true, false) => ", read_fronts: blended",
            (true, true) => ", read_fronts: per-texel",
        };
        // View samples err least near a texel of about one pixel (docs/ipsvi.md).
        let auto = if set.cache_size == 0 { " (auto)" } else { "" };
        let texel = super::cache_plane::texel_pixels(scene, s, width, height)
            .map(|px| format!("; cache {}{auto}, texel {px:.2} px at the lit box's centre", s.cache_size))
            .unwrap_or_default();
        // The kernel `auto` takes depends on the device: the frame's line shape names it.
        let kernel = match s.segments {
            0 => format!("; line_kernel: {}", s.line_kernel.name()),
            n => format!("; line_kernel: {} x{n}", s.line_kernel.name()),
        };
        Some(format!(
            "ipsvi sync strategy: {}; cache_update: {}{write}{fronts}{texel}{kernel}",
            s.sync,
            s.cache_update.name()
        ))
    }
}
