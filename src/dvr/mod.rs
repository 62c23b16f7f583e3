//! Baselines: unshaded emission-absorption DVR and gradient Blinn-Phong, one
//! dispatch each of the plain ray cast ([`crate::render::raycast`]). Compared
//! with the optical model the scene names.

use crate::render::raycast::{self, Shading};
use crate::render::view_chunks::check_view_step;
use crate::render::{FrameResult, GpuScene, RenderError, RenderTechnique, ResourceNeed};
use crate::scene::{OpticalModel, Scene};
use crate::vk::Profiler;

/// Unshaded emission-absorption ray casting.
pub struct Dvr;

/// Gradient Blinn-Phong ray casting, no shadows.
pub struct Phong;

impl RenderTechnique for Dvr {
    fn name(&self) -> &'static str {
        "dvr"
    }
    fn summary(&self) -> &'static str {
        "unshaded emission-absorption ray casting (one dispatch; chunked past the loop limit)"
    }
    fn reference_model(&self, scene: &Scene) -> OpticalModel {
        scene.reference.model
    }
    fn resources(&self, _scene: &Scene, width: u32, height: u32) -> Vec<ResourceNeed> {
        raycast::resources(Shading::Unshaded, width, height)
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
        raycast::render(gpu, Shading::Unshaded, width, height, profiler)
    }
}

impl RenderTechnique for Phong {
    fn name(&self) -> &'static str {
        "phong"
    }
    fn summary(&self) -> &'static str {
        "gradient Blinn-Phong ray casting, no shadows (one dispatch; chunked past the loop limit)"
    }
    fn reference_model(&self, scene: &Scene) -> OpticalModel {
        scene.reference.model
    }
    fn resources(&self, _scene: &Scene, width: u32, height: u32) -> Vec<ResourceNeed> {
        raycast::resources(Shading::BlinnPhong, width, height)
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
        raycast::render(gpu, Shading::BlinnPhong, width, height, profiler)
    }
}
