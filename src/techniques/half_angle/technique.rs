//! Half-angle slicing as a [`RenderTechnique`]: settings from `[half_angle]`,
//! model (i), and the frame of [`super::render`].

use super::LightBufferParams;
use crate::render::frame_params::FrameParams;
use crate::render::raycast::{self, Shading};
use crate::render::{FrameResult, GpuScene, RecordedFrame, RenderError, RenderTechnique, ResourceNeed};
use crate::scene::{OpticalModel, Scene};
use crate::techniques::half_angle::HalfAngleSettings;
use crate::vk::{Profiler, Recorder};

/// Half-angle slicing.
pub struct HalfAngle;

impl RenderTechnique for HalfAngle {
    fn name(&self) -> &'static str {
        "half-angle"
    }

    fn summary(&self) -> &'static str {
        "half-angle slicing: one dispatch and barrier per slice, one light ([half_angle])"
    }

    /// Slices carry the transmittance alone.
    fn reference_model(&self, _scene: &Scene) -> OpticalModel {
        OpticalModel::SingleScattering
    }

    /// One transmittance in the light buffer.
    fn reference_chromatic(&self, _scene: &Scene) -> bool {
        false
    }

    fn resources(&self, scene: &Scene, width: u32, height: u32) -> Vec<ResourceNeed> {
        if scene.lights.is_empty() {
            return raycast::resources(scene, Shading::EmissionOnly, width, height);
        }
        let n = scene.settings.get::<HalfAngleSettings>().light_buffer_size;
        vec![
            ResourceNeed::of::<FrameParams>("frame params", 1),
            ResourceNeed::of::<LightBufferParams>("half-angle light buffer", 1),
            // R32F transmittance, ping-pong.
            ResourceNeed::image("half-angle light a", [n, n, 1], 4),
            ResourceNeed::image("half-angle light b", [n, n, 1], 4),
            ResourceNeed::output_image("half-angle eye buffer", width, height),
        ]
    }

    fn check(&self, scene: &Scene) -> Result<(), RenderError> {
        match scene.lights.len() {
            0 => crate::render::view_chunks::check_view_step(scene, self.name()),
            _ => super::check(scene),
        }
    }

    fn warnings(&self, scene: &Scene) -> Vec<String> {
        use crate::render::light_grid_limits::{camera_inside, stiff_medium, StiffLimit, MIN_HALF_ANGLE_SLICES};
        let mut out: Vec<String> =
            [stiff_medium(scene, self.name(), StiffLimit::LightGrid), camera_inside(scene, self.name())]
                .into_iter()
                .flatten()
                .collect();
        let slicing =
            (scene.lights.len() == 1).then(|| super::slicing(scene, &scene.settings.get::<HalfAngleSettings>()).ok());
        if let Some(slicing) = slicing.flatten() {
            if slicing.count < MIN_HALF_ANGLE_SLICES {
                out.push(format!(
                    "half-angle: {} slices through the volume (slice step {} voxels: render.step or \
                     half_angle.slice_step) carry its light too coarsely, so its image may be far from the reference; \
                     use a step below {:.3} voxels",
                    slicing.count,
                    scene.settings.get::<HalfAngleSettings>().slice_step_voxels(scene),
                    scene.settings.get::<HalfAngleSettings>().slice_step_voxels(scene) * slicing.count as f32
                        / MIN_HALF_ANGLE_SLICES as f32
                ));
            }
        }
        out
    }

    fn render(
        &self,
        gpu: &GpuScene,
        width: u32,
        height: u32,
        profiler: &mut Profiler,
    ) -> Result<FrameResult, RenderError> {
        super::render(gpu, width, height, profiler)
    }

    /// Front to back, the last slice adds the background: nothing is left to
    /// the host, so the frame records into the viewer's command buffer too.
    fn record(
        &self,
        gpu: &GpuScene,
        rec: &mut Recorder,
        width: u32,
        height: u32,
        profiler: &mut Profiler,
    ) -> Result<Option<RecordedFrame>, RenderError> {
        super::record(gpu, width, height, rec, profiler).map(Some)
    }
}
