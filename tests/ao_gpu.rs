//! AO preprocessing on the GPU (docs/ao.md, "GPU space sweep"): the space
//! sweep equals the brute-force CPU histograms, its assignment equals the CPU
//! search on the same packed vectors (a histogram equal to its neighbour's
//! copied, not searched), the barriers are load-bearing, and the GPU
//! assignment of given vectors equals the CPU's for every metric.
//! Validation and synchronization validation on: any message fails.

use crate::common;

use common::{assert_validation_clean, validated_context};
use glam::{UVec3, Vec3};
use sweeplab::scene::Volume;
use sweeplab::techniques::ao::gpu::{
    assign_packed, batch_bytes, supported_plan, GpuSweep, SearchState, SliceSync, SweepInputs, BATCH_BYTES,
};
use sweeplab::techniques::ao::gradient::central_gradient;
use sweeplab::techniques::ao::histogram::LocalHistograms;
use sweeplab::techniques::ao::packing::PackingScheme;
use sweeplab::techniques::ao::quantize::{train_lbg, Codebook, LbgParams};
use sweeplab::techniques::ao::search::CodebookSearch;
use sweeplab::techniques::ao::Metric;
use sweeplab::vk::Context;

/// `dims` U8 volume: seeded noise, with a constant block (zero gradient
/// inside it) in the low corner and two plateaus, so both hemispheres, plane
/// voxels, flat regions and borders all occur.
fn test_volume(dims: UVec3, spacing: Vec3, seed: u64) -> Volume {
    common::seeded_volume("ao-gpu-test", dims, spacing, seed, |p, random| {
        if p.x < 4 && p.y < 4 && p.z < 4 {
            90
        } else if p.x > dims.x / 2 {
            200 + ((random >> 60) as u8 & 1)
        } else {
            (random >> 56) as u8
        }
    })
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
    /// Hemisphere histograms the GPU copied instead of searching...
    copies: usize,
    /// ... and those equal to the same hemisphere of the voxel before, that
    /// voxel in the same slice and window of 32 voxels (where the parts are
    /// whole slices, exactly the ones to copy).
    equal_to_previous: usize,
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
    let mut result =
        Comparison { worst: 0.0, search_mismatches: 0, batches: 0, voxels: 0, copies: 0, equal_to_previous: 0 };
    let (mut f, mut b) = (vec![0f32; h.bins()], vec![0f32; h.bins()]);
    let mut scratch = h.scratch();
    let mut packed = vec![0f32; packing.packed_dim];
    let slice_voxels = (volume.dims.x * volume.dims.y) as usize;
    let mut previous = [vec![], vec![]];
    sweep
        .run(sync, |batch| {
            assert_eq!(batch.voxels.start, result.voxels, "batches in order");
            result.batches += 1;
            for (i, voxel) in batch.voxels.clone().enumerate() {
                h.voxel_into(voxel, &mut scratch, &mut f, &mut b);
                let normalized = |h: &[f32]| h.iter().map(|&v| v * batch.normalization).collect::<Vec<f32>>();
                let (gf, gb) = batch.voxel(i);
                let (gf, gb) = (normalized(gf), normalized(gb));
                for (gpu, cpu) in [(&gf, &f), (&gb, &b)] {
                    for (&g, &c) in gpu.iter().zip(cpu.iter()) {
                        let off = (g as f64 - c as f64).abs() / (relative_tolerance * c as f64);
                        result.worst = result.worst.max(if g == c { 0.0 } else { off });
                    }
                }
                for (side, histogram) in [gf, gb].into_iter().enumerate() {
                    packing.pack(&histogram, &mut packed);
                    let state = batch.states[2 * i + side];
                    let cpu = codebook.nearest(metric, &packed, 0);
                    result.search_mismatches += usize::from((state.best as usize, state.best_raw) != cpu);
                    result.copies += usize::from(state.done == SearchState::COPY);
                    let in_window = !(voxel % slice_voxels).is_multiple_of(32);
                    result.equal_to_previous += usize::from(in_window && packed == previous[side]);
                    previous[side].clone_from(&packed);
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

/// A hemisphere histogram equal to the previous voxel's is not searched: the
/// GPU copies its run's result after the walk (the CPU's shortcut), exactly
/// where the histograms are equal, and still picks the exhaustive search's
/// codeword.
#[test]
fn equal_neighbours_take_their_runs_result_without_a_search() {
    let ctx = validated_context();
    // Noise beside a flat block (x >= 8, one bin), so runs of equal
    // histograms along x, broken where the stencil meets the noise.
    let dims = UVec3::new(48, 6, 5);
    let value = |p: UVec3, random: u64| if p.x >= 8 { 200 } else { (random >> 56) as u8 };
    let volume = common::seeded_volume("ao-gpu-runs", dims, Vec3::ONE, 17, value);
    for metric in Metric::ALL {
        let c = compare(&ctx, &volume, 1, 4, metric, BATCH_BYTES, SliceSync::Barrier);
        assert_eq!(c.batches, 1, "{metric:?}: whole slices in one batch");
        assert_eq!(c.search_mismatches, 0, "{metric:?}: a copy differs from the exhaustive search");
        assert_eq!(c.copies, c.equal_to_previous, "{metric:?}: copied exactly where equal to the voxel before");
        // More than half of the 2 x voxels hemisphere histograms.
        assert!(c.copies > volume.voxel_count(), "{metric:?}: {} of the histograms copied", c.copies);
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

/// The parts follow the device's `maxStorageBufferRange`: with the limit
/// forced down to 64 KiB, a volume whose unpacked histograms take 1.6 MB is
/// swept in one batch whose parts (each bound as its own window of the
/// batch's buffer, at offsets aligned for the device) fit the limit, and
/// still equals brute force; validation (which checks every window's range
/// and offset) stays clean. A budget of 20 KiB splits it into batches too.
#[test]
fn a_small_storage_buffer_range_binds_the_batch_in_windows_that_fit() {
    let mut ctx = validated_context();
    let limit = 64 << 10;
    ctx.limits.max_storage_buffer_range = limit;
    let volume = test_volume(UVec3::new(11, 9, 8), Vec3::ONE, 11);
    let (bins, packed_dim) = (256, 8);
    let bytes = batch_bytes(&ctx, bins, packed_dim);
    let per_voxel = 2 * (bins + 1) * 4;
    assert!(volume.voxel_count() * per_voxel > limit as usize, "the unbatched sweep must exceed the limit");
    assert!(bytes >= volume.voxel_count() * per_voxel, "the packed histograms and states fit: one batch");
    // Each part, with what aligning its window's offset adds, fits the limit;
    // a whole slice (99 voxels, 203 kB) would not.
    let h = LocalHistograms::new(&volume, 2, 8);
    let plan = supported_plan(&ctx, &volume, h.stencil(), bins, packed_dim, 6, false).unwrap();
    let align = ctx.limits.min_storage_buffer_offset_alignment as usize;
    let parts: Vec<_> = plan.batches.iter().flat_map(|b| &b.parts).collect();
    assert!(parts.iter().all(|p| p.rows as usize * 11 * per_voxel + align <= limit as usize), "{parts:?}");
    assert!(parts.iter().any(|p| p.rows < 9), "slices split into parts");
    let c = compare(&ctx, &volume, 2, 8, Metric::L2, bytes, SliceSync::Barrier);
    assert_eq!(c.batches, 1, "one batch bound in windows");
    assert!(c.worst <= 1.0, "a bin off by {:.2} tolerances", c.worst);
    assert_eq!(c.search_mismatches, 0);
    let c = compare(&ctx, &volume, 2, 8, Metric::L2, 20 << 10, SliceSync::Barrier);
    assert!(c.batches > 1, "a 20 KiB batch budget");
    assert!(c.worst <= 1.0, "a bin off by {:.2} tolerances", c.worst);
    assert_eq!(c.search_mismatches, 0);
    assert_validation_clean(&ctx);
}

/// `ao.backend = "gpu"` end to end at the device's real limit: a volume
/// whose unpacked histograms (70,560 voxels x 2,056 bytes at b = 8, 145 MB)
/// exceed lavapipe's 128 MiB `maxStorageBufferRange` in one batch. Before the
/// batches followed the limit, the validation layer reported
/// VUID-VkWriteDescriptorSet-descriptorType-00333 here; now clean, and the
/// result equals the CPU backend's.
#[test]
fn the_gpu_backend_past_one_storage_buffer_range_is_validation_clean_and_equals_the_cpu() {
    use sweeplab::techniques::ao::{preprocess_on, AoSettings, Backend, TrainingSet};
    let ctx = validated_context();
    let volume = test_volume(UVec3::new(42, 42, 40), Vec3::ONE, 13);
    let unbatched = volume.voxel_count() as u64 * 2 * 257 * 4;
    let range = u64::from(ctx.limits.max_storage_buffer_range);
    if unbatched <= range {
        eprintln!("skipped: this device's maxStorageBufferRange ({range}) holds the whole volume");
        return;
    }
    let settings = AoSettings {
        radius: 1,
        packed_dim: 8,
        clusters: 8,
        training: TrainingSet::Random { count: 512, seed: 3 },
        cache: false,
        backend: Some(Backend::Gpu),
        ..AoSettings::default()
    };
    let gpu = preprocess_on(&volume, &settings, Some(&ctx), &mut |_| {}).unwrap();
    assert_validation_clean(&ctx);
    let cpu =
        preprocess_on(&volume, &AoSettings { backend: Some(Backend::Cpu), ..settings }, None, &mut |_| {}).unwrap();
    assert_eq!(gpu.packed_codebook, cpu.packed_codebook, "the same training");
    let differing = gpu.cluster_ids.iter().zip(&cpu.cluster_ids).filter(|(g, c)| g != c).count();
    assert!(differing * 1000 <= volume.voxel_count(), "{differing} voxels assigned differently");
}

/// Records the sweep with one barrier left out and asserts that
/// synchronization validation reports the read-after-write hazard on the
/// resource it protects (with every barrier, clean: the tests above).
fn assert_racy_sweep_reported(sync: SliceSync, resource: &str) {
    let ctx = validated_context();
    let volume = test_volume(UVec3::new(6, 6, 5), Vec3::ONE, 3);
    compare(&ctx, &volume, 2, 4, Metric::L2, BATCH_BYTES, sync);
    let messages = ctx.take_validation_messages();
    assert!(
        messages.iter().any(|m| m.contains("SYNC-HAZARD-READ-AFTER-WRITE") && m.contains(resource)),
        "the sweep without its barrier on {resource} was not reported: {messages:?}"
    );
}

/// The barrier between binning the batch's slices and the stencil reading
/// it is load-bearing.
#[test]
fn the_sweep_without_its_slice_barrier_is_reported_by_sync_validation() {
    assert_racy_sweep_reported(SliceSync::RacyNoSliceBarrier, "ao binned slices");
}

/// The barrier between one slice's searches writing their results as hints
/// and the next slice's searches reading them is load-bearing (the shader
/// reads and writes them through separate bindings, the halves of one buffer
/// ping-ponged, so that validation can see the hazard).
#[test]
fn the_sweep_without_its_hints_barrier_is_reported_by_sync_validation() {
    assert_racy_sweep_reported(SliceSync::RacyNoHintsBarrier, "ao search hints");
}

/// The barrier between a part's searches and the copies of their results to
/// equal neighbours is load-bearing (the copies read the results through a
/// read-only binding of the states).
#[test]
fn the_sweep_without_its_run_copy_barrier_is_reported_by_sync_validation() {
    assert_racy_sweep_reported(SliceSync::RacyNoRunCopyBarrier, "ao search states");
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

/// The whole preprocessing with `ao.backend = "gpu"` against the CPU
/// reference on the Cornell box: the same packing and training (both on the
/// CPU), the same cluster ids except at near ties (the histograms differ in
/// the last bits), and the final codebook (mean unpacked histogram per
/// cluster) to the histograms' f32 tolerance.
#[test]
fn gpu_preprocessing_equals_the_cpu_reference() {
    use sweeplab::techniques::ao::quantize::{distance, unpack_cluster_ids};
    use sweeplab::techniques::ao::{preprocess_on, AoSettings, Backend, TrainingSet};
    let ctx = validated_context();
    let volume = sweeplab::scene::synthetic::cornell_box(14);
    for metric in [Metric::L2, Metric::Lmax] {
        let settings = AoSettings {
            radius: 3,
            packed_dim: 16,
            clusters: 32,
            metric,
            training: TrainingSet::Random { count: 1024, seed: 5 },
            cache: false,
            ..AoSettings::default()
        };
        let mut steps = Vec::new();
        let gpu = preprocess_on(&volume, &settings, Some(&ctx), &mut |p| steps.push(p.step.to_string())).unwrap();
        assert!(steps.iter().any(|s| s == "ao gpu sweep and assignment"), "{steps:?}");
        let cpu_settings = AoSettings { backend: Some(Backend::Cpu), ..settings.clone() };
        let cpu = preprocess_on(&volume, &cpu_settings, Some(&ctx), &mut |_| {}).unwrap();
        assert_eq!(
            (gpu.packing_matrix.clone(), gpu.packed_codebook.clone()),
            (cpu.packing_matrix, cpu.packed_codebook)
        );

        let h = LocalHistograms::new(&volume, settings.radius, settings.bits);
        let packing = packing_of(&h, settings.packed_dim as usize);
        let dim = packing.packed_dim;
        let word = |c: u32| &gpu.packed_codebook[c as usize * dim..(c as usize + 1) * dim];
        let (mut f, mut b) = (vec![0f32; h.bins()], vec![0f32; h.bins()]);
        let (mut packed, mut scratch, mut differing) = (vec![0f32; dim], h.scratch(), 0);
        for voxel in 0..volume.voxel_count() {
            if gpu.cluster_ids[voxel] == cpu.cluster_ids[voxel] {
                continue;
            }
            h.voxel_into(voxel, &mut scratch, &mut f, &mut b);
            let (g, c) = (unpack_cluster_ids(gpu.cluster_ids[voxel]), unpack_cluster_ids(cpu.cluster_ids[voxel]));
            for (histogram, g, c) in [(&f, g.0, c.0), (&b, g.1, c.1)] {
                packing.pack(histogram, &mut packed);
                let (dg, dc) = (distance(metric, &packed, word(g)), distance(metric, &packed, word(c)));
                assert!((dg - dc).abs() <= 1e-5 * dc.max(1e-12), "voxel {voxel}: no near tie, {dg} vs {dc}");
            }
            differing += 1;
        }
        assert!(differing * 1000 <= volume.voxel_count(), "{metric:?}: {differing} voxels differ");
        let tolerance = (h.stencil().voxel_count() as f64 + 6.0) * f64::from(f32::EPSILON) / 2.0;
        let bins = h.bins();
        let mut compared = 0;
        for c in 0..settings.clusters as usize {
            if gpu.cluster_sizes[c] != cpu.cluster_sizes[c] {
                assert!(differing > 0, "{metric:?}: cluster {c} differs in size with equal ids");
                continue;
            }
            compared += 1;
            for k in c * bins..(c + 1) * bins {
                let (g, r) = (gpu.codebook[k] as f64, cpu.codebook[k] as f64);
                assert!((g - r).abs() <= tolerance * r, "{metric:?}: cluster {c} bin {}: {g} vs {r}", k - c * bins);
            }
        }
        assert!(compared * 10 >= 9 * settings.clusters as usize, "{metric:?}: {compared} clusters compared");
        let (dg, dc) = (gpu.stats.assignment_distortion, cpu.stats.assignment_distortion);
        assert!((dg - dc).abs() <= 1e-5 * dc, "{metric:?}: distortion {dg} vs {dc}");
    }
    assert_validation_clean(&ctx);
}

/// GPU results are cached apart from the CPU's (they may differ in the last
/// bits); `backend = "gpu"` without a device is an error.
#[test]
fn the_backend_is_part_of_the_cache_key_and_gpu_needs_a_device() {
    use sweeplab::techniques::ao::{preprocess_cached_on, AoSettings, Backend, CacheOutcome, TrainingSet};
    let ctx = validated_context();
    let volume = test_volume(UVec3::new(8, 7, 6), Vec3::ONE, 9);
    let dir = std::env::temp_dir().join(format!("sweeplab-ao-gpu-cache-{}", std::process::id()));
    // Empty: a failed earlier run whose process had the same id may have left entries.
    let _ = std::fs::remove_dir_all(&dir);
    let settings = AoSettings {
        radius: 2,
        packed_dim: 8,
        clusters: 4,
        training: TrainingSet::Random { count: 64, seed: 1 },
        cache_dir: Some(dir.to_string_lossy().into_owned()),
        ..AoSettings::default()
    };
    let stored = |outcome: CacheOutcome| match outcome {
        CacheOutcome::Stored(path, _) => path,
        other => panic!("expected a miss and a store, got {other:?}"),
    };
    let (gpu, outcome) = preprocess_cached_on(&volume, &settings, Some(&ctx), &mut |_| {}).unwrap();
    let gpu_file = stored(outcome);
    let (cpu, outcome) = preprocess_cached_on(&volume, &settings, None, &mut |_| {}).unwrap();
    assert_ne!(stored(outcome), gpu_file, "the CPU result is not the GPU's file");
    let (again, outcome) = preprocess_cached_on(&volume, &settings, Some(&ctx), &mut |_| {}).unwrap();
    assert_eq!(outcome, CacheOutcome::Hit(gpu_file));
    assert_eq!(again, gpu);
    assert_eq!(cpu.cluster_ids.len(), gpu.cluster_ids.len());
    let gpu_only = AoSettings { backend: Some(Backend::Gpu), ..settings };
    let e = preprocess_cached_on(&volume, &gpu_only, None, &mut |_| {}).unwrap_err().to_string();
    assert!(e.contains("ao.backend = \"gpu\"") && e.contains("Vulkan device"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
    assert_validation_clean(&ctx);
}

/// Timing of the GPU preprocessing, run by hand (docs/ao.md, "Measured"):
/// `AO_VOLUME=engine AO_RADIUS=8 AO_CLUSTERS=2048
/// cargo test --release --test suite ao_gpu::gpu_preprocessing_timing -- --ignored --nocapture`
/// (`AO_VOLUME=cornell`: the 64^3 Cornell box). `AO_PASSES=1` runs the sweep
/// a second time, with the trained codebook, for the GPU time of each pass.
#[test]
#[ignore = "a measurement of minutes, not a check"]
fn gpu_preprocessing_timing() {
    use std::time::Instant;
    use sweeplab::techniques::ao::gpu::assign_volume;
    use sweeplab::techniques::ao::{preprocess_on, AoSettings};
    let var = |name: &str| std::env::var(name).ok();
    let number = |name: &str, default: u32| var(name).and_then(|v| v.parse().ok()).unwrap_or(default);
    let volume = match var("AO_VOLUME").as_deref() {
        Some("engine") => {
            let path = sweeplab::scene::loaders::data_dir().join("engine.vti");
            sweeplab::scene::loaders::load_volume(&path).expect("engine.vti in the data folder")
        }
        _ => sweeplab::scene::synthetic::cornell_box(64),
    };
    let settings = AoSettings {
        radius: number("AO_RADIUS", 8),
        clusters: number("AO_CLUSTERS", 2048),
        cache: false,
        ..AoSettings::default()
    };
    let ctx = Context::new(&Default::default()).expect("a Vulkan device");
    let started = Instant::now();
    let mut last = String::new();
    let r = preprocess_on(&volume, &settings, Some(&ctx), &mut |p| {
        if p.step != last || p.fraction >= 1.0 {
            eprintln!("{}", p.line());
            last = p.step.to_string();
        }
    })
    .unwrap();
    let t = &r.stats.timings;
    let stencil =
        sweeplab::techniques::ao::histogram::SphereStencil::new(settings.radius, volume.spacing).voxel_count();
    eprintln!(
        "{} {} r = {} (N_r {stencil}) n_c = {} packed {}: total {:.1} s = packing {:.2} + TS histograms (CPU) {:.2} \
         + training {:.2} ({} Lloyd iterations) + GPU sweep and assignment {:.2}",
        volume.name,
        volume.dims,
        settings.radius,
        settings.clusters,
        settings.packed_dim,
        started.elapsed().as_secs_f64(),
        t.packing,
        t.training_histograms,
        t.training,
        r.stats.lloyd_iterations,
        t.assignment,
    );
    if var("AO_PASSES").is_some() {
        let h = LocalHistograms::new(&volume, settings.radius, settings.bits);
        let packing = packing_of(&h, settings.packed_dim as usize);
        let codebook = Codebook { dim: packing.packed_dim, words: r.packed_codebook.clone() };
        let started = Instant::now();
        let (again, passes) = assign_volume(&ctx, &h, &packing, &codebook, settings.metric, &mut |_| {}).unwrap();
        assert_eq!(again.cluster_ids, r.cluster_ids);
        eprintln!("second sweep {:.2} s; GPU ms per pass: {passes:?}", started.elapsed().as_secs_f64());
    }
}
