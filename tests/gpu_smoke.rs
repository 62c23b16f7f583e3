use crate::common;

use common::*;
use glam::Vec3;
use sweeplab::render::technique::total_bytes;
use sweeplab::render::{GpuScene, ResourceNeed};
use sweeplab::techniques::ao::AoSettings;
use sweeplab::techniques::half_angle::HalfAngleSettings;
use sweeplab::techniques::ipsvi::EarlyTermination;
use sweeplab::techniques::ipsvi::IpsviSettings;
use sweeplab::techniques::lightvolume::LightVolumeSettings;
use sweeplab::techniques::{render, Technique};
use sweeplab::vk::Profiler;

#[test]
fn every_baseline_renders_validation_clean() {
    let ctx = validated_context();
    let scene = scene_with(sphere_volume(24, 9.0), vec![directional(Vec3::new(-1.0, -1.0, -0.5), 2.0)], 32, 32);
    let gpu = GpuScene::upload(&ctx, &scene).unwrap();
    let mut profiler = Profiler::new(&ctx, 256).unwrap();
    for t in Technique::all() {
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
    use sweeplab::reference::gpu::{plan_for, render_with};
    use sweeplab::render::view_chunks::ChunkSync;
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

/// Bytes lavapipe allocates for a resource: images are stored in whole 4x4
/// texel blocks with rows padded to 64 bytes (llvmpipe's texture layout; it
/// accounts for every image here, from 1x1 R32F to 6x6x6 RGBA32F).
fn lavapipe_bytes(need: &ResourceNeed) -> u64 {
    match need.image {
        None => need.bytes,
        Some(([x, y, z], texel_bytes)) => {
            let row = (x.next_multiple_of(4) as u64 * texel_bytes as u64).next_multiple_of(64);
            row * y.next_multiple_of(4) as u64 * z as u64
        }
    }
}

/// Each technique lists what its frame allocates: the list accounts for the
/// device memory the frame held at its peak beyond the scene's own (volume,
/// LUT, lights), lit and unlit (the emission-only fallback), in several
/// configurations. Exactly on lavapipe; at least the contents elsewhere.
#[test]
fn every_technique_lists_the_memory_its_frame_allocates() {
    let ctx = validated_context();
    let (width, height) = (24, 20);
    let light = |x: f32| directional(Vec3::new(x, -1.0, -0.5), 1.0);
    let lit = scene_with(sphere_volume(24, 9.0), vec![light(-1.0)], width, height);
    let unlit = scene_with(sphere_volume(24, 9.0), vec![], width, height);
    // Other settings, other resources: the exit-point images, an uncompensated
    // volume at a quarter of the resolution, a smaller light buffer.
    let mut tuned = lit.clone();
    tuned.settings.get_mut::<IpsviSettings>().early_termination = EarlyTermination::ExitPoints;
    let lightvolume = tuned.settings.get_mut::<LightVolumeSettings>();
    (lightvolume.scale, lightvolume.compensated) = (4, false);
    tuned.settings.get_mut::<HalfAngleSettings>().light_buffer_size = 64;
    // Three lights: light volume passes of several members (half-angle takes one light).
    let three = scene_with(sphere_volume(24, 9.0), vec![light(-1.0), light(-0.8), light(1.0)], width, height);
    let all: Vec<Technique> = Technique::all().collect();
    let cases = [("lit", &lit, &all[..]), ("unlit", &unlit, &all[..]), ("tuned", &tuned, &all[..])];
    // The three lights' sweeps merged: per-sweep caches and colour accumulation.
    let mut merged = three.clone();
    merged.settings.get_mut::<IpsviSettings>().merge_sweeps = true;
    let cases = cases.into_iter().chain([
        ("three lights", &three, &[Technique::Ipsvi, Technique::LightVolume][..]),
        ("three lights merged", &merged, &[Technique::Ipsvi][..]),
    ]);
    for (what, scene, techniques) in cases {
        let gpu = GpuScene::upload(&ctx, scene).unwrap();
        let mut profiler = Profiler::new(&ctx, 256).unwrap();
        let scene_bytes = ctx.memory.device_local_bytes();
        for &t in techniques {
            let needs = t.resources(scene, width, height);
            let listed = total_bytes(&needs);
            let out = render(&gpu, t, width, height, &mut profiler).unwrap();
            let frame_bytes = out.profile.gpu_memory_bytes - scene_bytes;
            println!("{t} ({what}): listed {listed}, frame {frame_bytes}: {needs:?}");
            assert!(listed <= frame_bytes, "{t} ({what}): lists {listed} bytes, the frame held {frame_bytes}");
            if ctx.info.name.contains("llvmpipe") {
                let padded: u64 = needs.iter().map(lavapipe_bytes).sum();
                assert_eq!(frame_bytes, padded, "{t} ({what}): the frame held {frame_bytes}, {padded} listed (padded)");
            }
        }
        drop(gpu);
    }
    assert_validation_clean(&ctx);
}

/// Technique `ao` lists what its frame allocates in every mode (the glow
/// block only in glow mode), lit and unlit, against the device memory the
/// frame held (exactly on lavapipe), validation-clean.
#[test]
fn ao_lists_the_memory_its_frame_allocates_in_every_mode() {
    use sweeplab::techniques::ao::AoMode;
    let ctx = validated_context();
    let (width, height) = (24, 20);
    let lit = scene_with(sphere_volume(24, 9.0), vec![directional(Vec3::new(-1.0, -1.0, -0.5), 1.0)], width, height);
    let unlit = scene_with(sphere_volume(24, 9.0), vec![], width, height);
    let mut listed_by_mode = Vec::new();
    for (what, base) in [("lit", &lit), ("unlit", &unlit)] {
        for mode in AoMode::ALL {
            let mut scene = base.clone();
            let ao = scene.settings.get_mut::<AoSettings>();
            (ao.radius, ao.clusters, ao.packed_dim, ao.cache, ao.mode) = (3, 8, 16, false, mode);
            let gpu = GpuScene::upload(&ctx, &scene).unwrap();
            let mut profiler = Profiler::new(&ctx, 256).unwrap();
            let scene_bytes = ctx.memory.device_local_bytes();
            let needs = Technique::Ao.resources(&scene, width, height);
            let listed = total_bytes(&needs);
            let out = render(&gpu, Technique::Ao, width, height, &mut profiler).unwrap();
            let frame_bytes = out.profile.gpu_memory_bytes - scene_bytes;
            println!("ao {} ({what}): listed {listed}, frame {frame_bytes}: {needs:?}", mode.name());
            assert!(listed <= frame_bytes, "ao {} ({what}): lists {listed}, the frame held {frame_bytes}", mode.name());
            if ctx.info.name.contains("llvmpipe") {
                let padded: u64 = needs.iter().map(lavapipe_bytes).sum();
                assert_eq!(frame_bytes, padded, "ao {} ({what}): held {frame_bytes}, {padded} listed", mode.name());
            }
            listed_by_mode.push((mode, listed));
            drop(gpu);
        }
    }
    let bytes = |m: AoMode| listed_by_mode.iter().find(|(n, _)| *n == m).unwrap().1;
    assert_eq!(bytes(AoMode::Glow), bytes(AoMode::Dvr) + 8 * 16, "the glow block: one vec4 per cluster");
    assert_eq!(bytes(AoMode::Phase), bytes(AoMode::Dvr), "both hemispheres read the same lookup");
    assert_validation_clean(&ctx);
}
