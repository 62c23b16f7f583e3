use super::{GlobalBarrier, LineSync};
use crate::techniques::ipsvi::merged_steps::LineDispatch;
use crate::vk::commands::{Recorder, SecondaryCommands};
use crate::vk::pipeline::ComputePipeline;
use crate::vk::{Context, VkError};
use ash::vk;
use std::any::Any;

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

/// `secondary` with per-line timestamps (`bench sync`'s traces): each sweep's
/// blocks and the global barrier after each, recorded into a secondary
/// command buffer for this frame (the profiler's queries are the frame's)
/// and executed from the primary. The device runs what
/// [`ReplayedSweeps`] replays, barriers inside a secondary; only the host's
/// recording is per frame, and that is outside the timestamps.
#[derive(Default)]
pub struct RerecordedSweeps {
    recorded: Vec<SecondaryCommands>,
}

impl LineSync for RerecordedSweeps {
    fn records_sweeps_per_frame(&self) -> bool {
        true
    }

    fn keep_secondary(&mut self, recorded: SecondaryCommands) {
        self.recorded.push(recorded);
    }

    fn after_block(&mut self, rec: &mut Recorder, block: usize) -> Result<(), VkError> {
        GlobalBarrier.after_block(rec, block)
    }

    fn frame_resources(self: Box<Self>) -> Vec<Box<dyn Any>> {
        self.recorded.into_iter().map(|r| Box::new(r) as Box<dyn Any>).collect()
    }
}

/// One secondary command buffer per sweep (in frame order, `sweeps` as
/// (first dispatch, dispatch count) of `dispatches`; merged, the frame is one
/// sweep of steps): its dispatches and the barrier after each, parameters read
/// from buffers by the pushed index.
/// A secondary inherits nothing: it binds the line pipeline, `line_set`, and
/// per block its parity's set 1 of `sides`.
pub fn record_sweeps(
    ctx: &Context,
    sweeps: &[(usize, usize)],
    dispatches: &[LineDispatch],
    line: &ComputePipeline,
    line_set: vk::DescriptorSet,
    sides: [vk::DescriptorSet; 2],
) -> Result<SecondaryCommands, VkError> {
    SecondaryCommands::record(ctx, "ipsvi sweep", sweeps.len(), |i, rec| {
        let (first, count) = sweeps[i];
        rec.bind(line, line_set);
        for d in &dispatches[first..first + count] {
            rec.bind_set1(line, sides[d.parity as usize]);
            rec.push(line, &d.index);
            rec.dispatch(d.groups, 1, 1);
            GlobalBarrier.after_block(rec, 0)?;
        }
        Ok(())
    })
}
