//! The paper's space sweep of local histograms on the GPU (section 5),
//! slice by slice along z, recorded pass by pass per batch of parts
//! ([`super::plan`]) so that each pipeline is bound once per batch:
//!
//! 1. `ao_histogram_bin` bins every slice the batch's stencils read (its
//!    centre slices and e_z more on each side, glsl/ao_histogram_common.glsl)
//!    in one dispatch; barrier `binned_slices_write_to_stencil_read`;
//! 2. `ao_histogram_stencil`: every part's stencil, in chunks within
//!    llvmpipe's loop cap (barrier `stencil_chunk_write_to_next_chunk_read`
//!    between chunks; the parts' histograms are disjoint); barrier
//!    `unpacked_write_to_pack_read`;
//! 3. `ao_histogram_pack`: every part's normalization and packing; barrier
//!    `packed_write_to_assignment_read`;
//! 4. `ao_assign`: the parts in order, each slice's searches started at the
//!    previous slice's codewords at the same (x, y) (neighbouring histograms
//!    are close, so the exact search visits few codewords), behind
//!    `search_hints_write_to_next_slice_read`; the hints ping-pong between the
//!    halves of one buffer, read and written through separate bindings.
//!
//! Every pass has a debug label and a profiler scope of its name. A batch is
//! one submission; its unpacked histograms and search results are then read
//! back in place for the final codebook, so only one batch of unpacked
//! histograms exists at a time.

use std::collections::BTreeMap;
use std::ops::Range;

use ash::vk;
use bytemuck::{Pod, Zeroable};
use glam::UVec3;
use gpu_allocator::MemoryLocation;

use super::assign::{AssignPass, AssignRange, SearchState};
use super::plan::{packed_stride, unpacked_stride, SweepPlan};
use crate::scene::Volume;
use crate::shaders::{ao_histogram_bin, ao_histogram_pack, ao_histogram_sweep};
use crate::techniques::ao::error::AoError;
use crate::techniques::ao::gradient::gradient_scale;
use crate::techniques::ao::histogram::SphereStencil;
use crate::techniques::ao::packing::PackingScheme;
use crate::techniques::ao::quantize::Codebook;
use crate::techniques::ao::search::CodebookSearch;
use crate::techniques::ao::settings::Metric;
use crate::vk::barriers::{Access, Barrier};
use crate::vk::commands::{submit_and_wait, Recorder};
use crate::vk::descriptors::Resource;
use crate::vk::pipeline::{ComputePipeline, ComputePipelineDesc};
use crate::vk::staging::{copy_buffer, readback_buffer, Uploads};
use crate::vk::{Buffer, Context, Profiler, VkError};

pub const BIN_PASS: &str = "ao_histogram_bin";
pub const STENCIL_PASS: &str = "ao_histogram_stencil";
pub const PACK_PASS: &str = "ao_histogram_pack";

/// Unpacked histograms one batch holds at most, bytes, before the device's
/// memory ([`batch_bytes`]) lowers it: 35 slices of 64 x 64 at b = 8, so a
/// 64^3 volume takes 2 batches (each a submission that binds the sweep's four
/// pipelines again; best-practices validation counts every rebind).
pub const BATCH_BYTES: usize = 288 << 20;

/// The share of the smallest device-local heap the batch buffers may take
/// (the volume, the other buffers and other programs need the rest).
const HEAP_SHARE: u64 = 4;

/// Mirrors the `Sweep` push constants (glsl/ao_histogram_common.glsl).
#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct SweepPush {
    first_binned: i32,
    slice: i32,
    first_row: i32,
    rows: i32,
    first_entry: i32,
    entry_count: i32,
    part_voxel: i32,
    unpacked_first: i32,
}

macro_rules! assert_sweep_push_layout {
    ($($shader:ident),*) => {$(
        crate::assert_gpu_layout!(
            SweepPush,
            $shader::layout::SWEEP,
            [first_binned, slice, first_row, rows, first_entry, entry_count, part_voxel, unpacked_first]
        );
    )*};
}
assert_sweep_push_layout!(ao_histogram_bin, ao_histogram_sweep, ao_histogram_pack);

/// Mirrors `Share`: one nonzero entry of a packing-matrix row.
#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct Share {
    packed_bin: u32,
    share: f32,
}

crate::assert_gpu_layout!(Share, ao_histogram_pack::layout::SHARE, [packed_bin, share]);

/// Whether the batch's binning is ordered before the stencils read it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SliceSync {
    Barrier,
    /// RACY: no `binned_slices_write_to_stencil_read`. Only for proving that
    /// synchronization validation reports the missing barrier; the histograms
    /// are undefined.
    RacyNoSliceBarrier,
    /// RACY: no `search_hints_write_to_next_slice_read` between the parts'
    /// searches. Only for proving that synchronization validation reports
    /// it; the search starts (not their results) are undefined.
    RacyNoHintsBarrier,
    /// RACY: no `search_state_write_to_run_copy_read` between a part's
    /// searches and the copies of their results to equal neighbours. Only for
    /// proving that synchronization validation reports it; the copies'
    /// results are undefined.
    RacyNoRunCopyBarrier,
}

/// What one batch leaves for the CPU, read in place from the GPU's buffers.
pub struct BatchOutput<'a> {
    /// Linear indices of the batch's voxels.
    pub voxels: Range<usize>,
    pub bins: usize,
    /// Per voxel [`unpacked_stride`] floats: the forward histogram, a discard
    /// slot, the backward histogram, a discard slot; not normalized.
    pub unpacked: &'a [f32],
    /// 1 / N_r in f32: `h * normalization` (an f32 product) is the
    /// normalized histogram value the GPU packed.
    pub normalization: f32,
    /// Per voxel the forward then the backward search's result.
    pub states: &'a [SearchState],
}

impl BatchOutput<'_> {
    /// Forward and backward histogram of the batch's `i`-th voxel, not
    /// normalized.
    pub fn voxel(&self, i: usize) -> (&[f32], &[f32]) {
        let base = i * unpacked_stride(self.bins);
        (&self.unpacked[base..base + self.bins], &self.unpacked[base + self.bins + 1..base + 2 * self.bins + 1])
    }
}

/// The settled inputs of a sweep.
pub struct SweepInputs<'a> {
    pub volume: &'a Volume,
    pub stencil: &'a SphereStencil,
    pub bins: usize,
    pub packing: &'a PackingScheme,
    pub codebook: &'a Codebook,
    pub search: &'a CodebookSearch<'a>,
    pub metric: Metric,
    /// Unpacked histograms one batch may hold, bytes ([`batch_bytes`] on
    /// the sweep's device).
    pub max_batch_bytes: usize,
}

/// GPU time per pass, summed over the sweep's submissions (ms).
pub type PassTimes = BTreeMap<String, f64>;

/// Bytes per voxel of the batch buffers: unpacked histograms, packed
/// histograms, search states.
fn batch_bytes_per_voxel(bins: usize, packed_dim: usize) -> [usize; 3] {
    [unpacked_stride(bins) * 4, 2 * packed_stride(packed_dim) * 4, 2 * size_of::<SearchState>()]
}

/// The unpacked histograms one batch holds on `ctx`, bytes: at most
/// [`BATCH_BYTES`], the packed histograms and search states within
/// `maxStorageBufferRange` (each is bound whole; the unpacked histograms are
/// bound a part at a time, [`part_bytes`]), and the three together within a
/// quarter of the smallest device-local heap. The batch is at least one x row
/// ([`SweepPlan::new`]); [`GpuSweep::new`] refuses a row that breaks the range.
pub fn batch_bytes(ctx: &Context, bins: usize, packed_dim: usize) -> usize {
    let per_voxel = batch_bytes_per_voxel(bins, packed_dim);
    let range = ctx.limits.max_storage_buffer_range as usize;
    let by_range = per_voxel[1..].iter().map(|&b| range / b).min().unwrap_or(0);
    let by_memory = (device_local_heap(ctx) / HEAP_SHARE) as usize / per_voxel.iter().sum::<usize>();
    let voxels = (BATCH_BYTES / per_voxel[0]).min(by_range).min(by_memory);
    voxels * per_voxel[0]
}

/// The unpacked histograms one part holds at most on `ctx`, bytes: a part's
/// window of the batch's buffer, bound as one storage buffer from an offset
/// rounded down to `minStorageBufferOffsetAlignment`, must fit
/// `maxStorageBufferRange` with what the rounding adds.
pub fn part_bytes(ctx: &Context) -> usize {
    let align = ctx.limits.min_storage_buffer_offset_alignment.max(1) as usize;
    (ctx.limits.max_storage_buffer_range as usize).saturating_sub(align)
}

/// One part's window of the batch's unpacked histograms: the bytes bound
/// (`offset` aligned for the device) and where the part's first float lies in
/// them. Parts at the same place of different batches share a window.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct UnpackedWindow {
    batch_voxel: usize,
    voxels: usize,
    offset: u64,
    range: u64,
    first_float: u32,
}

/// The distinct windows of a plan's parts, and which one each part binds.
struct UnpackedWindows {
    windows: Vec<UnpackedWindow>,
    /// Per batch, per part (the plan's order): the index into `windows`.
    of_part: Vec<Vec<usize>>,
}

impl UnpackedWindows {
    /// The windows of `plan`'s parts, for a device whose storage buffer
    /// offsets align to `align` bytes.
    fn new(plan: &SweepPlan, align: u64) -> UnpackedWindows {
        let voxel_bytes = (unpacked_stride(plan.bins) * 4) as u64;
        let align = align.max(1);
        let mut windows: Vec<UnpackedWindow> = Vec::new();
        let mut window_of = |part: &super::plan::Part| {
            let voxels = part.rows as usize * plan.dims.x as usize;
            if let Some(i) = windows.iter().position(|w| w.batch_voxel == part.batch_voxel && w.voxels == voxels) {
                return i;
            }
            let start = part.batch_voxel as u64 * voxel_bytes;
            let offset = start / align * align;
            windows.push(UnpackedWindow {
                batch_voxel: part.batch_voxel,
                voxels,
                offset,
                range: start - offset + voxels as u64 * voxel_bytes,
                first_float: ((start - offset) / 4) as u32,
            });
            windows.len() - 1
        };
        let of_part = plan.batches.iter().map(|b| b.parts.iter().map(&mut window_of).collect()).collect();
        UnpackedWindows { windows, of_part }
    }

    /// The largest window, bytes.
    fn largest(&self) -> usize {
        self.windows.iter().map(|w| w.range as usize).max().unwrap_or(0)
    }
}

/// The smallest device-local heap's size, bytes.
fn device_local_heap(ctx: &Context) -> u64 {
    // SAFETY: the physical device belongs to this instance.
    let memory = unsafe { ctx.instance.get_physical_device_memory_properties(ctx.physical_device) };
    memory.memory_heaps[..memory.memory_heap_count as usize]
        .iter()
        .filter(|h| h.flags.contains(vk::MemoryHeapFlags::DEVICE_LOCAL))
        .map(|h| h.size)
        .min()
        .unwrap_or(u64::MAX)
}

/// The sweep's plan for these settings on `ctx` ([`batch_bytes`]), or why
/// the GPU cannot run them (checked before any preprocessing work).
pub fn supported_plan(
    ctx: &Context,
    volume: &Volume,
    stencil: &SphereStencil,
    bins: usize,
    packed_dim: usize,
    clusters: usize,
    lmax: bool,
) -> Result<SweepPlan, AoError> {
    let max_batch_bytes = batch_bytes(ctx, bins, packed_dim);
    let plan = SweepPlan::new(
        volume.dims,
        bins,
        packed_dim,
        stencil.voxel_count(),
        clusters,
        lmax,
        max_batch_bytes,
        part_bytes(ctx),
    )
    .map_err(AoError::GpuLimit)?;
    let plan = check_indices(volume, plan)?;
    for (name, bytes) in binding_sizes(ctx, volume, stencil, &plan, clusters, packed_dim) {
        within_storage_range(ctx, name, bytes)?;
    }
    Ok(plan)
}

/// Shaders index the volume, and the batch's histograms, in i32.
fn check_indices(volume: &Volume, plan: SweepPlan) -> Result<SweepPlan, AoError> {
    let batch_floats = plan.batch_voxels * unpacked_stride(plan.bins).max(2 * plan.packed_stride);
    if volume.voxel_count().max(batch_floats) >= i32::MAX as usize {
        return Err(AoError::GpuLimit(format!("{} voxels overflow the shaders' 32-bit indices", volume.dims)));
    }
    Ok(plan)
}

/// Every storage buffer the sweep binds, with its size in bytes (the
/// packing shares are at most bins + packed_dim entries; the unpacked
/// histograms: the largest part's window).
fn binding_sizes(
    ctx: &Context,
    volume: &Volume,
    stencil: &SphereStencil,
    plan: &SweepPlan,
    clusters: usize,
    packed_dim: usize,
) -> Vec<(&'static str, usize)> {
    let [ex, ey, ez] = stencil.extent.to_array().map(|v| v as usize);
    let [nx, ny, _] = volume.dims.to_array().map(|v| v as usize);
    let bins = plan.bins;
    let [_, packed, states] = batch_bytes_per_voxel(bins, packed_dim).map(|b| b * plan.batch_voxels);
    let align = ctx.limits.min_storage_buffer_offset_alignment;
    let unpacked = UnpackedWindows::new(plan, align).largest();
    vec![
        ("ao normalized values", volume.voxel_count() * 4),
        ("ao binned slices", (plan.batch_slices + 2 * ez) * (nx + 2 * ex) * (ny + 2 * ey) * 4),
        ("ao stencil directions", stencil.voxel_count() * 16),
        ("ao packing shares", (bins + packed_dim) * size_of::<Share>()),
        ("ao unpacked histograms", unpacked),
        ("ao packed histograms", packed),
        ("ao search states", states),
        ("ao search hints", 2 * hints_per_slice(nx, ny) * 4),
        ("ao codewords", clusters * plan.packed_stride * 4),
        ("ao codeword order", clusters * clusters * 4),
    ]
}

/// Search hints of one slice (a forward and a backward search per voxel);
/// the hints buffer holds two slices', ping-ponged ([`hint_halves`]).
fn hints_per_slice(nx: usize, ny: usize) -> usize {
    nx * ny * 2
}

/// Where slice `z`'s searches read their hints (what slice z - 1 wrote) and
/// where they write theirs, in hints: the halves alternate with z.
fn hint_halves(z: u32, nx: usize, ny: usize) -> (usize, usize) {
    let half = hints_per_slice(nx, ny);
    let read = (z as usize % 2) * half;
    (read, half - read)
}

/// A storage buffer of `bytes` is bound whole: it must fit the device's
/// `maxStorageBufferRange`.
fn within_storage_range(ctx: &Context, name: &str, bytes: usize) -> Result<(), AoError> {
    let range = ctx.limits.max_storage_buffer_range;
    if bytes as u64 > range as u64 {
        return Err(AoError::GpuLimit(format!(
            "{name} would take {bytes} bytes in one storage buffer, over this device's maxStorageBufferRange \
             ({range}); lower ao.bits, ao.clusters or ao.radius, or use ao.backend = \"cpu\""
        )));
    }
    Ok(())
}

pub struct GpuSweep<'c> {
    ctx: &'c Context,
    plan: SweepPlan,
    extent: UVec3,
    normalization: f32,
    bin: ComputePipeline,
    stencil: ComputePipeline,
    pack: ComputePipeline,
    sets: [vk::DescriptorSet; 3],
    /// The parts' windows of the unpacked histograms, and their set-1 sets
    /// for the stencil and the pack pipeline.
    windows: UnpackedWindows,
    window_sets: [Vec<vk::DescriptorSet>; 2],
    assign: AssignPass,
    profiler: Profiler,
    unpacked: Buffer,
    states: Buffer,
    /// Host-visible copies of `unpacked` and `states`, written after each batch.
    readback: [Buffer; 2],
    _values: Buffer,
    _binned: Buffer,
    _stencil_directions: Buffer,
    _stencil_offsets: Buffer,
    _share_starts: Buffer,
    _shares: Buffer,
    _packed: Buffer,
    _hints: Buffer,
}

impl<'c> GpuSweep<'c> {
    pub fn new(ctx: &'c Context, inputs: &SweepInputs) -> Result<GpuSweep<'c>, AoError> {
        let volume = inputs.volume;
        let (stencil, bins, packing) = (inputs.stencil, inputs.bins, inputs.packing);
        let dims = volume.dims;
        // 1 / N_r rounded once, as the CPU's f64 normalization is.
        let normalization = (1.0 / stencil.voxel_count().max(1) as f64) as f32;
        let lmax = inputs.metric == Metric::Lmax;
        let plan = SweepPlan::new(
            dims,
            bins,
            packing.packed_dim,
            stencil.voxel_count(),
            inputs.codebook.len(),
            lmax,
            inputs.max_batch_bytes,
            part_bytes(ctx),
        )
        .map_err(AoError::GpuLimit)
        .and_then(|p| check_indices(volume, p))?;
        for (name, bytes) in binding_sizes(ctx, volume, stencil, &plan, inputs.codebook.len(), packing.packed_dim) {
            within_storage_range(ctx, name, bytes)?;
        }
        let windows = UnpackedWindows::new(&plan, ctx.limits.min_storage_buffer_offset_alignment);
        let e = stencil.extent;
        // A batch's centre slices and e_z more on each side.
        let binned_slots = plan.batch_slices as u32 + 2 * e.z;
        let (px, py) = (dims.x + 2 * e.x, dims.y + 2 * e.y);
        // The specialization constants of glsl/ao_histogram_common.glsl, ids 1..=11.
        let [gx, gy, gz] = gradient_scale(volume.spacing).map(f32::to_bits);
        let constants: Vec<(u32, u32)> = [gx, gy, gz, dims.x, dims.y, dims.z, bins as u32, e.x, e.y, e.z]
            .into_iter()
            .chain([plan.packed_stride as u32])
            .enumerate()
            .map(|(i, value)| (i as u32 + 1, value))
            .collect();

        // Every buffer a shader reads or writes is device-local; the inputs
        // arrive through staging (one submission), the results leave through
        // read-back copies after each batch.
        let usage = vk::BufferUsageFlags::STORAGE_BUFFER;
        let device_buffer = |name: &str, bytes: usize, extra: vk::BufferUsageFlags| {
            Buffer::new(ctx, name, bytes.max(4) as u64, usage | extra, MemoryLocation::GpuOnly)
        };
        let mut uploads = Uploads::new(ctx);
        let values: Vec<f32> = (0..volume.voxel_count()).map(|i| volume.data.normalized(i)).collect();
        let values = uploads.buffer("ao normalized values", &values, usage)?;
        let none = vk::BufferUsageFlags::empty();
        let binned = device_buffer("ao binned slices", (binned_slots * px * py) as usize * 4, none)?;
        let directions: Vec<[f32; 4]> =
            stencil.directions.iter().zip(&stencil.weights).map(|(d, &w)| [d.x, d.y, d.z, w as f32]).collect();
        let offsets: Vec<i32> =
            stencil.offsets.iter().map(|o| ((o.z + e.z as i32) * py as i32 + o.y) * px as i32 + o.x).collect();
        let stencil_directions = uploads.buffer("ao stencil directions", &directions, usage)?;
        let stencil_offsets = uploads.buffer("ao stencil offsets", &offsets, usage)?;
        let mut share_starts = vec![0u32];
        let mut shares = Vec::new();
        for row in &packing.shares {
            shares.extend(row.iter().map(|&(packed_bin, share)| Share { packed_bin, share }));
            share_starts.push(shares.len() as u32);
        }
        if shares.is_empty() {
            shares.push(Share::zeroed());
        }
        let share_starts = uploads.buffer("ao packing row starts", &share_starts, usage)?;
        let shares = uploads.buffer("ao packing shares", &shares, usage)?;
        let batch = plan.batch_voxels;
        let (fill, copy_out) = (vk::BufferUsageFlags::TRANSFER_DST, vk::BufferUsageFlags::TRANSFER_SRC);
        let unpacked_bytes = batch * unpacked_stride(bins) * 4;
        let unpacked = device_buffer("ao unpacked histograms", unpacked_bytes, fill | copy_out)?;
        let packed = device_buffer("ao packed histograms", batch * 2 * plan.packed_stride * 4, none)?;
        let states_bytes = batch * 2 * size_of::<SearchState>();
        let states = device_buffer("ao search states", states_bytes, copy_out)?;
        let hints = device_buffer("ao search hints", 2 * hints_per_slice(dims.x as usize, dims.y as usize) * 4, none)?;
        let readback = [
            readback_buffer(ctx, "ao unpacked histograms readback", unpacked_bytes as u64)?,
            readback_buffer(ctx, "ao search states readback", states_bytes as u64)?,
        ];

        // The stencil and pack pipelines bind one set 1 per window.
        let pipeline = |name: &str, shader, specialization: &[(u32, u32)], max_sets: usize| {
            let max_sets = max_sets as u32;
            ComputePipeline::new(ctx, &ComputePipelineDesc { name, shader, specialization, max_sets })
        };
        let mut bin = pipeline(BIN_PASS, &ao_histogram_bin::INTERFACE, &constants, 1)?;
        let bin_set = bin.create_set(&[
            (ao_histogram_bin::VALUES, Resource::StorageBuffer(&values)),
            (ao_histogram_bin::BINNED, Resource::StorageBuffer(&binned)),
        ])?;
        let mut sweep = pipeline(STENCIL_PASS, &ao_histogram_sweep::INTERFACE, &constants, windows.windows.len())?;
        let sweep_set = sweep.create_set(&[
            (ao_histogram_sweep::VALUES, Resource::StorageBuffer(&values)),
            (ao_histogram_sweep::BINNED, Resource::StorageBuffer(&binned)),
            (ao_histogram_sweep::STENCIL_DIRECTIONS, Resource::StorageBuffer(&stencil_directions)),
            (ao_histogram_sweep::STENCIL_OFFSETS, Resource::StorageBuffer(&stencil_offsets)),
        ])?;
        let window =
            |w: &UnpackedWindow| Resource::StorageBufferWindow { buffer: &unpacked, offset: w.offset, range: w.range };
        let sweep_windows = windows
            .windows
            .iter()
            .map(|w| sweep.create_set1(&[(ao_histogram_sweep::UNPACKED, window(w))]))
            .collect::<Result<Vec<_>, _>>()?;
        let pack_constants: Vec<(u32, u32)> = [(0, normalization.to_bits())].into_iter().chain(constants).collect();
        let mut pack = pipeline(PACK_PASS, &ao_histogram_pack::INTERFACE, &pack_constants, windows.windows.len())?;
        let pack_windows = windows
            .windows
            .iter()
            .map(|w| pack.create_set1(&[(ao_histogram_pack::UNPACKED, window(w))]))
            .collect::<Result<Vec<_>, _>>()?;
        let pack_set = pack.create_set(&[
            (ao_histogram_pack::SHARE_STARTS, Resource::StorageBuffer(&share_starts)),
            (ao_histogram_pack::SHARES, Resource::StorageBuffer(&shares)),
            (ao_histogram_pack::PACKED, Resource::StorageBuffer(&packed)),
        ])?;
        let assign = AssignPass::new(
            ctx,
            &mut uploads,
            inputs.codebook,
            inputs.search,
            inputs.metric,
            &plan,
            [&packed, &states, &hints],
        )?;
        uploads.finish()?;
        // One scope per pass and batch.
        let profiler = Profiler::new(ctx, 4)?;
        Ok(GpuSweep {
            ctx,
            plan,
            extent: e,
            normalization,
            bin,
            stencil: sweep,
            pack,
            sets: [bin_set, sweep_set, pack_set],
            windows,
            window_sets: [sweep_windows, pack_windows],
            assign,
            profiler,
            unpacked,
            states,
            readback,
            _values: values,
            _binned: binned,
            _stencil_directions: stencil_directions,
            _stencil_offsets: stencil_offsets,
            _share_starts: share_starts,
            _shares: shares,
            _packed: packed,
            _hints: hints,
        })
    }

    pub fn plan(&self) -> &SweepPlan {
        &self.plan
    }

    /// Sweeps the whole volume; `consume` gets every batch's output, in order.
    pub fn run(
        &mut self,
        sync: SliceSync,
        mut consume: impl FnMut(&BatchOutput) -> Result<(), AoError>,
    ) -> Result<PassTimes, AoError> {
        let mut times = PassTimes::new();
        // The first batch's histograms are zeroed in a submission of their
        // own; each batch zeroes the next one's after its read-back. So no
        // batch's first profiler scope starts right after a transfer, which
        // only an ALL_COMMANDS timestamp would wait for.
        submit_and_wait(self.ctx, "ao unpacked histograms clear", |rec| {
            clear_unpacked(rec, &self.unpacked);
            Ok(())
        })?;
        let batches = self.plan.batches.len();
        for b in 0..batches {
            self.profiler.reset();
            self.record_batch(b, sync, b + 1 < batches)?;
            let report = self.profiler.resolve(0)?;
            for pass in report.passes {
                *times.entry(pass.name).or_default() += pass.gpu_ms;
            }
            let voxels = self.plan.batches[b].voxels.clone();
            let output = BatchOutput {
                bins: self.plan.bins,
                normalization: self.normalization,
                unpacked: self.readback[0].mapped(voxels.len() * unpacked_stride(self.plan.bins))?,
                states: self.readback[1].mapped(2 * voxels.len())?,
                voxels,
            };
            consume(&output)?;
        }
        Ok(times)
    }

    /// Records batch `b`; with `clear_next`, then zeroes the unpacked
    /// histograms for the next batch once they are copied out.
    fn record_batch(&mut self, b: usize, sync: SliceSync, clear_next: bool) -> Result<(), VkError> {
        let GpuSweep {
            ctx,
            plan,
            extent,
            bin,
            stencil,
            pack,
            sets,
            windows,
            window_sets,
            assign,
            profiler,
            unpacked,
            states,
            readback,
            ..
        } = self;
        let (nx, padded) = (plan.dims.x, [plan.dims.x + 2 * extent.x, plan.dims.y + 2 * extent.y]);
        let batch = &plan.batches[b];
        let binned = batch.binned_slices(extent.z);
        // A batch that is part of a slice bins only the rows its stencil reads.
        let rows = batch.rows();
        let push = SweepPush { first_binned: binned.start, ..SweepPush::zeroed() };
        // Part k of the batch and the window it binds.
        let window_of = |k: usize| windows.of_part[b][k];
        let part_push = |k: usize, part: &super::plan::Part| SweepPush {
            slice: part.z as i32,
            first_row: part.first_row as i32,
            rows: part.rows as i32,
            part_voxel: part.batch_voxel as i32,
            unpacked_first: windows.windows[window_of(k)].first_float as i32,
            ..push
        };
        submit_and_wait(ctx, "ao histogram sweep", |rec| {
            // The histograms were zeroed before this submission ([`Self::run`]).
            let scope = profiler.begin(rec, BIN_PASS)?;
            rec.bind(bin, sets[0]);
            let (first_row, row_count) = (rows.start as i32, rows.len() as i32);
            rec.push(bin, &SweepPush { slice: binned.start, first_row, rows: row_count, ..push });
            let padded_rows = (rows.len() as u32 + 2 * extent.y).min(padded[1]);
            rec.dispatch(padded[0].div_ceil(8), padded_rows.div_ceil(8), binned.len() as u32);
            profiler.end(rec, scope)?;
            if sync != SliceSync::RacyNoSliceBarrier {
                rec.barrier(&Barrier::memory(
                    "binned_slices_write_to_stencil_read",
                    Access::COMPUTE_WRITE,
                    Access::COMPUTE_READ,
                ));
            }
            // The parts' histograms are disjoint: only a chunk depends on
            // the one before (it adds into the same histograms).
            let scope = profiler.begin(rec, STENCIL_PASS)?;
            rec.bind(stencil, sets[1]);
            for (i, chunk) in plan.stencil_chunks.iter().enumerate() {
                if i > 0 {
                    rec.barrier(&Barrier::memory(
                        "stencil_chunk_write_to_next_chunk_read",
                        Access::COMPUTE_WRITE,
                        Access::COMPUTE_READ_WRITE,
                    ));
                }
                for (k, part) in batch.parts.iter().enumerate() {
                    let push = SweepPush {
                        first_entry: chunk.start as i32,
                        entry_count: chunk.len() as i32,
                        ..part_push(k, part)
                    };
                    rec.bind_set1(stencil, window_sets[0][window_of(k)]);
                    rec.push(stencil, &push);
                    rec.dispatch(nx.div_ceil(8), part.rows.div_ceil(8), 1);
                }
            }
            profiler.end(rec, scope)?;
            rec.barrier(&Barrier::memory("unpacked_write_to_pack_read", Access::COMPUTE_WRITE, Access::COMPUTE_READ));
            let scope = profiler.begin(rec, PACK_PASS)?;
            rec.bind(pack, sets[2]);
            for (k, part) in batch.parts.iter().enumerate() {
                rec.bind_set1(pack, window_sets[1][window_of(k)]);
                rec.push(pack, &part_push(k, part));
                rec.dispatch((part.rows * nx).div_ceil(64), 1, 1);
            }
            profiler.end(rec, scope)?;
            rec.barrier(&Barrier::memory(
                "packed_write_to_assignment_read",
                Access::COMPUTE_WRITE,
                Access::COMPUTE_READ,
            ));
            let ranges: Vec<AssignRange> = batch
                .parts
                .iter()
                .map(|part| {
                    let (read, write) = hint_halves(part.z, nx as usize, plan.dims.y as usize);
                    let row_offset = 2 * part.first_row as usize * nx as usize;
                    AssignRange {
                        first: 2 * part.batch_voxel,
                        count: 2 * part.rows as usize * nx as usize,
                        hint_first: read + row_offset,
                        hint_out_first: write + row_offset,
                        has_hints: part.z > 0,
                        // The same hemisphere of the previous voxel.
                        copy_stride: 2,
                    }
                })
                .collect();
            assign.record(rec, profiler, &ranges, sync)?;
            // The next batch's first slice starts at the hints this batch's
            // last slice wrote.
            rec.barrier(&Barrier::memory(
                "search_hints_write_to_next_batch_read",
                Access::COMPUTE_WRITE,
                Access::COMPUTE_READ_WRITE,
            ));
            // The batch's histograms and search results go to the host.
            rec.barrier(&Barrier::memory("sweep_write_to_readback_copy", Access::COMPUTE_WRITE, Access::TRANSFER_READ));
            let voxels = batch.voxels.len();
            copy_buffer(rec, unpacked, &readback[0], (voxels * unpacked_stride(plan.bins) * 4) as u64);
            copy_buffer(rec, states, &readback[1], (2 * voxels * size_of::<SearchState>()) as u64);
            rec.barrier(&Barrier::memory("readback_copy_to_host_read", Access::TRANSFER_WRITE, Access::HOST_READ));
            if clear_next {
                rec.barrier(&Barrier::memory(
                    "unpacked_readback_copy_to_next_batch_clear",
                    Access::TRANSFER_READ,
                    Access::CLEAR_WRITE,
                ));
                clear_unpacked(rec, unpacked);
            }
            Ok(())
        })
    }
}

/// Zeroes the unpacked histograms the stencil adds into (a memset, far
/// cheaper than a zeroing loop per invocation on llvmpipe), ordered before
/// the next stencil in submission order.
fn clear_unpacked(rec: &mut Recorder, unpacked: &Buffer) {
    rec.fill_buffer(unpacked, 0);
    rec.barrier(&Barrier::memory(
        "unpacked_clear_to_stencil_accumulate",
        Access::CLEAR_WRITE,
        Access::COMPUTE_READ_WRITE,
    ));
}
