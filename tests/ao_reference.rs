//! The ambient-occlusion ground truth: on the GPU, chunked
//! across dispatches, equal to the CPU computation; its chunk barrier
//! load-bearing; and the clustered image approaching the image of the
//! unclustered histograms as n_c grows.

use crate::common;

use common::*;
use sweeplab::metrics::compare;
use sweeplab::render::view_chunks::ChunkSync;
use sweeplab::render::{GpuScene, VolumeTexels};
use sweeplab::scene::{Scene, TransferLut};
use sweeplab::techniques::ao::ground_truth::gpu::reference_gpu;
use sweeplab::techniques::ao::ground_truth::unclustered::unclustered_lookup;
use sweeplab::techniques::ao::ground_truth::{reference_cpu, AoReferenceParams};
use sweeplab::techniques::ao::render::AoRenderer;
use sweeplab::techniques::ao::AoSettings;
use sweeplab::techniques::{render, Technique};
use sweeplab::vk::Profiler;

fn cornell(n: u32, radius: u32, size: u32) -> Scene {
    cornell_box_scene(n, size, &format!("radius = {radius}\ncache = false\npacked_dim = 32"))
}

#[test]
fn the_gpu_ground_truth_equals_the_cpu_one_across_dispatches() {
    let ctx = validated_context();
    let scene = cornell(12, 3, 16);
    let params = AoReferenceParams { radius: 3, pairs: 8, step: 0.5 };
    // Float32: exact trilinear filtering, as the CPU's.
    let gpu = GpuScene::upload_with(&ctx, &scene, VolumeTexels::Float32).unwrap();
    let mut profiler = Profiler::new(&ctx, 64).unwrap();
    profiler.reset();
    // Three directions per dispatch: three dispatches adding to the sums.
    let on_gpu = reference_gpu(&gpu, &params, Some(3), &mut profiler, ChunkSync::Barrier).unwrap();
    let lut = scene.transfer.bake(TransferLut::DEFAULT_SIZE);
    let on_cpu = reference_cpu(&scene.volume, &lut, &params);
    assert_eq!(on_gpu.len(), 2 * scene.volume.voxel_count());
    let d =
        on_gpu.iter().zip(&on_cpu).flat_map(|(a, b)| a.iter().zip(b).map(|(x, y)| (x - y).abs())).fold(0.0, f32::max);
    println!("GPU against CPU ground truth: max difference {d:.2e}");
    assert!(d < 1e-4, "GPU ground truth differs from the CPU's by {d}");
    // Inside the back wall's corner occlusion is nearly complete; in the
    // middle of the room, empty.
    let index = |x: usize, y: usize, z: usize| x + 12 * (y + 12 * z);
    let corner = on_cpu[2 * index(0, 0, 0)][3].max(on_cpu[2 * index(0, 0, 0) + 1][3]);
    let middle = on_cpu[2 * index(6, 6, 6)][3];
    assert!(corner > 0.4 && middle < 0.05, "corner {corner}, middle {middle}");
    drop(gpu);
    assert_validation_clean(&ctx);
}

/// The barrier between the ground truth's dispatches is load-bearing: without
/// it, synchronization validation reports the hazard on the sums.
#[test]
fn the_ground_truth_without_its_chunk_barrier_is_reported() {
    let ctx = validated_context();
    let scene = cornell(8, 2, 8);
    let params = AoReferenceParams { radius: 2, pairs: 4, step: 0.5 };
    let gpu = GpuScene::upload(&ctx, &scene).unwrap();
    let mut profiler = Profiler::new(&ctx, 64).unwrap();
    profiler.reset();
    reference_gpu(&gpu, &params, Some(1), &mut profiler, ChunkSync::Barrier).unwrap();
    assert_validation_clean(&ctx);
    profiler.reset();
    reference_gpu(&gpu, &params, Some(1), &mut profiler, ChunkSync::RacyNoBarrier).unwrap();
    let messages = ctx.take_validation_messages();
    assert!(
        messages.iter().any(|m| m.contains("SYNC-HAZARD") && m.contains("ao reference sums")),
        "racy ground-truth dispatches were not reported: {messages:?}"
    );
}

#[test]
fn the_clustered_image_approaches_the_unclustered_one_as_n_c_grows() {
    let ctx = validated_context();
    let size = 48;
    let mut scene = cornell(16, 4, size);
    let lut = scene.transfer.bake(TransferLut::DEFAULT_SIZE);
    let mut profiler = Profiler::new(&ctx, 64).unwrap();
    let per_voxel = |scene: &Scene, lookup: &[[f32; 4]], profiler: &mut Profiler| {
        let gpu = GpuScene::upload(&ctx, scene).unwrap();
        let renderer = AoRenderer::per_voxel(&gpu, lookup, &scene.settings.get::<AoSettings>()).unwrap();
        renderer.frame(&gpu, (size, size), profiler).unwrap().image
    };
    let unclustered =
        per_voxel(&scene, &unclustered_lookup(&scene.volume, &scene.settings.get::<AoSettings>(), &lut), &mut profiler);
    let params = AoReferenceParams { radius: 4, pairs: 32, step: 0.5 };
    let truth = per_voxel(&scene, &reference_cpu(&scene.volume, &lut, &params), &mut profiler);
    let mut errors = Vec::new();
    for clusters in [2, 8, 32, 128] {
        scene.settings.get_mut::<AoSettings>().clusters = clusters;
        let gpu = GpuScene::upload(&ctx, &scene).unwrap();
        let image = render(&gpu, Technique::Ao, size, size, &mut profiler).unwrap().image;
        let error = compare(&image, &unclustered).unwrap();
        let against_truth = compare(&image, &truth).unwrap();
        println!(
            "n_c = {clusters:4}: rmse against unclustered {:.4e} ({:.2} % of peak), against the ground truth {:.4e}",
            error.rmse,
            100.0 * error.rmse / unclustered.max_value() as f64,
            against_truth.rmse
        );
        errors.push(error.rmse);
    }
    println!("unclustered against the ground truth: rmse {:.4e}", compare(&unclustered, &truth).unwrap().rmse);
    for (i, e) in errors.windows(2).enumerate() {
        assert!(e[1] < e[0] * 1.05, "the error grew from step {i} to {}: {errors:?}", i + 1);
    }
    assert!(errors[3] < 0.5 * errors[0], "n_c = 128 is not closer to the unclustered image: {errors:?}");
    assert_validation_clean(&ctx);
}
