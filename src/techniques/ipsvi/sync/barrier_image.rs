use super::LineSync;
use crate::vk::barriers::{Access, Barrier};
use crate::vk::commands::Recorder;
use crate::vk::{Buffer, Image, VkError};

/// `barrier-image`: after each block, image memory barriers narrowed to the
/// images the next block reads: the cache pairs (illumination and front; with
/// view samples also the sample pair) and the output it accumulates into, plus
/// buffer barriers on the claim keys of `cache_write = "farthest"` and on the
/// shape counters every block adds to (src/techniques/ipsvi/line_shape.rs).
pub struct ImageBarriers {
    cache_write_to_next_line_read: Barrier,
}

impl ImageBarriers {
    pub fn new(cache_and_output: &[&Image], buffers: &[&Buffer]) -> ImageBarriers {
        ImageBarriers {
            cache_write_to_next_line_read: Barrier::images_and_buffers(
                "cache_write_to_next_line_read",
                cache_and_output,
                buffers,
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
