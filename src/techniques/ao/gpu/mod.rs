//! The AO preprocessing's per-voxel work on the GPU: the space sweep of local
//! histograms ([`sweep`]) and the nearest-codeword assignment ([`assign`]),
//! with the final codebook summed on the CPU from the streamed read-back.
//! The CPU path (`crate::techniques::ao::preprocess` with `ao.backend = "cpu"`) stays the
//! reference. See docs/ao.md, "GPU space sweep".

pub mod assign;
pub mod plan;
pub mod sweep;

pub use assign::{assign_packed, SearchState};
pub use sweep::{batch_bytes, supported_plan, BatchOutput, GpuSweep, PassTimes, SliceSync, SweepInputs, BATCH_BYTES};

use super::histogram::LocalHistograms;
use super::packing::PackingScheme;
use super::parallel::{for_each_chunk, worker_count};
use super::quantize::{pack_cluster_ids, Codebook};
use super::search::CodebookSearch;
use super::settings::Metric;
use super::{AoError, ClusterSums, VolumeAssignment};
use crate::vk::Context;

/// The GPU's [`VolumeAssignment`] of every voxel, and the GPU time of each
/// pass: the sweep on `ctx`, each batch's unpacked histograms summed per
/// cluster on all CPU cores from the read-back (f64, as the CPU path sums).
/// `progress` gets the fraction done.
pub fn assign_volume(
    ctx: &Context,
    histograms: &LocalHistograms,
    packing: &PackingScheme,
    codebook: &Codebook,
    metric: Metric,
    progress: &mut dyn FnMut(f64),
) -> Result<(VolumeAssignment, PassTimes), AoError> {
    let volume = histograms.volume();
    let (clusters, bins) = (codebook.len(), histograms.bins());
    let search = CodebookSearch::new(codebook, metric);
    let inputs = SweepInputs {
        volume,
        stencil: histograms.stencil(),
        bins,
        packing,
        codebook,
        search: &search,
        metric,
        max_batch_bytes: batch_bytes(ctx, bins, packing.packed_dim),
    };
    let mut sweep = GpuSweep::new(ctx, &inputs)?;
    let total = volume.voxel_count();
    let mut cluster_ids = vec![0u32; total];
    let mut distortion_sum = 0f64;
    let mut sums = ClusterSums::new(clusters, bins);
    let times = sweep.run(SliceSync::Barrier, |batch| {
        for (i, state) in batch.states.chunks(2).enumerate() {
            cluster_ids[batch.voxels.start + i] = pack_cluster_ids(state[0].best, state[1].best);
            distortion_sum += state[0].best_raw as f64 + state[1].best_raw as f64;
        }
        let voxels = batch.voxels.len();
        let chunks = worker_count();
        let per_chunk = voxels.div_ceil(chunks);
        let parts = for_each_chunk(
            chunks,
            || ClusterSums::new(clusters, bins),
            |sums, c| {
                for i in c * per_chunk..((c + 1) * per_chunk).min(voxels) {
                    let (forward, backward) = batch.voxel(i);
                    sums.add_scaled(batch.states[2 * i].best as usize, forward, batch.normalization);
                    sums.add_scaled(batch.states[2 * i + 1].best as usize, backward, batch.normalization);
                }
            },
            |_, (), _| {},
        );
        parts.iter().for_each(|part| sums.absorb(part));
        progress(batch.voxels.end as f64 / total as f64);
        Ok(())
    })?;
    Ok((VolumeAssignment { cluster_ids, sums, distortion_sum }, times))
}
