//! Baselines: unshaded emission-absorption DVR and gradient Blinn-Phong, one
//! dispatch each of the plain ray cast ([`crate::render::raycast`]). Compared
//! with the optical model the scene names.

use crate::render::raycast::{self, Shading};
use crate::render::view_chunks::check_view_step;
use crate::render::view_chunks::ChunkSync;
use crate::render::{FrameResult, GpuScene, RecordedFrame, RenderError, RenderTechnique, ResourceNeed};
use crate::scene::{OpticalModel, Scene};
use crate::vk::{Profiler, Recorder};

/// A baseline: the plain ray cast with one shading.
pub struct Baseline {
    shading: Shading,
    summary: &'static str,
}

/// Unshaded emission-absorption ray casting.
pub const DVR: Baseline = Baseline {
    shading: Shading::Unshaded,
    summary: "unshaded emission-absorption ray casting (one dispatch; chunked past the loop limit)",
};

/// Gradient Blinn-Phong ray casting, no shadows.
pub const PHONG: Baseline = Baseline {
    shading: Shading::BlinnPhong,
    summary: "gradient Blinn-Phong ray casting, no shadows (one dispatch; chunked past the loop limit)",
};

impl RenderTechnique for Baseline {
    fn name(&self) -> &'static str {
        self.shading.pass_name()
    }
    fn summary(&self) -> &'static str {
        self.summary
    }
    fn reference_model(&self, scene: &Scene) -> OpticalModel {
        scene.reference.model
    }
    fn resources(&self, scene: &Scene, width: u32, height: u32) -> Vec<ResourceNeed> {
        raycast::resources(scene, self.shading, width, height)
    }
    fn check(&self, scene: &Scene) -> Result<(), RenderError> {
        check_view_step(scene, self.name())
    }
    fn render(
        &self,
        gpu: &GpuScene,
        width: u32,
        height: u32,
        profiler: &mut Profiler,
    ) -> Result<FrameResult, RenderError> {
        raycast::render(gpu, self.shading, width, height, profiler)
    }
    fn record(
        &self,
        gpu: &GpuScene,
        rec: &mut Recorder,
        width: u32,
        height: u32,
        profiler: &mut Profiler,
    ) -> Result<Option<RecordedFrame>, RenderError> {
        raycast::record_with(gpu, self.shading, (width, height), rec, profiler, ChunkSync::Barrier).map(Some)
    }
}
