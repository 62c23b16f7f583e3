//! The reference of the clustering error: the lookup computed from each
//! voxel's *own* two histograms (equations 4-5 exactly as for a cluster, but
//! without the codebook), as a per-voxel lookup for
//! [`crate::techniques::ao::render::AoRenderer::per_voxel`]. The clustered image tends to
//! it as n_c grows. CPU, one thread, every voxel's histograms as the
//! preprocessing computes them: for the volumes of tests and the bench.

use crate::scene::{TransferLut, Volume};
use crate::techniques::ao::environment::{cpu_environment, hemisphere_mass, GlowMapping};
use crate::techniques::ao::histogram::LocalHistograms;
use crate::techniques::ao::AoSettings;

/// Voxels whose histograms are held at once.
const BATCH: usize = 1024;

/// `(E_env, O_env)` per voxel and hemisphere (entry 2 v + h, forward first),
/// then in glow mode the glow block in the same order.
pub fn unclustered_lookup(volume: &Volume, settings: &AoSettings, lut: &TransferLut) -> Vec<[f32; 4]> {
    let histograms = LocalHistograms::new(volume, settings.radius, settings.bits);
    let bins = histograms.bins();
    let mass = hemisphere_mass(volume, settings.radius);
    let glow = GlowMapping::from_settings(settings);
    let voxels = volume.voxel_count();
    let mut scratch = histograms.scratch();
    let mut lookup = vec![[0f32; 4]; 2 * voxels];
    let mut glow_block = Vec::new();
    let mut batch = vec![0f32; 2 * BATCH * bins];
    for first in (0..voxels).step_by(BATCH) {
        let count = BATCH.min(voxels - first);
        // As the preprocessing computes them, interleaved for cpu_environment.
        let slab = histograms.slab(first..first + count, &mut scratch);
        for i in 0..count {
            let (forward, backward) = slab.voxel(i);
            batch[2 * i * bins..(2 * i + 1) * bins].copy_from_slice(forward);
            batch[(2 * i + 1) * bins..(2 * i + 2) * bins].copy_from_slice(backward);
        }
        let env = cpu_environment(&batch[..2 * count * bins], bins, lut, mass, glow);
        lookup[2 * first..2 * (first + count)].copy_from_slice(&env[..2 * count]);
        glow_block.extend_from_slice(&env[2 * count..]);
    }
    lookup.extend(glow_block);
    lookup
}
