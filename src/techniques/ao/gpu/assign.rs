//! The nearest-codeword assignment on the GPU (glsl/ao_assign.comp): the CPU's
//! exact search ([`CodebookSearch`]) with the same sorted lists, started at a
//! hint, one invocation per packed hemisphere histogram. The walk along a
//! list is split into dispatches of [`SweepPlan::walk_entries`] entries
//! (llvmpipe's loop cap), its state carried between them behind the barrier
//! `search_state_write_to_next_walk_read`. A histogram equal to the same
//! hemisphere's of the previous voxel is not searched: after the walk, a
//! run-copy dispatch behind `search_state_write_to_run_copy_read` gives it
//! its run's result (the CPU's assignment skips such a search too).

use ash::vk;
use bytemuck::{Pod, Zeroable};
use gpu_allocator::MemoryLocation;

use super::plan::{packed_stride, SweepPlan};
use super::sweep::SliceSync;
use crate::shaders::ao_assign as shader;
use crate::techniques::ao::error::AoError;
use crate::techniques::ao::quantize::Codebook;
use crate::techniques::ao::search::{CodebookSearch, SLACK};
use crate::techniques::ao::settings::Metric;
use crate::vk::barriers::{Access, Barrier};
use crate::vk::commands::submit_and_wait;
use crate::vk::descriptors::Resource;
use crate::vk::pipeline::{ComputePipeline, ComputePipelineDesc};
use crate::vk::staging::{copy_buffer, readback_buffer, Uploads};
use crate::vk::{Buffer, Context, Profiler, Recorder, VkError};

/// The pass's name: pipeline, debug label and profiler scope.
pub const ASSIGN_PASS: &str = "ao_assign";

const GROUP_SIZE: u32 = 64;

/// Mirrors the `Assign` push constants.
#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct AssignPush {
    first: i32,
    count: i32,
    hint_first: i32,
    hint_out_first: i32,
    has_hints: i32,
    first_entry: i32,
    entries: i32,
    first_chunk: i32,
    last_chunk: i32,
    clusters: i32,
    packed_stride: i32,
    copy_stride: i32,
    run_copy: i32,
}

crate::assert_gpu_layout!(
    AssignPush,
    shader::layout::ASSIGN,
    [
        first,
        count,
        hint_first,
        hint_out_first,
        has_hints,
        first_entry,
        entries,
        first_chunk,
        last_chunk,
        clusters,
        packed_stride,
        copy_stride,
        run_copy
    ]
);

/// Mirrors `SearchState`: where one histogram's search stands.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct SearchState {
    pub hint: u32,
    pub to_hint: f32,
    pub best: u32,
    /// Distance to `best` as [`crate::techniques::ao::quantize::distance`] gives it (L2 squared).
    pub best_raw: f32,
    /// [`SearchState::SEARCHING`], [`SearchState::FOUND`] or [`SearchState::COPY`].
    pub done: u32,
}

impl SearchState {
    /// The walk reached the end of the list (or has not stopped yet).
    pub const SEARCHING: u32 = 0;
    /// The walk stopped where no later codeword could win.
    pub const FOUND: u32 = 1;
    /// Not searched: equal to the previous voxel's histogram, it took the
    /// result of its run's first histogram.
    pub const COPY: u32 = 2;
}

crate::assert_gpu_layout!(SearchState, shader::layout::SEARCH_STATE, [hint, to_hint, best, best_raw, done]);

/// Where a dispatch's histograms are.
#[derive(Clone, Copy, Debug)]
pub struct AssignRange {
    /// First histogram in the packed and state buffers.
    pub first: usize,
    pub count: usize,
    /// First histogram's hint in the hint buffer (written by the range
    /// before)...
    pub hint_first: usize,
    /// ... and where its own results go, in the other half of the buffer.
    pub hint_out_first: usize,
    /// false: start every search at codeword 0.
    pub has_hints: bool,
    /// Histograms from one to the next that may take its result when equal
    /// (2 in the sweep: the same hemisphere of the previous voxel); 0: every
    /// histogram is searched.
    pub copy_stride: usize,
}

pub struct AssignPass {
    pipeline: ComputePipeline,
    set: vk::DescriptorSet,
    clusters: usize,
    stride: usize,
    walk_entries: usize,
    walk_chunks: usize,
    _codewords: Buffer,
    _order: Buffer,
    _order_distances: Buffer,
}

impl AssignPass {
    /// Stages the codebook and its sorted lists in `uploads` (the caller
    /// finishes them before recording); `packed` holds the histograms
    /// (stride [`packed_stride`]), `states` one [`SearchState`] per histogram,
    /// `hints` the start codewords, read from one part of it and written to
    /// another ([`AssignRange`]) through two bindings.
    pub fn new(
        ctx: &Context,
        uploads: &mut Uploads,
        codebook: &Codebook,
        search: &CodebookSearch,
        metric: Metric,
        plan: &SweepPlan,
        [packed, states, hints]: [&Buffer; 3],
    ) -> Result<AssignPass, VkError> {
        let stride = packed_stride(codebook.dim);
        let clusters = codebook.len();
        let mut words = vec![0f32; clusters * stride];
        for c in 0..clusters {
            words[c * stride..c * stride + codebook.dim].copy_from_slice(codebook.word(c));
        }
        let usage = vk::BufferUsageFlags::STORAGE_BUFFER;
        let codewords = uploads.buffer("ao codewords", &words, usage)?;
        let order: Vec<u32> = search.order().iter().map(|&j| j as u32).collect();
        let order = uploads.buffer("ao codeword order", &order, usage)?;
        let order_distances = uploads.buffer("ao codeword order distances", search.order_distances(), usage)?;
        let metric_id = Metric::ALL.iter().position(|&m| m == metric).unwrap_or(0) as u32;
        let desc = ComputePipelineDesc {
            name: ASSIGN_PASS,
            shader: &shader::INTERFACE,
            specialization: &[(0, metric_id), (1, (1.0 + SLACK).to_bits()), (2, (1.0 - SLACK).to_bits())],
            max_sets: 1,
        };
        let mut pipeline = ComputePipeline::new(ctx, &desc)?;
        let set = pipeline.create_set(&[
            (shader::PACKED, Resource::StorageBuffer(packed)),
            (shader::CODEWORDS, Resource::StorageBuffer(&codewords)),
            (shader::ORDER, Resource::StorageBuffer(&order)),
            (shader::ORDER_DISTANCES, Resource::StorageBuffer(&order_distances)),
            (shader::STATES, Resource::StorageBuffer(states)),
            (shader::HINTS_IN, Resource::StorageBuffer(hints)),
            (shader::HINTS_OUT, Resource::StorageBuffer(hints)),
            (shader::STATES_IN, Resource::StorageBuffer(states)),
        ])?;
        Ok(AssignPass {
            pipeline,
            set,
            clusters,
            stride,
            walk_entries: plan.walk_entries,
            walk_chunks: plan.walk_chunks,
            _codewords: codewords,
            _order: order,
            _order_distances: order_distances,
        })
    }

    /// Records the search of `ranges`' histograms, which an earlier barrier
    /// made visible, in order and with the pipeline bound once; leaves each
    /// result in `states` and, as the next slice's hint, in `hints`. Each
    /// range is one slice (or part of one) and starts at the hints the range
    /// before wrote.
    /// `sync` other than [`SliceSync::Barrier`] (RACY, only for proving that
    /// synchronization validation reports it) leaves out the ranges' order
    /// after each other or the run copies' after the walk.
    pub fn record(
        &self,
        rec: &mut Recorder,
        profiler: &mut Profiler,
        ranges: &[AssignRange],
        sync: SliceSync,
    ) -> Result<(), VkError> {
        let scope = profiler.begin(rec, ASSIGN_PASS)?;
        rec.bind(&self.pipeline, self.set);
        for (i, range) in ranges.iter().enumerate() {
            if i > 0 && sync != SliceSync::RacyNoHintsBarrier {
                rec.barrier(&Barrier::memory(
                    "search_hints_write_to_next_slice_read",
                    Access::COMPUTE_WRITE,
                    Access::COMPUTE_READ_WRITE,
                ));
            }
            self.record_walk(rec, range);
            if range.copy_stride > 0 {
                if sync != SliceSync::RacyNoRunCopyBarrier {
                    rec.barrier(&Barrier::memory(
                        "search_state_write_to_run_copy_read",
                        Access::COMPUTE_WRITE,
                        Access::COMPUTE_READ_WRITE,
                    ));
                }
                // The walk's chunk fields do not matter to the run copies.
                rec.push(&self.pipeline, &self.push(range, 0, true));
                rec.dispatch((range.count as u32).div_ceil(GROUP_SIZE), 1, 1);
            }
        }
        profiler.end(rec, scope)
    }

    /// The push constants of walk chunk `chunk` of `range`, or of its run
    /// copies.
    fn push(&self, range: &AssignRange, chunk: usize, run_copy: bool) -> AssignPush {
        AssignPush {
            first: range.first as i32,
            count: range.count as i32,
            hint_first: range.hint_first as i32,
            hint_out_first: range.hint_out_first as i32,
            has_hints: range.has_hints as i32,
            first_entry: (chunk * self.walk_entries) as i32,
            entries: self.walk_entries as i32,
            first_chunk: (chunk == 0) as i32,
            last_chunk: (chunk + 1 == self.walk_chunks) as i32,
            clusters: self.clusters as i32,
            packed_stride: self.stride as i32,
            copy_stride: range.copy_stride as i32,
            run_copy: run_copy as i32,
        }
    }

    /// One range's walk, in dispatches of `walk_entries` list entries.
    fn record_walk(&self, rec: &mut Recorder, range: &AssignRange) {
        for chunk in 0..self.walk_chunks {
            if chunk > 0 {
                rec.barrier(&Barrier::memory(
                    "search_state_write_to_next_walk_read",
                    Access::COMPUTE_WRITE,
                    Access::COMPUTE_READ_WRITE,
                ));
            }
            rec.push(&self.pipeline, &self.push(range, chunk, false));
            rec.dispatch((range.count as u32).div_ceil(GROUP_SIZE), 1, 1);
        }
    }
}

/// The nearest codeword (index, distance as [`Codebook::nearest`] gives it)
/// of each of `vectors` (`codebook.dim` floats each), searched on the GPU,
/// each search started at `hints[i]` (codeword 0 without hints), a vector
/// equal to the one before it taking that one's result. One submission; for
/// tests and for assigning vectors the CPU already holds.
pub fn assign_packed(
    ctx: &Context,
    vectors: &[f32],
    codebook: &Codebook,
    metric: Metric,
    hints: Option<&[u32]>,
) -> Result<Vec<(u32, f32)>, AoError> {
    let dim = codebook.dim;
    let count = vectors.len() / dim.max(1);
    let search = CodebookSearch::new(codebook, metric);
    let plan = SweepPlan::new(glam::UVec3::ONE, 2, dim.max(2), 1, codebook.len(), metric == Metric::Lmax, 64, 64)
        .map_err(AoError::GpuLimit)?;
    let stride = plan.packed_stride;
    let mut padded = vec![0f32; count.max(1) * stride];
    for (i, v) in vectors.chunks(dim).enumerate() {
        padded[i * stride..i * stride + dim].copy_from_slice(v);
    }
    let usage = vk::BufferUsageFlags::STORAGE_BUFFER;
    let mut uploads = Uploads::new(ctx);
    let packed = uploads.buffer("ao assign vectors", &padded, usage)?;
    let states_bytes = count.max(1) * size_of::<SearchState>();
    let states = Buffer::new(
        ctx,
        "ao search states",
        states_bytes as u64,
        usage | vk::BufferUsageFlags::TRANSFER_SRC,
        MemoryLocation::GpuOnly,
    )?;
    let readback = readback_buffer(ctx, "ao search states readback", states_bytes as u64)?;
    // The given hints, then room for the results the pass writes.
    let mut hint_values = hints.map_or_else(|| vec![0u32; count.max(1)], |h| h.to_vec());
    hint_values.resize(2 * count.max(1), 0);
    let hint_buffer = uploads.buffer("ao search hints", &hint_values, usage)?;
    let pass = AssignPass::new(ctx, &mut uploads, codebook, &search, metric, &plan, [&packed, &states, &hint_buffer])?;
    uploads.finish()?;
    let mut profiler = Profiler::new(ctx, 4)?;
    submit_and_wait(ctx, "ao assign packed", |rec| {
        let range = AssignRange {
            first: 0,
            count,
            hint_first: 0,
            hint_out_first: count,
            has_hints: hints.is_some(),
            copy_stride: 1,
        };
        pass.record(rec, &mut profiler, &[range], SliceSync::Barrier)?;
        rec.barrier(&Barrier::memory(
            "search_state_write_to_readback_copy",
            Access::COMPUTE_WRITE,
            Access::TRANSFER_READ,
        ));
        copy_buffer(rec, &states, &readback, states_bytes as u64);
        rec.barrier(&Barrier::memory("readback_copy_to_host_read", Access::TRANSFER_WRITE, Access::HOST_READ));
        Ok(())
    })?;
    let states: Vec<SearchState> = readback.read(count)?;
    Ok(states.iter().map(|s| (s.best, s.best_raw)).collect())
}
