use super::LineSync;
use crate::vk::barriers::{Access, Barrier};
use crate::vk::commands::Recorder;
use crate::vk::{Image, VkError};

/// `barrier-image`: after each block, image memory barriers narrowed to the
/// images the next block reads: the cache pair (illumination and front) and
/// the output it accumulates into.
pub struct ImageBarriers {
    cache_write_to_next_line_read: Barrier,
}

impl ImageBarriers {
    pub fn new(cache_and_output: &[&Image]) -> ImageBarriers {
        ImageBarriers {
            cache_write_to_next_line_read: Barrier::images(
                "cache_write_to_next_line_read",
                cache_and_output,
                Access::COMPUTE_WRITE,
                Access::COMPUTE_READ_WRITE,
            ),
        }
    }
}

impl LineSync for ImageBarriers {
    fn after_block(&mut self, rec: &mut Recorder, _block: usize) -> Result<(), VkError> {
        rec.barrier(&self.cache_write_to_next_line_read);
        Ok(())
    }
}
