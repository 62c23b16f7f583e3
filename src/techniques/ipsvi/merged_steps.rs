//! The frame's line dispatches. Unmerged, one per block record, sweep after
//! sweep. With `ipsvi.merge_sweeps`, step k of every independent sweep (the
//! zones of a point or spot light, the sweeps of several lights) is one
//! dispatch: the step table lists, per step and sweep, the sweep's k-th block
//! record and the first workgroup of its share, and each workgroup of
//! glsl/ipsvi_line.comp (MERGED) finds its block there. Record k of every sweep
//! has parity k % 2, so one pipeline serves the whole step. (Tried: one
//! workgroup row per sweep, padded to the step's largest block, no search:
//! 10-30 % more CPU time on lavapipe, the padding rows of small blocks.)

use super::gpu_params::BlockParams;

/// One line dispatch: its push constant (block record, or step when merged),
/// the pipeline parity it runs and its workgroups.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LineDispatch {
    pub index: u32,
    pub parity: u32,
    pub groups: u32,
}

/// A step-table entry of a sweep that has no block at that step.
pub const NO_BLOCK: u32 = u32::MAX;

/// Invocations per pixel (`segments`) and per cache texel (`texels`) of a
/// line dispatch: 1 and 1 in the serial kernel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Lanes {
    pub segments: u32,
    pub texels: u32,
}

impl Lanes {
    pub const SERIAL: Lanes = Lanes { segments: 1, texels: 1 };
}

/// Workgroups of a block's line dispatch: `segments` invocations per pixel
/// of the block (1: the serial kernel), then `texels` per texel of the cache
/// region it updates, then (farthest), from the next multiple of `segments`
/// on, `segments` per pixel of the next block it claims texels for; `group`
/// invocations each (glsl/ipsvi_line_main.glsl).
pub fn block_groups(record: &BlockParams, group: u32, lanes: Lanes) -> u32 {
    let segments = lanes.segments;
    let pixels_and_texels = record.pixel_count * segments + record.region[2] * record.region[3] * lanes.texels;
    let claims = record.claim_count * segments;
    let claims_first = if claims > 0 { pixels_and_texels.next_multiple_of(segments) } else { pixels_and_texels };
    (claims_first + claims).div_ceil(group)
}

/// One dispatch per block record, in record order (the unmerged frame).
pub fn per_block(records: &[BlockParams], group: u32, lanes: Lanes) -> Vec<LineDispatch> {
    records
        .iter()
        .enumerate()
        .map(|(i, r)| LineDispatch { index: i as u32, parity: r.parity, groups: block_groups(r, group, lanes) })
        .collect()
}

/// The merged frame: one dispatch per step, and the step table as the shader
/// reads it (sweep count, padding, then per step and sweep: block record,
/// first workgroup).
pub struct MergedSteps {
    pub dispatches: Vec<LineDispatch>,
    pub table: Vec<u32>,
}

/// Merges sweeps given as (first record, record count) of `records`.
pub fn merge(sweeps: &[(usize, usize)], records: &[BlockParams], group: u32, lanes: Lanes) -> MergedSteps {
    let steps = sweeps.iter().map(|s| s.1).max().unwrap_or(0);
    let mut table = vec![sweeps.len() as u32, 0];
    let mut dispatches = Vec::with_capacity(steps);
    for k in 0..steps {
        let mut groups = 0;
        for &(first, count) in sweeps {
            if k < count {
                table.extend([(first + k) as u32, groups]);
                groups += block_groups(&records[first + k], group, lanes);
            } else {
                table.extend([NO_BLOCK, 0]);
            }
        }
        dispatches.push(LineDispatch { index: k as u32, parity: (k % 2) as u32, groups });
    }
    MergedSteps { dispatches, table }
}

impl MergedSteps {
    /// The block records step `step` runs (one per sweep that has one).
    pub fn blocks_of(table: &[u32], step: u32) -> Vec<u32> {
        let sweeps = table.first().copied().unwrap_or(0) as usize;
        (0..sweeps).map(|s| table[2 + 2 * (step as usize * sweeps + s)]).filter(|&b| b != NO_BLOCK).collect()
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn segments_multiply_the_pixel_and_claim_invocations_and_claims_start_aligned() {
        let r = BlockParams { pixel_count: 10, region: [0, 0, 3, 1], claim_count: 5, ..BlockParams::default() };
        let seg = |segments, texels| Lanes { segments, texels };
        // Serial: 10 + 3 + 5 = 18 invocations.
        assert_eq!(block_groups(&r, 1, Lanes::SERIAL), 18);
        // 4 segments: 40 + 3 = 43, claims from 44, 20 more: 64.
        assert_eq!(block_groups(&r, 1, seg(4, 1)), 64);
        assert_eq!(block_groups(&r, 8, seg(4, 1)), 8);
        let no_claims = BlockParams { claim_count: 0, ..r };
        assert_eq!(block_groups(&no_claims, 1, seg(4, 1)), 43);
        // 2 lanes per texel: 40 + 6 = 46, claims from 48, 20 more: 68.
        assert_eq!(block_groups(&r, 1, seg(4, 2)), 68);
    }

    use super::*;

    fn record(pixels: u32, parity: u32) -> BlockParams {
        BlockParams { pixel_count: pixels, parity, ..BlockParams::default() }
    }

    #[test]
    fn each_step_lists_every_sweep_that_reaches_it_with_its_workgroups() {
        // Sweep 0: 3 blocks, sweep 1: 1 block, sweep 2: 2 blocks.
        let records = [record(10, 0), record(8, 1), record(8, 0), record(16, 0), record(3, 0), record(20, 1)];
        let merged = merge(&[(0, 3), (3, 1), (4, 2)], &records, 8, Lanes::SERIAL);
        assert_eq!(merged.dispatches.len(), 3, "as many steps as the longest sweep has blocks");
        assert_eq!(merged.dispatches[0], LineDispatch { index: 0, parity: 0, groups: 2 + 2 + 1 });
        assert_eq!(merged.dispatches[1], LineDispatch { index: 1, parity: 1, groups: 1 + 3 });
        assert_eq!(merged.dispatches[2], LineDispatch { index: 2, parity: 0, groups: 1 });
        assert_eq!(merged.table, [3, 0, 0, 0, 3, 2, 4, 4, 1, 0, NO_BLOCK, 0, 5, 1, 2, 0, NO_BLOCK, 0, NO_BLOCK, 0]);
        for (k, d) in merged.dispatches.iter().enumerate() {
            for s in 0..3 {
                let block = merged.table[2 + 2 * (k * 3 + s)];
                if block != NO_BLOCK {
                    assert_eq!(records[block as usize].parity, d.parity, "step {k} sweep {s}");
                }
            }
        }
        assert_eq!(MergedSteps::blocks_of(&merged.table, 1), [1, 5]);
    }

    #[test]
    fn unmerged_is_one_dispatch_per_record() {
        let records = [record(10, 0), record(0, 1)];
        let d = per_block(&records, 4, Lanes::SERIAL);
        assert_eq!(
            d,
            [LineDispatch { index: 0, parity: 0, groups: 3 }, LineDispatch { index: 1, parity: 1, groups: 0 }]
        );
    }
}
