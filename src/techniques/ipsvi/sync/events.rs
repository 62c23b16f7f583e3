use super::LineSync;
use crate::vk::barriers::{Access, Barrier};
use crate::vk::commands::Recorder;
use crate::vk::events::EventPool;
use crate::vk::{Context, VkError};
use std::any::Any;

/// `events`: split barriers, one event per block: set after the block, waited
/// for before whatever comes next (the next block, the next sweep's cache
/// initialisation, or the read-back), with the same dependency.
pub struct SplitBarriers {
    pool: EventPool,
    /// What each event orders: the block's cache writes before the next reads.
    cache_write_to_next_line_read: Barrier,
    /// The block whose event is set and not yet waited for.
    pending: Option<usize>,
}

impl SplitBarriers {
    /// Events for a frame of `blocks` blocks; they must outlive its submission.
    pub fn new(ctx: &Context, blocks: usize) -> Result<SplitBarriers, VkError> {
        Ok(SplitBarriers {
            pool: EventPool::new(ctx, blocks)?,
            cache_write_to_next_line_read: Barrier::memory(
                "cache_write_to_next_line_read",
                Access::COMPUTE_WRITE,
                Access::COMPUTE_READ_WRITE,
            ),
            pending: None,
        })
    }

    fn wait_pending(&mut self, rec: &mut Recorder) {
        if let Some(block) = self.pending.take() {
            rec.wait_event(self.pool.events[block], &self.cache_write_to_next_line_read);
        }
    }
}

impl LineSync for SplitBarriers {
    fn before_sweep(&mut self, rec: &mut Recorder) {
        self.wait_pending(rec);
    }

    fn before_block(&mut self, rec: &mut Recorder, _block: usize) {
        self.wait_pending(rec);
    }

    fn after_block(&mut self, rec: &mut Recorder, block: usize) -> Result<(), VkError> {
        rec.set_event(self.pool.events[block], &self.cache_write_to_next_line_read);
        self.pending = Some(block);
        Ok(())
    }

    fn end_frame(&mut self, rec: &mut Recorder) {
        self.wait_pending(rec);
    }

    fn frame_resources(self: Box<Self>) -> Vec<Box<dyn Any>> {
        vec![Box::new(self.pool)]
    }
}
