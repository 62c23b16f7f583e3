use super::LineSync;
use crate::vk::commands::Recorder;
use crate::vk::pipeline::ComputePipeline;
use crate::vk::VkError;
use ash::vk;

/// `submits`: one queue submission per block, ordered by a timeline semaphore
/// (`Recorder::split_submission`): the cost of host-visible granularity.
pub struct SubmissionPerBlock;

impl LineSync for SubmissionPerBlock {
    fn bind_line(&self, rec: &mut Recorder, line: &ComputePipeline, set: vk::DescriptorSet, side: vk::DescriptorSet) {
        // A new command buffer starts with nothing bound.
        rec.bind(line, set);
        rec.bind_set1(line, side);
    }

    fn after_block(&mut self, rec: &mut Recorder, _block: usize) -> Result<(), VkError> {
        rec.split_submission()
    }
}
