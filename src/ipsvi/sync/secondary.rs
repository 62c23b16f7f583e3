use super::LineSync;
use crate::ipsvi::gpu_params::BlockParams;
use crate::vk::barriers::{Access, Barrier};
use crate::vk::commands::{Recorder, SecondaryCommands};
use crate::vk::pipeline::ComputePipeline;
use crate::vk::{Context, VkError};
use ash::vk;

/// `secondary`: each sweep's blocks and the global barrier after each, recorded
/// once into a secondary command buffer ([`record_sweeps`]) and executed from
/// every frame's primary.
pub struct ReplayedSweeps<'r> {
    recorded: &'r SecondaryCommands,
}

impl<'r> ReplayedSweeps<'r> {
    pub fn new(recorded: &'r SecondaryCommands) -> ReplayedSweeps<'r> {
        ReplayedSweeps { recorded }
    }
}

impl LineSync for ReplayedSweeps<'_> {
    fn replay_sweep(&mut self, rec: &mut Recorder, sweep: usize) -> bool {
        rec.execute(self.recorded, sweep);
        true
    }

    /// Unreached: every sweep is replayed.
    fn after_block(&mut self, _rec: &mut Recorder, _block: usize) -> Result<(), VkError> {
        Ok(())
    }
}

/// One secondary command buffer per sweep (in frame order, `sweeps` as
/// (first block record, record count)): its blocks and the
/// barrier after each, parameters read from the blocks buffer by block index.
/// A secondary inherits nothing: it binds the line pipelines and `line_set`.
pub fn record_sweeps(
    ctx: &Context,
    sweeps: &[(usize, usize)],
    block_records: &[BlockParams],
    lines: &[ComputePipeline; 2],
    line_set: vk::DescriptorSet,
    workgroups: impl Fn(&BlockParams) -> u32,
) -> Result<SecondaryCommands, VkError> {
    SecondaryCommands::record(ctx, "ipsvi sweep", sweeps.len(), |i, rec| {
        let (first, count) = sweeps[i];
        rec.bind(&lines[0], line_set);
        for (k, record) in block_records.iter().enumerate().skip(first).take(count) {
            let line = &lines[record.parity as usize];
            rec.bind_pipeline(line);
            rec.push(line, &(k as u32));
            rec.dispatch(workgroups(record), 1, 1);
            rec.barrier(&Barrier::memory(
                "cache_write_to_next_line_read",
                Access::COMPUTE_WRITE,
                Access::COMPUTE_READ_WRITE,
            ));
        }
        Ok(())
    })
}
