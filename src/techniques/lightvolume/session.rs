//! The light volume across viewer frames: one [`LightVolumeRenderer`] kept from
//! frame to frame, so a moved light is a selective update of the volume, not a
//! rebuild.

use super::renderer::{LightVolumeRenderer, UpdateReport};
use crate::render::{FrameResult, FrameSession, GpuScene, RecordedFrame, RenderError};
use crate::scene::Light;
use crate::vk::{Profiler, Recorder};

pub struct LightVolumeSession<'s> {
    renderer: LightVolumeRenderer<'s>,
    last: Option<UpdateReport>,
}

impl<'s> LightVolumeSession<'s> {
    pub fn new(gpu: &'s GpuScene<'s>) -> Result<Self, RenderError> {
        Ok(LightVolumeSession { renderer: LightVolumeRenderer::new(gpu)?, last: None })
    }
}

impl FrameSession for LightVolumeSession<'_> {
    fn frame(
        &mut self,
        lights: &[Option<Light>],
        width: u32,
        height: u32,
        profiler: &mut Profiler,
    ) -> Result<FrameResult, RenderError> {
        let out = self.renderer.render(lights, width, height, profiler, false)?;
        let image = out.image.ok_or_else(|| RenderError::Invalid("light volume frame without an image".into()))?;
        self.last = Some(out.update);
        Ok(FrameResult { image, dispatches: out.dispatches, barriers: out.barriers, shape: None })
    }

    fn record(
        &mut self,
        lights: &[Option<Light>],
        rec: &mut Recorder,
        width: u32,
        height: u32,
        profiler: &mut Profiler,
    ) -> Result<Option<RecordedFrame>, RenderError> {
        let recorded = self.renderer.record_frame(rec, lights, Some((width, height)), profiler)?;
        let output =
            recorded.output.ok_or_else(|| RenderError::Invalid("light volume frame without an image".into()))?;
        self.last = Some(recorded.update);
        Ok(Some(RecordedFrame::counted(rec, output, Vec::new())))
    }

    fn reuses_gpu_resources(&self) -> bool {
        true
    }

    fn follows_lights(&self) -> bool {
        true
    }

    fn secondaries_recorded(&self) -> usize {
        self.last.as_ref().map_or(0, |u| u.recorded)
    }

    fn last_decision(&self) -> Option<String> {
        self.last.as_ref().map(|u| format!("{}: {}", u.plan.kind.scope_name(), u.plan.reason))
    }
}
