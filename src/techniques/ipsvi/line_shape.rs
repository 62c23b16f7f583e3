//! The counters behind an IPSVI frame's [`LineShape`]: a small buffer the line
//! kernels add to (glsl/ipsvi_shape.glsl `Shape`: flags, the view-stops pass's
//! chain maxima, and per block
//! record [`CHAIN_SLOTS`] maxima of its invocations' serial chains, a run of
//! [`CHAIN_ROLE_SLOTS`] for each role), cleared at the start of every frame and
//! copied back at its end.

use super::gpu_params::BlockParams;
use super::merged_steps::LineDispatch;
use crate::render::{ChainsByRole, LineShape, RenderError, StopsPassShape};
use crate::vk::barriers::{Access, Barrier};
use crate::vk::{Buffer, Context, Recorder, VkError};
use ash::vk;
use gpu_allocator::MemoryLocation;

/// Bytes before the chains: the two 64-bit digests, the flags word and the
/// view-stops pass's CHAIN_ROLE_SLOTS maxima.
const HEADER_BYTES: u64 = 20 + 4 * CHAIN_ROLE_SLOTS as u64;
/// The first word of the view-stops pass's maxima.
const STOPS_CHAIN_WORD: usize = 5;

/// glsl/ipsvi_shape.glsl SHAPE_PARTIAL_SUBGROUPS.
const PARTIAL_SUBGROUPS: u32 = 1;

/// glsl/ipsvi_shape.glsl CHAIN_ROLE_SLOTS: maxima per role and block
/// record, the roles in [`ChainsByRole`]'s order (CHAIN_PIXELS, CHAIN_TEXELS,
/// CHAIN_CLAIMS).
const CHAIN_ROLE_SLOTS: usize = 16;
const CHAIN_SLOTS: usize = 3 * CHAIN_ROLE_SLOTS;

pub struct ShapeCounters {
    /// Written by the line dispatches (device-local: every workgroup adds to it).
    pub counters: Buffer,
    readback: Buffer,
    records: usize,
}

impl ShapeCounters {
    /// The device-local counters of a frame of `records` block records (the
    /// technique lists them with its resources).
    pub fn bytes(records: usize) -> u64 {
        (HEADER_BYTES + 4 * (records * CHAIN_SLOTS) as u64).next_multiple_of(8)
    }

    pub fn new(ctx: &Context, records: usize) -> Result<ShapeCounters, VkError> {
        let bytes = ShapeCounters::bytes(records);
        let usage = vk::BufferUsageFlags::STORAGE_BUFFER
            | vk::BufferUsageFlags::TRANSFER_DST
            | vk::BufferUsageFlags::TRANSFER_SRC;
        let counters = Buffer::new(ctx, "ipsvi line shape", bytes, usage, MemoryLocation::GpuOnly)?;
        let readback = Buffer::staging(
            ctx,
            "ipsvi line shape readback",
            bytes,
            vk::BufferUsageFlags::TRANSFER_DST,
            MemoryLocation::GpuToCpu,
        )?;
        Ok(ShapeCounters { counters, readback, records })
    }

    /// Zeroes the counters; the frame's clear barriers (global) order it
    /// before the first line dispatch.
    pub fn record_clear(&self, rec: &mut Recorder) {
        rec.fill_buffer(&self.counters, 0);
    }

    /// After the frame's last line dispatch: the counters to the host.
    pub fn record_readback(&self, rec: &mut Recorder) {
        rec.barrier(&Barrier::memory(
            "line_shape_write_to_readback_copy",
            Access::COMPUTE_WRITE,
            Access::TRANSFER_READ,
        ));
        rec.copy_buffer(&self.counters, &self.readback);
        rec.barrier(&Barrier::memory("line_shape_copy_to_host_read", Access::TRANSFER_WRITE, Access::HOST_READ));
    }

    /// The frame's shape, once its submission finished: per line dispatch
    /// its invocations and the longest chain of each role in the blocks it
    /// ran, and the view-stops pass's where it ran `stops_invocations`.
    #[allow(clippy::too_many_arguments)]
    pub fn read(
        &self,
        kernel: String,
        dispatches: &[LineDispatch],
        blocks_of: impl Fn(&LineDispatch) -> Vec<u32>,
        records: &[BlockParams],
        group: u32,
        digests: bool,
        stops_invocations: Option<u64>,
    ) -> Result<LineShape, RenderError> {
        let words: Vec<u32> = self.readback.read(HEADER_BYTES as usize / 4 + self.records * CHAIN_SLOTS)?;
        if words[4] & PARTIAL_SUBGROUPS != 0 {
            return Err(RenderError::Invalid(
                "ipsvi.line_kernel = \"segmented\": this device ran the line dispatches in partial subgroups, \
                 over which a pixel's segments cannot be combined; use ipsvi.line_kernel = \"serial\""
                    .into(),
            ));
        }
        let slots = &words[HEADER_BYTES as usize / 4..];
        let role_of = |b: u32, role: usize| {
            let first = b as usize * CHAIN_SLOTS + role * CHAIN_ROLE_SLOTS;
            slots[first..][..CHAIN_ROLE_SLOTS].iter().copied().max().unwrap_or(0)
        };
        let per_dispatch: Vec<(u32, ChainsByRole)> = dispatches
            .iter()
            .filter_map(|d| {
                let blocks = blocks_of(d);
                let shades = blocks.iter().any(|&b| records[b as usize].pixel_count > 0);
                let longest = |role| blocks.iter().map(|&b| role_of(b, role)).max().unwrap_or(0);
                let chains = ChainsByRole { pixels: longest(0), texels: longest(1), claims: longest(2) };
                shades.then_some((d.groups * group, chains))
            })
            .collect();
        let mut shape = LineShape::from_dispatches(kernel, &per_dispatch);
        shape.stops_pass = stops_invocations.map(|invocations| StopsPassShape {
            invocations,
            chain: words[STOPS_CHAIN_WORD..][..CHAIN_ROLE_SLOTS].iter().copied().max().unwrap_or(0),
        });
        if digests {
            let digest = |w: usize| u64::from(words[w]) | (u64::from(words[w + 1]) << 32);
            shape.claim_digest = Some(digest(0));
            shape.stop_digest = Some(digest(2));
        }
        Ok(shape)
    }
}
