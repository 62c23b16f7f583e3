use super::LineSync;
use crate::vk::commands::{Recorder, SecondaryCommands};
use crate::vk::pipeline::ComputePipeline;
use crate::vk::VkError;
use ash::vk;
use std::any::Any;

/// A strategy's synchronization after every other block only (blocks 0, 2,
/// 4, ... in frame order), nothing after the others: racy by design. `bench
/// sync` times the gaps after both kinds of block in the same frame, so what
/// the machine did during the frame is common to both and cancels in their
/// difference. Never for images anyone looks at.
pub struct EveryOther<'a> {
    inner: Box<dyn LineSync + 'a>,
}

impl<'a> EveryOther<'a> {
    pub fn new(inner: Box<dyn LineSync + 'a>) -> EveryOther<'a> {
        EveryOther { inner }
    }

    /// Whether the boundary after `block` is synchronized.
    pub fn synchronizes_after(block: usize) -> bool {
        block.is_multiple_of(2)
    }
}

impl LineSync for EveryOther<'_> {
    fn before_sweep(&mut self, rec: &mut Recorder) {
        self.inner.before_sweep(rec);
    }

    fn records_sweeps_per_frame(&self) -> bool {
        self.inner.records_sweeps_per_frame()
    }

    fn keep_secondary(&mut self, recorded: SecondaryCommands) {
        self.inner.keep_secondary(recorded);
    }

    fn before_block(&mut self, rec: &mut Recorder, block: usize) {
        self.inner.before_block(rec, block);
    }

    fn bind_line(&self, rec: &mut Recorder, line: &ComputePipeline, set: vk::DescriptorSet, side: vk::DescriptorSet) {
        self.inner.bind_line(rec, line, set, side);
    }

    fn after_block(&mut self, rec: &mut Recorder, block: usize) -> Result<(), VkError> {
        if EveryOther::synchronizes_after(block) {
            self.inner.after_block(rec, block)
        } else {
            Ok(())
        }
    }

    fn end_frame(&mut self, rec: &mut Recorder) {
        self.inner.end_frame(rec);
    }

    fn frame_resources(self: Box<Self>) -> Vec<Box<dyn Any>> {
        self.inner.frame_resources()
    }
}
