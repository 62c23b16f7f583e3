//! How consecutive line blocks of a sweep are synchronized, one object per
//! [`SyncStrategy`](super::SyncStrategy): what a strategy records before a
//! sweep, before and after each block, and at the end of the frame, or the
//! whole sweep at once where it replays a recording. The renderer records the
//! sweep; each strategy names the barriers it adds for what they protect.

mod barrier_global;
mod barrier_image;
mod events;
mod racy;
mod secondary;
mod submits;

pub use barrier_global::GlobalBarrier;
pub use barrier_image::ImageBarriers;
pub use events::SplitBarriers;
pub use racy::Unsynchronized;
pub use secondary::{record_sweeps, ReplayedSweeps, RerecordedSweeps};
pub use submits::SubmissionPerBlock;

use crate::vk::commands::{Recorder, SecondaryCommands};
use crate::vk::pipeline::ComputePipeline;
use crate::vk::VkError;
use ash::vk;
use std::any::Any;

/// The synchronization between the line blocks of a frame. Blocks and sweeps
/// are numbered in frame order (the order of the blocks buffer).
pub trait LineSync {
    /// Before sweep initialisation overwrites the cache: the previous sweep's
    /// last block must be done with it.
    fn before_sweep(&mut self, _rec: &mut Recorder) {}

    /// Records all of `sweep`'s blocks and the synchronization between them at
    /// once and returns true, or returns false: the renderer records each block.
    fn replay_sweep(&mut self, _rec: &mut Recorder, _sweep: usize) -> bool {
        false
    }

    /// Whether each sweep's blocks go into a secondary command buffer recorded
    /// for this frame, with this object's synchronization and the profiler's
    /// per-line scopes, and executed from the primary (`secondary` timed per
    /// line: a secondary recorded once cannot carry one frame's queries).
    fn records_sweeps_per_frame(&self) -> bool {
        false
    }

    /// Keeps a secondary recorded for this frame until its submission finished
    /// (returned by `frame_resources`).
    fn keep_secondary(&mut self, _recorded: SecondaryCommands) {}

    /// Before `block`'s dispatch, with the line descriptor set bound for the sweep.
    fn before_block(&mut self, _rec: &mut Recorder, _block: usize) {}

    /// Binds the block's side of the ping-pong pairs (`side`, set 1); the
    /// pipeline and set 0 (`_set`) stay bound from the start of the sweep.
    fn bind_line(&self, rec: &mut Recorder, line: &ComputePipeline, _set: vk::DescriptorSet, side: vk::DescriptorSet) {
        rec.bind_set1(line, side);
    }

    /// After `block`'s dispatch: what orders it before the next block.
    fn after_block(&mut self, rec: &mut Recorder, block: usize) -> Result<(), VkError>;

    /// After the last sweep, before the output is read back.
    fn end_frame(&mut self, _rec: &mut Recorder) {}

    /// What the recorded frame uses of this object (the events of `events`):
    /// kept by the submitter until the submission finished.
    fn frame_resources(self: Box<Self>) -> Vec<Box<dyn Any>> {
        Vec::new()
    }
}
