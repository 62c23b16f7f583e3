use super::LineSync;
use crate::vk::commands::Recorder;
use crate::vk::VkError;

/// `racy`: RACY, nothing between blocks, for cost comparison only; the image
/// is undefined and synchronization validation reports the hazard.
pub struct Unsynchronized;

impl LineSync for Unsynchronized {
    fn after_block(&mut self, _rec: &mut Recorder, _block: usize) -> Result<(), VkError> {
        Ok(())
    }
}
