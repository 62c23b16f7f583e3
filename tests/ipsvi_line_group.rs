//! The workgroup size of the line dispatches (a specialization constant chosen
//! per renderer, src/techniques/ipsvi/line_group.rs) changes how pixels are grouped, never
//! the image: every invocation shades its own pixel or texel.
use crate::common;

use common::*;
use glam::Vec3;
use sweeplab::render::GpuScene;
use sweeplab::scene::synthetic::slab_under_sphere;
use sweeplab::scene::{presets, Falloff, Light, LightKind};
use sweeplab::techniques::ipsvi::renderer::IpsviRenderer;
use sweeplab::techniques::ipsvi::{CacheUpdate, CacheWrite, IpsviSettings, SyncStrategy};
use sweeplab::vk::Profiler;

#[test]
fn every_workgroup_size_gives_the_same_image_validation_clean() {
    let point = Light {
        kind: LightKind::Point { position: Vec3::new(0.1, 0.3, 0.2) },
        color: Vec3::ONE,
        intensity: 1.5,
        falloff: Falloff::None,
    };
    let (w, h) = (40, 32);
    let mut scene = scene_with(slab_under_sphere(24), vec![directional(Vec3::new(0.3, -1.0, 0.2), 2.0), point], w, h);
    scene.transfer = presets::preset("slab-sphere").unwrap();
    let ctx = validated_context();
    let gpu = GpuScene::upload(&ctx, &scene).unwrap();
    let mut profiler = Profiler::new(&ctx, 1024).unwrap();
    for (cache_update, cache_write) in [
        (CacheUpdate::ViewSamples, CacheWrite::Farthest),
        (CacheUpdate::ViewSamples, CacheWrite::Nearest),
        (CacheUpdate::LightRays, CacheWrite::Farthest),
    ] {
        let s = IpsviSettings { cache_size: 32, line_width: 2, cache_update, cache_write, ..IpsviSettings::default() };
        let mut frame = |group: Option<u32>| {
            let mut renderer = IpsviRenderer::with_line_group(&gpu, &s, w, h, group).unwrap();
            if let Some(g) = group {
                assert_eq!(renderer.line_group(), g);
            }
            profiler.reset();
            renderer.frame(&mut profiler, SyncStrategy::BarrierGlobal).unwrap().image
        };
        let widest = frame(Some(64));
        for group in [None, Some(8), Some(16), Some(32)] {
            assert!(frame(group) == widest, "{cache_update:?} {cache_write:?}: group {group:?} differs from 64");
        }
        assert_validation_clean(&ctx);
    }
    assert!(IpsviRenderer::with_line_group(&gpu, &IpsviSettings::default(), w, h, Some(48)).is_err());
}
