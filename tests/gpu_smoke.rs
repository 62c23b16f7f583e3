mod common;

use common::*;
use glam::Vec3;
use sweeplab::render::technique::total_bytes;
use sweeplab::render::{render, GpuScene, Technique};
use sweeplab::vk::Profiler;

#[test]
fn every_baseline_renders_validation_clean() {
    let ctx = validated_context();
    let scene = scene_with(sphere_volume(24, 9.0), vec![directional(Vec3::new(-1.0, -1.0, -0.5), 2.0)], 32, 32);
    let gpu = GpuScene::upload(&ctx, &scene).unwrap();
    let mut profiler = Profiler::new(&ctx, 256).unwrap();
    for t in Technique::ALL {
        let out = render(&gpu, t, 32, 32, &mut profiler).unwrap();
        assert!(out.image.all_finite());
        let centre = out.image.get(16, 16);
        let corner = out.image.get(0, 0);
        assert!(centre[0] > corner[0] + 0.05, "{t}: centre {centre:?} corner {corner:?}");
        println!(
            "{t}: dispatches {} barriers {} centre {centre:?}\n{}",
            out.dispatches,
            out.barriers,
            out.profile.table()
        );
    }
    drop(gpu);
    assert_validation_clean(&ctx);
}

/// The barrier between reference chunks is load-bearing: recorded without it,
/// synchronization validation must report the hazard.
#[test]
fn reference_without_chunk_barrier_is_reported_by_sync_validation() {
    use sweeplab::reference::gpu::{plan_for, render_with, ChunkSync};
    let ctx = validated_context();
    let mut scene = scene_with(sphere_volume(24, 9.0), vec![directional(Vec3::new(-1.0, -1.0, -0.5), 2.0)], 16, 16);
    // A fine shadow step forces several chunks.
    scene.reference.shadow_step_voxels = 0.05;
    scene.reference.step_voxels = 0.25;
    let gpu = GpuScene::upload(&ctx, &scene).unwrap();
    assert!(plan_for(&gpu).chunks >= 3, "{:?}", plan_for(&gpu));
    let mut profiler = Profiler::new(&ctx, 256).unwrap();
    profiler.reset();
    render_with(&gpu, 16, 16, &mut profiler, ChunkSync::Barrier).unwrap();
    assert_validation_clean(&ctx);
    profiler.reset();
    render_with(&gpu, 16, 16, &mut profiler, ChunkSync::RacyNoBarrier).unwrap();
    let messages = ctx.take_validation_messages();
    assert!(messages.iter().any(|m| m.contains("SYNC-HAZARD")), "racy chunks were not reported: {messages:?}");
}

/// Each technique lists what its frame allocates: the list accounts for the
/// device memory the frame held at its peak beyond the scene's own (volume,
/// LUT, lights), lit and unlit (the emission-only fallback). Drivers may pad a
/// resource: lavapipe pads a 1x1 R32F image (4 bytes) to 256, and nothing else
/// here, so on lavapipe each resource may be up to 252 bytes over its list entry.
#[test]
fn every_technique_lists_the_memory_its_frame_allocates() {
    let ctx = validated_context();
    let (width, height) = (24, 20);
    for lights in [vec![directional(Vec3::new(-1.0, -1.0, -0.5), 2.0)], vec![]] {
        let scene = scene_with(sphere_volume(24, 9.0), lights, width, height);
        let gpu = GpuScene::upload(&ctx, &scene).unwrap();
        let mut profiler = Profiler::new(&ctx, 256).unwrap();
        let scene_bytes = ctx.memory.device_local_bytes();
        for t in Technique::ALL {
            let needs = t.resources(&scene, width, height);
            let listed = total_bytes(&needs);
            let out = render(&gpu, t, width, height, &mut profiler).unwrap();
            let frame_bytes = out.profile.gpu_memory_bytes - scene_bytes;
            println!("{t} ({} lights): listed {listed}, frame {frame_bytes}: {needs:?}", scene.lights.len());
            assert!(listed <= frame_bytes, "{t}: lists {listed} bytes, the frame held {frame_bytes}");
            if ctx.info.name.contains("llvmpipe") {
                let padding = 252 * needs.len() as u64;
                assert!(frame_bytes <= listed + padding, "{t}: the frame held {frame_bytes}, {listed} listed");
            }
        }
        drop(gpu);
    }
    assert_validation_clean(&ctx);
}
