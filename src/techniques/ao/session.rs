//! Technique `ao` across viewer frames: the preprocessing result, the uploaded
//! cluster ids and codebook, and the lookup computed once per session (the
//! paper: the codebook is uploaded once, the lookup recomputed per transfer-
//! function change). A TF, camera or light edit re-uploads the scene and
//! starts a new session ([`FrameSession::follows_lights`] is false), whose
//! first frame recomputes the lookup, without preprocessing again (the
//! technique keeps the last result in memory).

use super::render::AoRenderer;
use super::technique::preprocessed;
use super::AoSettings;
use crate::render::{FrameResult, FrameSession, GpuScene, RecordedFrame, RenderError};
use crate::scene::Light;
use crate::vk::{Profiler, Recorder};

pub struct AoSession<'s> {
    gpu: &'s GpuScene<'s>,
    renderer: AoRenderer,
    /// The lookup holds this session's transfer function.
    lookup_current: bool,
}

impl<'s> AoSession<'s> {
    pub fn new(gpu: &'s GpuScene<'s>) -> Result<Self, RenderError> {
        let settings = AoSettings::from_scene(gpu.scene)?;
        let pre = preprocessed(&gpu.scene.volume, &settings, Some(gpu.ctx), &mut |_| {})?;
        let renderer = AoRenderer::new(gpu, &pre, &settings)?;
        Ok(AoSession { gpu, renderer, lookup_current: false })
    }

    /// The lookup for this session's TF: its own submission, on the first frame.
    fn prepare(&mut self, profiler: &mut Profiler) -> Result<(), RenderError> {
        if !self.lookup_current {
            self.renderer.update_environment(self.gpu, profiler)?;
            self.lookup_current = true;
        }
        Ok(())
    }
}

impl FrameSession for AoSession<'_> {
    fn frame(
        &mut self,
        _lights: &[Option<Light>],
        width: u32,
        height: u32,
        profiler: &mut Profiler,
    ) -> Result<FrameResult, RenderError> {
        self.prepare(profiler)?;
        self.renderer.frame(self.gpu, (width, height), profiler)
    }

    fn record(
        &mut self,
        _lights: &[Option<Light>],
        rec: &mut Recorder,
        width: u32,
        height: u32,
        profiler: &mut Profiler,
    ) -> Result<Option<RecordedFrame>, RenderError> {
        self.prepare(profiler)?;
        self.renderer.record(self.gpu, (width, height), rec, profiler).map(Some)
    }

    fn follows_lights(&self) -> bool {
        false
    }
}
