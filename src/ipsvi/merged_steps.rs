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

/// Workgroups of a block's line dispatch: one invocation per pixel of the
/// block, then one per texel of the cache region it updates, then (farthest)
/// one per pixel of the next block it claims texels for; `group` invocations each.
pub fn block_groups(record: &BlockParams, group: u32) -> u32 {
    (record.pixel_count + record.region[2] * record.region[3] + record.claim_count).div_ceil(group)
}

/// One dispatch per block record, in record order (the unmerged frame).
pub fn per_block(records: &[BlockParams], group: u32) -> Vec<LineDispatch> {
    records
        .iter()
        .enumerate()
        .map(|(i, r)| LineDispatch { index: i as u32, parity: r.parity, groups: block_groups(r, group) })
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
pub fn merge(sweeps: &[(usize, usize)], records: &[BlockParams], group: u32) -> MergedSteps {
    let steps = sweeps.iter().map(|s| s.1).max().unwrap_or(0);
    let mut table = vec![sweeps.len() as u32, 0];
    let mut dispatches = Vec::with_capacity(steps);
    for k in 0..steps {
        let mut groups = 0;
        for &(first, count) in sweeps {
            if k < count {
                table.extend([(first + k) as u32, groups]);
                groups += block_groups(&records[first + k], group);
            } else {
                table.extend([NO_BLOCK, 0]);
            }
        }
        dispatches.push(LineDispatch { index: k as u32, parity: (k % 2) as u32, groups });
    }
    MergedSteps { dispatches, table }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn record(pixels: u32, parity: u32) -> BlockParams {
        BlockParams { pixel_count: pixels, parity, ..BlockParams::default() }
    }

    #[test]
    fn each_step_lists_every_sweep_that_reaches_it_with_its_workgroups() {
        // Sweep 0: 3 blocks, sweep 1: 1 block, sweep 2: 2 blocks.
        let records = [record(10, 0), record(8, 1), record(8, 0), record(16, 0), record(3, 0), record(20, 1)];
        let merged = merge(&[(0, 3), (3, 1), (4, 2)], &records, 8);
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
    }

    #[test]
    fn unmerged_is_one_dispatch_per_record() {
        let records = [record(10, 0), record(0, 1)];
        let d = per_block(&records, 4);
        assert_eq!(
            d,
            [LineDispatch { index: 0, parity: 0, groups: 3 }, LineDispatch { index: 1, parity: 1, groups: 0 }]
        );
    }
}
