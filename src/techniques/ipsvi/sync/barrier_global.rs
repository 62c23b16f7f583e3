use super::LineSync;
use crate::vk::barriers::{Access, Barrier};
use crate::vk::commands::Recorder;
use crate::vk::VkError;

/// `barrier-global`: one global memory barrier after each block (the default).
pub struct GlobalBarrier;

impl LineSync for GlobalBarrier {
    fn after_block(&mut self, rec: &mut Recorder, _block: usize) -> Result<(), VkError> {
        rec.barrier(&Barrier::memory(
            "cache_write_to_next_line_read",
            Access::COMPUTE_WRITE,
            Access::COMPUTE_READ_WRITE,
        ));
        Ok(())
    }
}
