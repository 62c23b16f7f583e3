//! The light volume as a [`RenderTechnique`]: settings from `[lightvolume]`,
//! model (i), and one frame from an empty volume (an entire update).

use super::groups::contributions;
use super::illumination::IlluminationVolume;
use super::plan::{plan_update, PeakGeometry, PlanState};
use super::propagation::Capacity;
use super::render_frame;
use crate::render::frame_params::FrameParams;
use crate::render::{FrameResult, FrameSession, GpuScene, RenderError, RenderTechnique, ResourceNeed};
use crate::scene::{OpticalModel, Scene};
use crate::techniques::lightvolume::LightVolumeSettings;
use crate::vk::Profiler;
use glam::UVec3;

/// Light volume illumination with selective light updates.
pub struct LightVolume;

impl RenderTechnique for LightVolume {
    fn name(&self) -> &'static str {
        "lightvolume"
    }

    fn summary(&self) -> &'static str {
        "light volume: slice-by-slice propagation in coherence-based groups, one secondary command buffer per \
         group, then a ray cast ([lightvolume])"
    }

    /// The propagated quantity is each light's transmittance.
    fn reference_model(&self, _scene: &Scene) -> OpticalModel {
        OpticalModel::SingleScattering
    }

    /// Coloured when its propagation is (`lightvolume.chromatic`).
    fn reference_chromatic(&self, scene: &Scene) -> bool {
        scene.settings.get::<LightVolumeSettings>().chromatic
    }

    fn resources(&self, scene: &Scene, width: u32, height: u32) -> Vec<ResourceNeed> {
        let s = &scene.settings.get::<LightVolumeSettings>();
        let grid = IlluminationVolume::size_for(scene.volume.dims, s.scale);
        let mut needs = vec![
            // RGBA32F; the low words of the compensated sum, or a 1-voxel placeholder.
            ResourceNeed::image("lightvolume illumination", grid.to_array(), 16),
            ResourceNeed::image(
                "lightvolume illumination low",
                if s.compensated { grid } else { UVec3::ONE }.to_array(),
                16,
            ),
        ];
        // The passes of the first frame, as the renderer plans them.
        let lights: Vec<_> = scene.lights.iter().copied().map(Some).collect();
        let bx = scene.volume_box();
        let geometry = PeakGeometry { box_half: bx.half_extent, voxel_length: bx.voxel_length };
        let state = PlanState { invalid: true, ..Default::default() };
        let plan = plan_update(&[], &contributions(&lights, bx.half_extent), s, &state, geometry);
        if !plan.passes.is_empty() {
            let capacity = Capacity::needed(&plan.passes).grown(None, s.pass_lights);
            needs.push(ResourceNeed::of::<FrameParams>("lightvolume frame params", 1));
            needs.extend(capacity.resources(grid));
        }
        needs.push(ResourceNeed::of::<FrameParams>("lightvolume view params", 1));
        needs.push(ResourceNeed::output_image("lightvolume output", width, height));
        needs.extend(super::raycast::RayCast::resources(scene, width, height));
        needs
    }

    /// The volume kept across frames: a moved light is a selective update.
    fn session<'s>(&self, gpu: &'s GpuScene<'s>) -> Result<Option<Box<dyn FrameSession + 's>>, RenderError> {
        Ok(Some(Box::new(super::session::LightVolumeSession::new(gpu)?)))
    }

    fn warnings(&self, scene: &Scene) -> Vec<String> {
        use crate::render::light_grid_limits::{stiff_medium, StiffLimit};
        stiff_medium(scene, self.name(), StiffLimit::LightGrid).into_iter().collect()
    }

    fn check(&self, scene: &Scene) -> Result<(), RenderError> {
        crate::render::view_chunks::check_view_step(scene, self.name())
    }

    fn render(
        &self,
        gpu: &GpuScene,
        width: u32,
        height: u32,
        profiler: &mut Profiler,
    ) -> Result<FrameResult, RenderError> {
        let out = render_frame(gpu, width, height, profiler, false)?;
        let image = out.image.ok_or_else(|| RenderError::Invalid("light volume frame without an image".into()))?;
        Ok(FrameResult { image, dispatches: out.dispatches, barriers: out.barriers, shape: None })
    }
}
