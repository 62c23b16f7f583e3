//! How the GPU space sweep cuts the volume into dispatches and submissions.
//!
//! - A *part* is a run of whole rows of one slice: a whole slice unless its
//!   unpacked histograms exceed the batch budget or the part budget (one
//!   window of the unpacked histograms bound as a storage buffer, within
//!   `maxStorageBufferRange`; large b or large slices).
//! - A *batch* is a run of consecutive parts whose unpacked histograms fit in
//!   the read-back buffer; each batch is one submission, after which the CPU
//!   sums the unpacked histograms per cluster (the final codebook) and the
//!   buffers are reused. Only one batch of unpacked histograms ever exists.
//!   A batch is recorded pass by pass (every part's stencil, then every
//!   part's packing, ...), so each pipeline is bound once per batch.
//! - The stencil loop and the codeword walk are split into chunks that stay
//!   within llvmpipe's loop cap ([`LOOP_BUDGET`] iterations per invocation
//!   and dispatch).

use std::ops::Range;

use glam::UVec3;

use crate::render::view_chunks::LOOP_BUDGET;

/// Floats per packed histogram on the GPU: `packed_dim` rounded up to whole
/// chunks of 8 (the distance loop's unit, as on the CPU); the padding is zero.
pub fn packed_stride(packed_dim: usize) -> usize {
    packed_dim.div_ceil(8) * 8
}

/// Floats per voxel in the unpacked buffer: 2 x (bins + a discard slot).
pub fn unpacked_stride(bins: usize) -> usize {
    2 * (bins + 1)
}

/// Rows `first_row..first_row + rows` of slice `z`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Part {
    pub z: u32,
    pub first_row: u32,
    pub rows: u32,
    /// Linear index of the part's first voxel in the volume.
    pub first_voxel: usize,
    /// ... and in its batch's buffers.
    pub batch_voxel: usize,
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Batch {
    pub parts: Vec<Part>,
    /// The batch's voxels (consecutive linear indices).
    pub voxels: Range<usize>,
}

impl Batch {
    /// The centre slices of the batch's parts.
    pub fn slices(&self) -> Range<u32> {
        let first = self.parts.first().map_or(0, |p| p.z);
        first..self.parts.last().map_or(first, |p| p.z + 1)
    }

    /// The rows of its parts: all of them, or the rows of its one part of a
    /// slice.
    pub fn rows(&self) -> Range<u32> {
        let start = self.parts.iter().map(|p| p.first_row).min().unwrap_or(0);
        start..self.parts.iter().map(|p| p.first_row + p.rows).max().unwrap_or(start)
    }

    /// The slices its stencils read (e_z more on each side), binned once
    /// per batch.
    pub fn binned_slices(&self, extent_z: u32) -> Range<i32> {
        let centre = self.slices();
        centre.start as i32 - extent_z as i32..(centre.end + extent_z) as i32
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct SweepPlan {
    pub dims: UVec3,
    pub bins: usize,
    pub packed_stride: usize,
    pub batches: Vec<Batch>,
    /// Most voxels in a batch (sizes the batch buffers).
    pub batch_voxels: usize,
    /// Most centre slices in a batch (with 2 e_z, sizes the binned slices).
    pub batch_slices: usize,
    /// Stencil entries per histogram dispatch.
    pub stencil_chunks: Vec<Range<usize>>,
    /// Sorted-list entries a codeword-walk dispatch visits, and how many
    /// dispatches cover the whole list.
    pub walk_entries: usize,
    pub walk_chunks: usize,
}

impl SweepPlan {
    /// `max_batch_bytes` bounds the unpacked histograms of one batch,
    /// `max_part_bytes` those of one part.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        dims: UVec3,
        bins: usize,
        packed_dim: usize,
        stencil_entries: usize,
        clusters: usize,
        lmax: bool,
        max_batch_bytes: usize,
        max_part_bytes: usize,
    ) -> Result<SweepPlan, String> {
        let budget = LOOP_BUDGET as usize;
        let stride = packed_stride(packed_dim);
        let voxel_bytes = unpacked_stride(bins) * std::mem::size_of::<f32>();
        let (nx, ny) = (dims.x as usize, dims.y as usize);
        let batch_voxels = (max_batch_bytes / voxel_bytes).max(nx);
        let part_voxels = (max_part_bytes / voxel_bytes).min(batch_voxels);
        let rows_per_part = (part_voxels / nx).clamp(1, ny);
        let mut batches: Vec<Batch> = Vec::new();
        let mut current = Batch { parts: vec![], voxels: 0..0 };
        for z in 0..dims.z {
            for first_row in (0..dims.y).step_by(rows_per_part) {
                let rows = (rows_per_part as u32).min(dims.y - first_row);
                let first_voxel = (z as usize * ny + first_row as usize) * nx;
                let voxels = rows as usize * nx;
                if current.voxels.len() + voxels > batch_voxels {
                    batches.push(std::mem::replace(
                        &mut current,
                        Batch { parts: vec![], voxels: first_voxel..first_voxel },
                    ));
                }
                if current.parts.is_empty() {
                    current.voxels = first_voxel..first_voxel;
                }
                let batch_voxel = current.voxels.len();
                current.parts.push(Part { z, first_row, rows, first_voxel, batch_voxel });
                current.voxels.end = first_voxel + voxels;
            }
        }
        if !current.parts.is_empty() {
            batches.push(current);
        }
        let batch_voxels = batches.iter().map(|b| b.voxels.len()).max().unwrap_or(0);
        let batch_slices = batches.iter().map(|b| b.slices().len()).max().unwrap_or(0);

        // The first stencil chunk also zeroes the voxel's histograms; the
        // gradient takes 3 iterations.
        let per_chunk = budget
            .checked_sub(unpacked_stride(bins) + 8)
            .filter(|&n| n > 0)
            .ok_or_else(|| format!("2^b = {bins} bins do not leave room for a stencil chunk in llvmpipe's loop cap"))?;
        let stencil_chunks =
            (0..stencil_entries.max(1)).step_by(per_chunk).map(|s| s..(s + per_chunk).min(stencil_entries)).collect();
        // Packing: zeroing, every bin and its shares (at most bins + packed_dim), twice.
        let pack_iterations = 2 * (stride + 2 * bins + packed_dim);
        if pack_iterations > budget {
            return Err(format!("packing {bins} bins into {packed_dim} takes more than llvmpipe's loop cap"));
        }
        // One distance: stride / 8 chunks (Lmax: each with an 8-step inner loop);
        // the first chunk also compares the histogram with the previous
        // voxel's (stride / 8) and finds the hint's distance.
        let distance = (stride / 8) * if lmax { 9 } else { 1 };
        let walk_entries = (budget - stride / 8 - distance - 2) / (distance + 1);
        if walk_entries == 0 {
            return Err(format!("a packed dimension of {packed_dim} does not fit llvmpipe's loop cap"));
        }
        let walk_chunks = clusters.div_ceil(walk_entries).max(1);
        Ok(SweepPlan {
            dims,
            bins,
            packed_stride: stride,
            batches,
            batch_voxels,
            batch_slices,
            stencil_chunks,
            walk_entries,
            walk_chunks,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn batches_cover_the_volume_in_order_within_their_budget() {
        let dims = UVec3::new(5, 7, 4);
        let bytes = |voxels: usize| voxels * unpacked_stride(16) * 4;
        for budget_voxels in [1, 5, 12, 35, 36, 70, 1000] {
            let plan = SweepPlan::new(dims, 16, 8, 100, 8, false, bytes(budget_voxels), usize::MAX).unwrap();
            let mut next = 0;
            for batch in &plan.batches {
                assert_eq!(batch.voxels.start, next);
                assert!(batch.voxels.len() <= budget_voxels.max(5), "{budget_voxels}: {batch:?}");
                for part in &batch.parts {
                    assert_eq!(part.first_voxel, next);
                    assert_eq!(part.batch_voxel, next - batch.voxels.start);
                    assert_eq!(part.first_voxel, ((part.z * 7 + part.first_row) * 5) as usize);
                    next += part.rows as usize * 5;
                }
                assert_eq!(batch.voxels.end, next);
                let slices = batch.slices();
                assert!(batch.parts.iter().all(|p| slices.contains(&p.z)), "{batch:?}");
                assert_eq!(batch.binned_slices(2), slices.start as i32 - 2..slices.end as i32 + 2);
                assert!(slices.len() <= plan.batch_slices);
                let rows = batch.rows();
                assert!(batch.parts.iter().all(|p| rows.start <= p.first_row && p.first_row + p.rows <= rows.end));
                assert!(batch.parts.len() == 1 || rows == (0..7), "{batch:?}");
            }
            assert_eq!(next, 5 * 7 * 4, "budget {budget_voxels}");
        }
        // Everything in one batch when it fits: one submission.
        assert_eq!(SweepPlan::new(dims, 16, 8, 100, 8, false, bytes(140), usize::MAX).unwrap().batches.len(), 1);
    }

    /// A part budget below a slice splits slices into parts of whole rows
    /// within it, while a batch still holds as many parts as its own budget
    /// allows: one batch here, parts of 2 rows (10 voxels) each.
    #[test]
    fn parts_stay_within_their_own_budget_in_a_larger_batch() {
        let dims = UVec3::new(5, 7, 4);
        let bytes = |voxels: usize| voxels * unpacked_stride(16) * 4;
        let plan = SweepPlan::new(dims, 16, 8, 100, 8, false, bytes(140), bytes(12)).unwrap();
        assert_eq!(plan.batches.len(), 1);
        let parts = &plan.batches[0].parts;
        assert!(parts.iter().all(|p| p.rows as usize * 5 <= 12), "{parts:?}");
        assert_eq!(parts.iter().map(|p| p.rows as usize * 5).sum::<usize>(), 140);
        assert_eq!(parts.iter().filter(|p| p.z == 0).map(|p| p.rows).collect::<Vec<_>>(), vec![2, 2, 2, 1]);
        // A budget below one row still gives parts of one row.
        let plan = SweepPlan::new(dims, 16, 8, 100, 8, false, bytes(140), bytes(3)).unwrap();
        assert!(plan.batches[0].parts.iter().all(|p| p.rows == 1));
    }

    #[test]
    fn loops_stay_under_the_cap_and_split_only_past_it() {
        let dims = UVec3::splat(4);
        // r = 16: 17,076 stencil voxels, one chunk; r = 32: 137,064, three.
        let plan = SweepPlan::new(dims, 256, 64, 17_076, 2048, false, 1 << 20, usize::MAX).unwrap();
        assert_eq!(plan.stencil_chunks, vec![0..17_076]);
        assert_eq!(plan.walk_chunks, 1, "2048 codewords of 64 floats: one walk dispatch");
        let plan = SweepPlan::new(dims, 256, 64, 137_064, 2048, true, 1 << 20, usize::MAX).unwrap();
        assert_eq!(plan.stencil_chunks.len(), 3);
        assert_eq!(plan.stencil_chunks.last().unwrap().end, 137_064);
        assert!(plan.stencil_chunks.iter().all(|c| c.len() + 8 <= LOOP_BUDGET as usize));
        assert!(plan.walk_chunks * plan.walk_entries >= 2048);
        // The first chunk: the comparison with the previous voxel (8 chunks of
        // 8), the hint's distance, then the entries.
        assert!(8 + plan.walk_entries * (8 * 9 + 1) + 8 * 9 + 2 <= LOOP_BUDGET as usize);
    }
}
