//! IPSVI across viewer frames: one [`IpsviRenderer`] (pipelines, descriptor
//! sets, cache and position images, parameter and block buffers, and for the
//! `secondary` strategy its recorded sweeps) kept from frame to frame, and each
//! frame recorded into the caller's command buffer.
//!
//! What invalidates what: the session belongs to one uploaded scene, whose
//! camera, lights, transfer function and settings every part of the renderer
//! depends on (plans, parameter buffers, descriptor sets, specialization), so
//! an edit of any of them is a new session on the re-uploaded scene (the viewer
//! starts one: [`FrameSession::follows_lights`] is false). Within a session
//! only the frame size changes (a resized window): the renderer is rebuilt for
//! it, and its sweeps are recorded anew on the next `secondary` frame.

use super::renderer::IpsviRenderer;
use super::sync_strategy::SyncStrategy;
use crate::render::raycast::{self, Shading};
use crate::render::view_chunks::ChunkSync;
use crate::render::{FrameResult, FrameSession, GpuScene, RecordedFrame, RenderError};
use crate::scene::settings_table::SettingsTable;
use crate::scene::Light;
use crate::techniques::ipsvi::IpsviSettings;
use crate::vk::{Profiler, Recorder};

pub struct IpsviSession<'s> {
    gpu: &'s GpuScene<'s>,
    /// Built for the size of the last frame; `None` before the first (and for
    /// a scene without lights, which the emission ray cast renders).
    renderer: Option<IpsviRenderer<'s>>,
    size: (u32, u32),
    /// Secondary command buffers the last frame recorded.
    recorded: usize,
}

impl<'s> IpsviSession<'s> {
    pub fn new(gpu: &'s GpuScene<'s>) -> Result<Self, RenderError> {
        gpu.scene.settings.get::<IpsviSettings>().validate()?;
        Ok(IpsviSession { gpu, renderer: None, size: (0, 0), recorded: 0 })
    }

    fn sync(&self) -> SyncStrategy {
        self.gpu.scene.settings.get::<IpsviSettings>().sync
    }

    /// The renderer for a `width` x `height` frame, rebuilt if the size changed
    /// (the caller let the previous frame finish: the old one may go).
    fn renderer(&mut self, width: u32, height: u32) -> Result<&mut IpsviRenderer<'s>, RenderError> {
        if self.renderer.is_none() || self.size != (width, height) {
            self.renderer = None;
            self.renderer =
                Some(IpsviRenderer::new(self.gpu, &self.gpu.scene.settings.get::<IpsviSettings>(), width, height)?);
            self.size = (width, height);
        }
        Ok(self.renderer.as_mut().expect("built above"))
    }
}

impl FrameSession for IpsviSession<'_> {
    fn frame(
        &mut self,
        _lights: &[Option<Light>],
        width: u32,
        height: u32,
        profiler: &mut Profiler,
    ) -> Result<FrameResult, RenderError> {
        if self.gpu.scene.lights.is_empty() {
            self.recorded = 0;
            return raycast::emission_only(self.gpu, width, height, profiler);
        }
        let sync = self.sync();
        let renderer = self.renderer(width, height)?;
        let before = renderer.recorded_secondaries();
        let out = renderer.frame(profiler, sync)?;
        self.recorded = renderer.recorded_secondaries() - before;
        Ok(out)
    }

    /// Every strategy but `submits`, which needs several submissions: the
    /// viewer renders that one by `frame` and uploads it.
    fn record(
        &mut self,
        _lights: &[Option<Light>],
        rec: &mut Recorder,
        width: u32,
        height: u32,
        profiler: &mut Profiler,
    ) -> Result<Option<RecordedFrame>, RenderError> {
        let sync = self.sync();
        if sync == SyncStrategy::Submits {
            return Ok(None);
        }
        if self.gpu.scene.lights.is_empty() {
            self.recorded = 0;
            let frame = raycast::record_with(
                self.gpu,
                Shading::EmissionOnly,
                (width, height),
                rec,
                profiler,
                ChunkSync::Barrier,
            )?;
            return Ok(Some(frame));
        }
        let renderer = self.renderer(width, height)?;
        let before = renderer.recorded_secondaries();
        let frame = renderer.record(rec, profiler, sync)?;
        self.recorded = renderer.recorded_secondaries() - before;
        Ok(Some(frame))
    }

    /// The renderer's images and recorded sweeps serve every frame.
    fn reuses_gpu_resources(&self) -> bool {
        true
    }

    fn follows_lights(&self) -> bool {
        false
    }

    fn secondaries_recorded(&self) -> usize {
        self.recorded
    }
}
