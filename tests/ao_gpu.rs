//! AO preprocessing on the GPU (docs/ao.md, "GPU space sweep"): the space
//! sweep equals the brute-force CPU histograms, its assignment equals the CPU
//! search on the same packed vectors, the slice barrier is load-bearing, and
//! the GPU assignment of given vectors equals the CPU's for every metric.
//! Validation and synchronization validation on: any message fails.

mod common;

use common::{assert_validation_clean, validated_context};
use glam::{UVec3, Vec3};
use sweeplab::ao::gpu::{assign_packed, GpuSweep, SliceSync, SweepInputs, BATCH_BYTES};
use sweeplab::ao::gradient::central_gradient;
use sweeplab::ao::histogram::LocalHistograms;
use sweeplab::ao::packing::PackingScheme;
use sweeplab::ao::quantize::{train_lbg, Codebook, LbgParams};
use sweeplab::ao::search::CodebookSearch;
use sweeplab::ao::Metric;
use sweeplab::scene::{Volume, VoxelData};
use sweeplab::vk::Context;

/// `dims` U8 volume: seeded noise, with a constant block (zero gradient
/// inside it) in the low corner and two plateaus, so both hemispheres, plane
/// voxels, flat regions and borders all occur.
fn test_volume(dims: UVec3, spacing: Vec3, seed: u64) -> Volume {
    let mut state = seed;
    let mut data = Vec::new();
    for z in 0..dims.z {
        for y in 0..dims.y {
            for x in 0..dims.x {
                state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
                let v = if x < 4 && y < 4 && z < 4 {
                    90
                } else if x > dims.x / 2 {
                    200 + ((state >> 60) as u8 & 1)
                } else {
                    (state >> 56) as u8
                };
                data.push(v);
            }
        }
    }
    Volume {
        name: "ao-gpu-test".into(),
        dims,
        spacing,
        data: VoxelData::U8(data),
        value_range: (0.0, 255.0),
        non_finite_voxels: 0,
    }
}

/// The global histogram's packing scheme, as `preprocess` builds it.
fn packing_of(h: &LocalHistograms, packed_dim: usize) -> PackingScheme {
    let mut global = vec![0f64; h.bins()];
    for &k in h.voxel_bins() {
        global[k as usize] += 1.0;
    }
    PackingScheme::from_histogram(&global, packed_dim)
}

/// The CPU-packed forward and backward histograms of every `step`-th voxel.
fn packed_histograms(h: &LocalHistograms, packing: &PackingScheme, step: usize) -> Vec<f32> {
    let dim = packing.packed_dim;
    let (mut f, mut b) = (vec![0f32; h.bins()], vec![0f32; h.bins()]);
    let mut vectors = Vec::new();
    let mut scratch = h.scratch();
    for voxel in (0..h.volume().voxel_count()).step_by(step) {
        h.voxel_into(voxel, &mut scratch, &mut f, &mut b);
        for side in [&f, &b] {
            let mut packed = vec![0f32; dim];
            packing.pack(side, &mut packed);
            vectors.extend(packed);
        }
    }
    vectors
}

/// A codebook trained on the packed histograms of every third voxel.
fn codebook_of(h: &LocalHistograms, packing: &PackingScheme, clusters: usize, metric: Metric) -> Codebook {
    let params = LbgParams { metric, clusters, max_iterations: 10, threshold: 1e-3 };
    train_lbg(&packed_histograms(h, packing, 3), packing.packed_dim, params, &mut |_| {}).codebook
}

/// Largest |gpu - cpu| over all bins of all voxels, in units of the bin's
/// tolerance, and how many hemisphere searches differ from the CPU search of
/// the GPU's own (read back and CPU-packed) histograms.
struct Comparison {
    worst: f64,
    search_mismatches: usize,
    batches: usize,
    voxels: usize,
}

/// Sweeps `volume` on the GPU and compares with the brute-force reference.
///
/// Tolerance, per bin: the GPU sums a bin's weights in f32 (each weight
/// rounded to f32 once, then runs of equal bins summed before they are added),
/// the reference in f64. Every partial sum of positive terms is at most the
/// bin's value v, and a bin receives at most N_r terms, so with the rounding
/// of the weights and of the normalization the GPU is off by less than
/// (N_r + 4) u v, u = 2^-24. A bin the reference leaves empty received no
/// weight, so the GPU's must be exactly 0.
fn compare(
    ctx: &Context,
    volume: &Volume,
    radius: u32,
    bits: u32,
    metric: Metric,
    max_batch_bytes: usize,
    sync: SliceSync,
) -> Comparison {
    let h = LocalHistograms::new(volume, radius, bits);
    let stencil = h.stencil();
    let packing = packing_of(&h, 8.min(h.bins()));
    let codebook = codebook_of(&h, &packing, 6, metric);
    let search = CodebookSearch::new(&codebook, metric);
    let relative_tolerance = (stencil.voxel_count() as f64 + 4.0) * f64::from(f32::EPSILON) / 2.0;
    let inputs = SweepInputs {
        volume,
        stencil,
        bins: h.bins(),
        packing: &packing,
        codebook: &codebook,
        search: &search,
        metric,
        max_batch_bytes,
    };
    let mut sweep = GpuSweep::new(ctx, &inputs).unwrap();
    let mut result = Comparison { worst: 0.0, search_mismatches: 0, batches: 0, voxels: 0 };
    let (mut f, mut b) = (vec![0f32; h.bins()], vec![0f32; h.bins()]);
    let mut scratch = h.scratch();
    let mut packed = vec![0f32; packing.packed_dim];
    sweep
        .run(sync, |batch| {
            assert_eq!(batch.voxels.start, result.voxels, "batches in order");
            result.batches += 1;
            for (i, voxel) in batch.voxels.clone().enumerate() {
                h.voxel_into(voxel, &mut scratch, &mut f, &mut b);
                let (gf, gb) = batch.voxel(i);
                for (gpu, cpu) in [(gf, &f), (gb, &b)] {
                    for (&g, &c) in gpu.iter().zip(cpu.iter()) {
                        let off = (g as f64 - c as f64).abs() / (relative_tolerance * c as f64);
                        result.worst = result.worst.max(if g == c { 0.0 } else { off });
                    }
                }
                for (side, histogram) in [gf, gb].into_iter().enumerate() {
                    packing.pack(histogram, &mut packed);
                    let state = batch.states[2 * i + side];
                    let cpu = codebook.nearest(metric, &packed, 0);
                    result.search_mismatches += usize::from((state.best as usize, state.best_raw) != cpu);
                }
            }
            result.voxels = batch.voxels.end;
            Ok(())
        })
        .unwrap();
    assert_eq!(result.voxels, volume.voxel_count());
    result
}

#[test]
fn the_space_sweep_equals_brute_force_on_small_volumes() {
    let ctx = validated_context();
    // Isotropic and anisotropic, one batch (one submission) and many small
    // batches of parts of slices, b = 8 and b = 4, every metric.
    let cases = [
        (UVec3::new(11, 9, 8), Vec3::ONE, 3, 8, Metric::L2, BATCH_BYTES),
        (UVec3::new(10, 7, 9), Vec3::new(1.0, 1.5, 0.75), 3, 4, Metric::L1, BATCH_BYTES),
        (UVec3::new(9, 10, 6), Vec3::new(2.0, 1.0, 1.0), 2, 8, Metric::Lmax, 3 * 9 * 2 * 257 * 4),
    ];
    for (i, (dims, spacing, radius, bits, metric, batch_bytes)) in cases.into_iter().enumerate() {
        let volume = test_volume(dims, spacing, i as u64 + 1);
        // Inside the constant block: a zero gradient (two equal hemispheres).
        assert_eq!(central_gradient(&volume, UVec3::ONE), Vec3::ZERO);
        let c = compare(&ctx, &volume, radius, bits, metric, batch_bytes, SliceSync::Barrier);
        assert!(c.worst <= 1.0, "case {i}: a bin off by {:.2} tolerances", c.worst);
        assert_eq!(c.search_mismatches, 0, "case {i}: the GPU search differs from the CPU's");
        if batch_bytes < BATCH_BYTES {
            assert!(c.batches > dims.z as usize, "case {i}: parts of slices in several batches: {}", c.batches);
        } else {
            assert_eq!(c.batches, 1, "case {i}");
        }
    }
    assert_validation_clean(&ctx);
}

#[test]
fn a_stencil_past_the_loop_cap_is_split_and_still_equals_brute_force() {
    // r = 32: N_r = 137,064 stencil voxels, three dispatches per slice (a
    // single one would be cut off by llvmpipe after 65,535 iterations).
    let ctx = validated_context();
    let volume = test_volume(UVec3::new(6, 5, 4), Vec3::ONE, 7);
    let h = LocalHistograms::new(&volume, 32, 4);
    assert_eq!(h.stencil().voxel_count(), 137_064);
    let c = compare(&ctx, &volume, 32, 4, Metric::L2, BATCH_BYTES, SliceSync::Barrier);
    assert!(c.worst <= 1.0, "a bin off by {:.2} tolerances", c.worst);
    assert_eq!(c.search_mismatches, 0);
    assert_validation_clean(&ctx);
}

/// The barrier between binning the entering slice and the stencil reading
/// it is load-bearing: recorded without it, synchronization validation
/// reports the hazard on the ring (with it, clean: the tests above).
#[test]
fn the_sweep_without_its_slice_barrier_is_reported_by_sync_validation() {
    let ctx = validated_context();
    let volume = test_volume(UVec3::new(6, 6, 5), Vec3::ONE, 3);
    compare(&ctx, &volume, 2, 4, Metric::L2, BATCH_BYTES, SliceSync::RacyNoSliceBarrier);
    let messages = ctx.take_validation_messages();
    assert!(
        messages.iter().any(|m| m.contains("SYNC-HAZARD-READ-AFTER-WRITE") && m.contains("ao binned slice ring")),
        "the racy sweep was not reported: {messages:?}"
    );
}

#[test]
fn the_gpu_assignment_equals_the_cpu_search_for_every_metric_and_hint() {
    let ctx = validated_context();
    let volume = test_volume(UVec3::new(8, 8, 6), Vec3::ONE, 5);
    let h = LocalHistograms::new(&volume, 2, 8);
    let packing = packing_of(&h, 12);
    let dim = packing.packed_dim;
    // The CPU-packed histograms of every voxel (12 floats: not a multiple of 8).
    let vectors = packed_histograms(&h, &packing, 1);
    let count = vectors.len() / dim;
    for metric in Metric::ALL {
        let codebook = codebook_of(&h, &packing, 24, metric);
        let search = CodebookSearch::new(&codebook, metric);
        let hints: Vec<u32> = (0..count as u32).map(|i| (i * 7) % 24).collect();
        for hints in [None, Some(hints.as_slice())] {
            let gpu = assign_packed(&ctx, &vectors, &codebook, metric, hints).unwrap();
            for (i, x) in vectors.chunks(dim).enumerate() {
                let hint = hints.map_or(0, |h| h[i] as usize);
                let cpu = search.nearest(x, hint);
                assert_eq!((gpu[i].0 as usize, gpu[i].1), cpu, "{metric:?} vector {i} hint {hint}");
                assert_eq!(cpu, codebook.nearest(metric, x, 0), "{metric:?}: the exhaustive search");
            }
        }
    }
    assert_validation_clean(&ctx);
}
