//! Frame after frame of one uploaded scene (the viewer): a [`FrameSession`]
//! keeps what its technique may keep between frames. A technique without state
//! across frames renders each frame anew through its own `render`; one with
//! state (the light volume's selective updates) hands out its own session
//! through [`RenderTechnique::session`](super::RenderTechnique::session).

use super::error::RenderError;
use super::frame_result::FrameResult;
use super::gpu_scene::GpuScene;
use super::recorded_frame::RecordedFrame;
use super::technique::RenderTechnique;
use crate::scene::Light;
use crate::vk::{Profiler, Recorder};

pub trait FrameSession {
    /// Renders one `width` x `height` frame with `lights` (the scene's lights as
    /// edited since the session began; `None`: switched off).
    fn frame(
        &mut self,
        lights: &[Option<Light>],
        width: u32,
        height: u32,
        profiler: &mut Profiler,
    ) -> Result<FrameResult, RenderError>;

    /// Records one frame into `rec`, a command buffer its caller submits (see
    /// [`RenderTechnique::record`]); `None`: this session cannot, use `frame`.
    fn record(
        &mut self,
        _lights: &[Option<Light>],
        _rec: &mut Recorder,
        _width: u32,
        _height: u32,
        _profiler: &mut Profiler,
    ) -> Result<Option<RecordedFrame>, RenderError> {
        Ok(None)
    }

    /// Whether a recorded frame reuses GPU resources of the previous one (the
    /// light volume): then its caller lets the previous frame finish before
    /// `record`; otherwise each frame allocates its own, and frames overlap.
    fn reuses_gpu_resources(&self) -> bool {
        false
    }

    /// Whether `frame` follows edited lights; if not, a light change needs a
    /// new session on the re-uploaded scene.
    fn follows_lights(&self) -> bool;

    /// Secondary command buffers the last frame recorded; those it executed
    /// beyond these were recorded by earlier frames and replayed.
    fn secondaries_recorded(&self) -> usize {
        0
    }

    /// What the last frame decided, in words (the light volume's update kind
    /// and its reason).
    fn last_decision(&self) -> Option<String> {
        None
    }
}

/// Each frame rendered anew by the technique's `render` (its scene's lights).
pub struct EachFrameAnew<'s> {
    pub technique: &'s dyn RenderTechnique,
    pub gpu: &'s GpuScene<'s>,
}

impl FrameSession for EachFrameAnew<'_> {
    fn frame(
        &mut self,
        _lights: &[Option<Light>],
        width: u32,
        height: u32,
        profiler: &mut Profiler,
    ) -> Result<FrameResult, RenderError> {
        self.technique.render(self.gpu, width, height, profiler)
    }

    fn record(
        &mut self,
        _lights: &[Option<Light>],
        rec: &mut Recorder,
        width: u32,
        height: u32,
        profiler: &mut Profiler,
    ) -> Result<Option<RecordedFrame>, RenderError> {
        self.technique.record(self.gpu, rec, width, height, profiler)
    }

    fn follows_lights(&self) -> bool {
        false
    }
}
