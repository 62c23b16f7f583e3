//! Every synchronization strategy of the IPSVI sweep gives the image of
//! `barrier-global` bit for bit, with either line kernel, and is clean under
//! synchronization validation;
//! `racy` is reported by it.
use crate::common;

use common::*;
use glam::Vec3;
use sweeplab::render::GpuScene;
use sweeplab::scene::synthetic::slab_under_sphere;
use sweeplab::scene::{presets, Falloff, Light, LightKind};
use sweeplab::techniques::ipsvi::{render_with, IpsviSettings, LineKernel, SyncStrategy};
use sweeplab::vk::Profiler;

#[test]
fn every_strategy_gives_the_same_image_and_racy_is_reported() {
    let point = Light {
        kind: LightKind::Point { position: Vec3::new(0.1, 0.3, 0.2) },
        color: Vec3::ONE,
        intensity: 1.5,
        falloff: Falloff::None,
    };
    for lights in [vec![directional(Vec3::new(0.3, -1.0, 0.2), 2.0)], vec![point]] {
        let mut scene = scene_with(slab_under_sphere(24), lights, 24, 24);
        scene.transfer = presets::preset("slab-sphere").unwrap();
        let ctx = validated_context();
        let gpu = GpuScene::upload(&ctx, &scene).unwrap();
        let mut profiler = Profiler::new(&ctx, 256).unwrap();
        // Both line kernels: the strategies record the same dispatches around either.
        let kernels = [(LineKernel::Serial, 0), (LineKernel::Segmented, 4)];
        for (line_width, (line_kernel, segments)) in [1, 3].into_iter().flat_map(|w| kernels.map(|k| (w, k))) {
            let s = IpsviSettings { cache_size: 32, line_width, line_kernel, segments, ..IpsviSettings::default() };
            profiler.reset();
            let expected = render_with(&gpu, &s, 24, 24, &mut profiler, SyncStrategy::BarrierGlobal).unwrap();
            let kernel = expected.shape.as_ref().map(|shape| shape.kernel.as_str());
            assert_eq!(kernel, Some(if segments == 0 { "serial" } else { "segmented x4" }));
            assert_validation_clean(&ctx);
            for strategy in
                [SyncStrategy::BarrierImage, SyncStrategy::Events, SyncStrategy::Submits, SyncStrategy::Secondary]
            {
                profiler.reset();
                let frame = render_with(&gpu, &s, 24, 24, &mut profiler, strategy).unwrap();
                assert_eq!(
                    frame.image, expected.image,
                    "{strategy} differs from barrier-global (line width {line_width}, {line_kernel:?})"
                );
                assert_eq!(frame.dispatches, expected.dispatches);
                let messages = ctx.take_validation_messages();
                assert!(messages.is_empty(), "{strategy}: {messages:?}");
            }
            profiler.reset();
            render_with(&gpu, &s, 24, 24, &mut profiler, SyncStrategy::Racy).unwrap();
            let messages = ctx.take_validation_messages();
            assert!(
                messages.iter().any(|m| m.contains("SYNC-HAZARD")),
                "racy sweep not reported (line width {line_width}, {line_kernel:?})"
            );
        }
    }
}

#[test]
fn strategy_names_round_trip_and_racy_is_labelled() {
    for s in SyncStrategy::ALL {
        assert_eq!(s.name().parse::<SyncStrategy>().unwrap(), s);
        assert_eq!(s.to_string().contains("RACY"), s.is_racy());
    }
    assert!("barrier".parse::<SyncStrategy>().is_err());
}

/// The secondary strategy records each sweep once and replays it: frames of one
/// renderer stay equal to each other and to barrier-global, validation-clean.
#[test]
fn secondary_sweeps_are_replayed_across_frames() {
    use sweeplab::techniques::ipsvi::renderer::IpsviRenderer;
    let mut scene = scene_with(slab_under_sphere(24), vec![directional(Vec3::new(0.3, -1.0, 0.2), 2.0)], 24, 24);
    scene.transfer = presets::preset("slab-sphere").unwrap();
    let ctx = validated_context();
    let gpu = GpuScene::upload(&ctx, &scene).unwrap();
    let mut profiler = Profiler::new(&ctx, 256).unwrap();
    let s = IpsviSettings { cache_size: 32, line_width: 2, ..IpsviSettings::default() };
    let mut renderer = IpsviRenderer::new(&gpu, &s, 24, 24).unwrap();
    profiler.reset();
    let expected = renderer.frame(&mut profiler, SyncStrategy::BarrierGlobal).unwrap();
    for _ in 0..3 {
        profiler.reset();
        let frame = renderer.frame(&mut profiler, SyncStrategy::Secondary).unwrap();
        assert_eq!(frame.image, expected.image);
        assert_eq!(frame.dispatches, expected.dispatches, "replayed dispatches are counted");
    }
    assert_validation_clean(&ctx);
}

/// Each strategy adds what it says between blocks: one barrier per block for
/// the barriers, one wait per block for the events (the last wait before the
/// read-back), the global barriers inside the replayed sweeps for secondary,
/// and none for submits (a semaphore orders them) and racy.
#[test]
fn each_strategy_records_its_own_synchronization_per_block() {
    use sweeplab::techniques::ipsvi::renderer::{plans, IpsviRenderer};
    let mut scene = scene_with(slab_under_sphere(24), vec![directional(Vec3::new(0.3, -1.0, 0.2), 2.0)], 24, 24);
    scene.transfer = presets::preset("slab-sphere").unwrap();
    let ctx = validated_context();
    let gpu = GpuScene::upload(&ctx, &scene).unwrap();
    let mut profiler = Profiler::new(&ctx, 256).unwrap();
    use sweeplab::techniques::ipsvi::CacheUpdate;
    for cache_update in [CacheUpdate::LightRays, CacheUpdate::ViewSamples] {
        let s = IpsviSettings { cache_size: 32, line_width: 2, cache_update, ..IpsviSettings::default() };
        let sweeps = plans(&gpu, &s, 24, 24).iter().map(|p| p.sweeps.len() as u32).sum::<u32>();
        let blocks: u32 = plans(&gpu, &s, 24, 24).iter().flat_map(|p| &p.sweeps).map(|sw| sw.blocks.len() as u32).sum();
        assert!(blocks > 2, "a sweep of several blocks: {blocks}");
        // View samples with farthest writes (the default) claim for a sweep's first
        // block in a dispatch of its own, synchronized like a block.
        let dispatches = if cache_update == CacheUpdate::ViewSamples { blocks + sweeps } else { blocks };
        let mut renderer = IpsviRenderer::new(&gpu, &s, 24, 24).unwrap();
        let mut barriers = |strategy| {
            profiler.reset();
            renderer.frame(&mut profiler, strategy).unwrap().barriers
        };
        let unsynchronized = barriers(SyncStrategy::Racy);
        let _ = ctx.take_validation_messages(); // the racy frame's hazards
        for (strategy, per_block) in [
            (SyncStrategy::BarrierGlobal, 1),
            (SyncStrategy::BarrierImage, 1),
            (SyncStrategy::Events, 1),
            (SyncStrategy::Secondary, 1),
            (SyncStrategy::Submits, 0),
        ] {
            assert_eq!(barriers(strategy), unsynchronized + per_block * dispatches, "{strategy} {cache_update:?}");
        }
    }
    assert_validation_clean(&ctx);
}
