//! The chain workload's frames (glsl/sync_chain.comp): `lines` dispatches of
//! `invocations` each, every invocation a dependent chain of `trips` x
//! [`STEPS_PER_TRIP`] fused multiply-adds seeded by the previous line's
//! output, synchronized between lines by one of the study's strategies
//! (`crate::techniques::ipsvi::sync`, the same objects the sweep records with). The lines
//! ping-pong through the two halves of one device-local buffer, each side a
//! set 1 of {in, out} on separate bindings, so synchronization validation
//! sees which half a line reads and which it writes: the baseline's hazards
//! are reported, a strategy's barriers are load-bearing.
//!
//! Each frame's last output is read back and checked: every invocation holds
//! its seed plus the number of lines (each line adds exactly 1 whatever its
//! chain's length), so a chain cut short or a line that read before its
//! predecessor wrote fails the frame ([`ChainLines::frame`]), for every
//! strategy but the racy baseline.

use crate::bench::experiments::ExperimentError;
use crate::shaders::sync_chain as shader;
use crate::techniques::ipsvi::sync::{
    GlobalBarrier, ImageBarriers, LineSync, ReplayedSweeps, RerecordedSweeps, SplitBarriers, SubmissionPerBlock,
    Unsynchronized,
};
use crate::techniques::ipsvi::SyncStrategy;
use crate::vk::barriers::{Access, Barrier};
use crate::vk::commands::{submit_and_wait_or, Recorder, SecondaryCommands};
use crate::vk::descriptors::Resource;
use crate::vk::pipeline::{ComputePipeline, ComputePipelineDesc};
use crate::vk::staging::{copy_buffer, device_buffer_with_data, readback_buffer};
use crate::vk::{Buffer, Context, Profiler, VkError};
use ash::vk;
use bytemuck::{Pod, Zeroable};
use gpu_allocator::MemoryLocation;
use std::cell::OnceCell;

/// Dependent steps per loop trip (glsl/sync_chain.comp STEPS_PER_TRIP).
pub const STEPS_PER_TRIP: u32 = 64;
/// Invocations per workgroup (glsl/sync_chain.comp local_size_x).
pub const GROUP: u32 = 64;
/// The profiler scope (and debug label) of a chain frame's lines, and of each line.
pub const FRAME_SCOPE: &str = "sync_chain";
pub const LINE_SCOPE: &str = "sync_chain_line";

/// Mirrors the `Chain` push constants.
#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct ChainPush {
    trips: u32,
    invocations: u32,
    first_line: u32,
    scale: f32,
    offset: f32,
}

crate::assert_gpu_layout!(ChainPush, shader::layout::CHAIN, [trips, invocations, first_line, scale, offset]);

/// An invocation's seed (small integers: exact in float, and different per invocation).
fn seed(i: u32) -> f32 {
    (i % 1024) as f32
}

/// What a chain frame recorded.
#[derive(Clone, Copy, Debug)]
pub struct ChainFrame {
    pub dispatches: u32,
    pub barriers: u32,
}

/// One configuration's chain frames.
pub struct ChainLines<'a> {
    ctx: &'a Context,
    lines: u32,
    invocations: u32,
    trips: u32,
    pipeline: ComputePipeline,
    set0: vk::DescriptorSet,
    sides: [vk::DescriptorSet; 2],
    _seeds: Buffer,
    values: Buffer,
    readback: Buffer,
    /// `secondary`: the lines and their barriers, recorded on first use.
    secondaries: OnceCell<SecondaryCommands>,
}

impl<'a> ChainLines<'a> {
    /// Frames of `lines` lines of `invocations` (rounded up to a workgroup),
    /// each chain `trips` loop trips long.
    pub fn new(ctx: &'a Context, lines: u32, invocations: u32, trips: u32) -> Result<ChainLines<'a>, VkError> {
        let invocations = invocations.max(1).div_ceil(GROUP) * GROUP;
        let desc =
            ComputePipelineDesc { name: FRAME_SCOPE, shader: &shader::INTERFACE, specialization: &[], max_sets: 1 };
        let mut pipeline = ComputePipeline::new(ctx, &desc)?;
        let seeds: Vec<f32> = (0..invocations).map(seed).collect();
        let seeds = device_buffer_with_data(ctx, "sync chain seeds", &seeds, vk::BufferUsageFlags::STORAGE_BUFFER)?;
        let half = invocations as u64 * 4;
        let usage = vk::BufferUsageFlags::STORAGE_BUFFER | vk::BufferUsageFlags::TRANSFER_SRC;
        let values = Buffer::new(ctx, "sync chain values", 2 * half, usage, MemoryLocation::GpuOnly)?;
        let readback = readback_buffer(ctx, "sync chain readback", 2 * half)?;
        let set0 = pipeline.create_set(&[(shader::SEEDS, Resource::StorageBuffer(&seeds))])?;
        let window = |offset: u64| Resource::StorageBufferWindow { buffer: &values, offset, range: half };
        // Side 0 reads the first half and writes the second; side 1 the opposite.
        let side0 = pipeline.create_set1(&[(shader::VALUES_IN, window(0)), (shader::VALUES_OUT, window(half))])?;
        let side1 = pipeline.create_set1(&[(shader::VALUES_IN, window(half)), (shader::VALUES_OUT, window(0))])?;
        Ok(ChainLines {
            ctx,
            lines: lines.max(1),
            invocations,
            trips,
            pipeline,
            set0,
            sides: [side0, side1],
            _seeds: seeds,
            values,
            readback,
            secondaries: OnceCell::new(),
        })
    }

    pub fn lines(&self) -> u32 {
        self.lines
    }

    pub fn invocations(&self) -> u32 {
        self.invocations
    }

    pub fn pipelines(&self) -> Vec<vk::Pipeline> {
        vec![self.pipeline.raw]
    }

    fn push(&self, line: u32) -> ChainPush {
        ChainPush {
            trips: self.trips,
            invocations: self.invocations,
            first_line: u32::from(line == 0),
            scale: 1.0,
            offset: 1.0,
        }
    }

    /// Records the lines with `sync` between them (per-line profiler scopes
    /// where the profiler's detail is on).
    fn record_lines(
        &self,
        rec: &mut Recorder,
        profiler: &mut Profiler,
        sync: &mut dyn LineSync,
    ) -> Result<(), VkError> {
        rec.bind(&self.pipeline, self.set0);
        for n in 0..self.lines {
            let block = n as usize;
            sync.before_block(rec, block);
            sync.bind_line(rec, &self.pipeline, self.set0, self.sides[block % 2]);
            let scope = profiler.begin_detail(rec, LINE_SCOPE)?;
            rec.push(&self.pipeline, &self.push(n));
            rec.dispatch(self.invocations / GROUP, 1, 1);
            profiler.end(rec, scope)?;
            sync.after_block(rec, block)?;
        }
        Ok(())
    }

    /// The lines and a global barrier after each, recorded once (`secondary`).
    fn recorded(&self) -> Result<&SecondaryCommands, VkError> {
        if let Some(recorded) = self.secondaries.get() {
            return Ok(recorded);
        }
        let recorded = SecondaryCommands::record(self.ctx, "sync chain lines", 1, |_, rec| {
            rec.bind(&self.pipeline, self.set0);
            for n in 0..self.lines {
                rec.bind_set1(&self.pipeline, self.sides[n as usize % 2]);
                rec.push(&self.pipeline, &self.push(n));
                rec.dispatch(self.invocations / GROUP, 1, 1);
                GlobalBarrier.after_block(rec, n as usize)?;
            }
            Ok(())
        })?;
        Ok(self.secondaries.get_or_init(|| recorded))
    }

    /// The synchronization object of `sync` for one frame; with per-line
    /// scopes, `secondary` records its lines into a secondary for this frame
    /// (one recorded once cannot hold one frame's queries).
    fn line_sync(&self, sync: SyncStrategy, timed_lines: bool) -> Result<Box<dyn LineSync + '_>, VkError> {
        Ok(match sync {
            SyncStrategy::BarrierGlobal => Box::new(GlobalBarrier),
            SyncStrategy::BarrierImage => Box::new(ImageBarriers::new(&[], &[&self.values])),
            SyncStrategy::Events => Box::new(SplitBarriers::new(self.ctx, self.lines as usize)?),
            SyncStrategy::Secondary if timed_lines => Box::new(RerecordedSweeps::default()),
            SyncStrategy::Secondary => Box::new(ReplayedSweeps::new(self.recorded()?)),
            SyncStrategy::Submits => Box::new(SubmissionPerBlock),
            SyncStrategy::Racy => Box::new(Unsynchronized),
        })
    }

    /// Records, submits and waits for one frame, then checks its result
    /// (every strategy but `racy`).
    pub fn frame(&self, profiler: &mut Profiler, sync: SyncStrategy) -> Result<ChainFrame, ExperimentError> {
        let bytes = self.values.size;
        let (frame, _kept) = submit_and_wait_or(self.ctx, "sync chain frame", |rec| {
            // The previous frame's lines and read-back before this one's first line.
            rec.barrier(&Barrier::memory(
                "chain_previous_frame_to_first_line",
                Access::ANY,
                Access::COMPUTE_READ_WRITE,
            ));
            let mut line_sync = self.line_sync(sync, profiler.detail())?;
            let scope = profiler.begin(rec, FRAME_SCOPE)?;
            line_sync.before_sweep(rec);
            if !line_sync.replay_sweep(rec, 0) {
                if line_sync.records_sweeps_per_frame() {
                    let recorded = SecondaryCommands::record(self.ctx, "sync chain lines (timed)", 1, |_, srec| {
                        self.record_lines(srec, profiler, &mut *line_sync)
                    })?;
                    rec.execute(&recorded, 0);
                    line_sync.keep_secondary(recorded);
                } else {
                    self.record_lines(rec, profiler, &mut *line_sync)?;
                }
            }
            line_sync.end_frame(rec);
            profiler.end(rec, scope)?;
            rec.barrier(&Barrier::memory(
                "chain_last_line_write_to_readback",
                Access::COMPUTE_WRITE,
                Access::TRANSFER_READ,
            ));
            rec.note_transfer();
            copy_buffer(rec, &self.values, &self.readback, bytes);
            rec.barrier(&Barrier::memory("chain_readback_to_host_read", Access::TRANSFER_WRITE, Access::HOST_READ));
            let frame = ChainFrame { dispatches: rec.dispatch_count, barriers: rec.barrier_count };
            Ok::<_, VkError>((frame, line_sync.frame_resources()))
        })?;
        if !sync.is_racy() || self.lines == 1 {
            self.check()?;
        }
        Ok(frame)
    }

    /// The last line's output holds every invocation's seed plus the lines.
    fn check(&self) -> Result<(), ExperimentError> {
        let n = self.invocations as usize;
        let values: Vec<f32> = self.readback.read(2 * n)?;
        // The last line (index lines - 1) wrote the half its side writes.
        let out = if (self.lines - 1).is_multiple_of(2) { &values[n..] } else { &values[..n] };
        let expected = |i: usize| seed(i as u32) + self.lines as f32;
        match (0..n).find(|&i| out[i] != expected(i)) {
            None => Ok(()),
            Some(i) => Err(ExperimentError::Invalid(format!(
                "the chain workload's result is wrong ({} lines of {} trips): invocation {i} holds {}, expected {}; \
                 a chain was cut short or a line read before the previous one wrote",
                self.lines,
                self.trips,
                out[i],
                expected(i)
            ))),
        }
    }
}
