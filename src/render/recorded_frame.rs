//! A technique's frame recorded into a command buffer its caller submits: the
//! one recording path of both `render` (which adds its read-back) and the
//! viewer (which adds its present pass, in the same submission). The frame is
//! left in the technique's RGBA32F output image, in [`FRAME_OUTPUT_LAYOUT`],
//! last written as [`FRAME_OUTPUT_WRITE`]: a reader's barrier starts there.

use super::error::RenderError;
use super::frame_result::FrameResult;
use super::gpu_scene::GpuScene;
use super::output::OutputImage;
use crate::vk::barriers::Access;
use crate::vk::commands::submit_and_wait_or;
use crate::vk::Recorder;
use ash::vk;
use std::any::Any;
use std::sync::Arc;

/// The last access to a recorded frame's output image: compute-shader writes.
pub const FRAME_OUTPUT_WRITE: Access = Access::COMPUTE_WRITE;
/// The layout a recorded frame leaves its output image in.
pub const FRAME_OUTPUT_LAYOUT: vk::ImageLayout = vk::ImageLayout::GENERAL;

pub struct RecordedFrame {
    /// The frame, as [`FRAME_OUTPUT_WRITE`] left it in [`FRAME_OUTPUT_LAYOUT`].
    pub output: Arc<OutputImage>,
    /// Compute dispatches and pipeline barriers recorded for the frame.
    pub dispatches: u32,
    pub barriers: u32,
    /// What the recorded commands use besides the scene and the output
    /// (pipelines, parameter buffers, scratch images): the submitter keeps it
    /// until the submission finished.
    pub keep_alive: Vec<Box<dyn Any>>,
}

impl RecordedFrame {
    /// A frame whose counts are those `rec` holds now (it was recorded from
    /// the command buffer's start).
    pub fn counted(rec: &Recorder, output: Arc<OutputImage>, keep_alive: Vec<Box<dyn Any>>) -> RecordedFrame {
        RecordedFrame { output, dispatches: rec.dispatch_count, barriers: rec.barrier_count, keep_alive }
    }
}

/// Headless: the frame `record` records, then its read-back, submitted and
/// waited for; the counts include the read-back's barriers.
pub fn render_recorded(
    gpu: &GpuScene,
    record: impl FnOnce(&mut Recorder) -> Result<RecordedFrame, RenderError>,
) -> Result<FrameResult, RenderError> {
    let (frame, readback, dispatches, barriers) = submit_and_wait_or(gpu.ctx, "frame", |rec| {
        let frame = record(rec)?;
        let readback = frame.output.readback_buffer(gpu.ctx)?;
        frame.output.record_readback(rec, &readback);
        Ok::<_, RenderError>((frame, readback, rec.dispatch_count, rec.barrier_count))
    })?;
    Ok(FrameResult { image: frame.output.read(&readback)?, dispatches, barriers, shape: None })
}
