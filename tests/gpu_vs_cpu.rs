//! The GPU renderers against the CPU f64 renderers on the same discretization
//! (docs/optical-model.md): differences are float rounding only, so the
//! tolerances are tight. All runs with validation and synchronization validation.
mod common;

use common::*;
use glam::Vec3;
use sweeplab::metrics::compare;
use sweeplab::reference::cpu::{render_cpu, CpuRenderKind};
use sweeplab::reference::gpu::plan_for;
use sweeplab::render::{GpuScene, VolumeTexels};
use sweeplab::scene::synthetic::{noise, slab_under_sphere, three_spheres};
use sweeplab::scene::{Falloff, Light, LightKind, OpticalModel, Scene};
use sweeplab::techniques::{render, Technique};
use sweeplab::vk::Profiler;

fn gpu_and_cpu(
    scene: &Scene,
    technique: Technique,
    kind: CpuRenderKind,
) -> (sweeplab::linear_image::LinearImage, sweeplab::linear_image::LinearImage) {
    let ctx = validated_context();
    let (w, h) = (scene.render.width, scene.render.height);
    let gpu_image = {
        let gpu = GpuScene::upload_with(&ctx, scene, VolumeTexels::Float32).unwrap();
        let mut profiler = Profiler::new(&ctx, 4096).unwrap();
        render(&gpu, technique, w, h, &mut profiler).unwrap().image
    };
    assert_validation_clean(&ctx);
    let cpu_image = render_cpu(scene, kind, w, h).unwrap();
    (gpu_image, cpu_image)
}

/// Smooth volumes: with hard edges, f32 and f64 sample positions may fall on
/// either side of a discontinuity and a pixel legitimately flips.
fn spheres_scene(n: u32, size: u32) -> Scene {
    let mut scene = scene_with(three_spheres(n), vec![directional(Vec3::new(-1.0, -1.0, -0.5), 2.0)], size, size);
    scene.transfer = sweeplab::scene::presets::preset("spheres").unwrap();
    scene
}

fn noise_scene(n: u32, size: u32) -> Scene {
    let mut scene = scene_with(noise(n, 7), vec![directional(Vec3::new(-1.0, -1.0, -0.5), 2.0)], size, size);
    scene.transfer = sweeplab::scene::presets::preset("grayscale-ramp").unwrap();
    scene
}

/// Relative to the brightest reference value: float rounding of a few hundred
/// compositing steps and hardware texture filtering, nothing else.
const TIGHT: f64 = 2e-3;

#[test]
fn gpu_dvr_matches_cpu_f64_dvr_at_64x64() {
    for scene in [spheres_scene(48, 64), noise_scene(32, 64)] {
        let (gpu, cpu) = gpu_and_cpu(&scene, Technique::Dvr, CpuRenderKind::Dvr);
        let stats = compare(&gpu, &cpu).unwrap();
        let peak = cpu.max_value() as f64;
        assert!(peak > 0.1, "the test image must show something ({peak})");
        assert!(
            stats.max_abs <= TIGHT * peak && stats.rmse <= 1e-4 * peak,
            "{}: {stats:?} peak {peak}",
            scene.volume.name
        );
    }
}

#[test]
fn gpu_phong_matches_cpu_f64_phong() {
    let scene = spheres_scene(48, 48);
    let (gpu, cpu) = gpu_and_cpu(&scene, Technique::Phong, CpuRenderKind::Phong);
    let stats = compare(&gpu, &cpu).unwrap();
    let peak = cpu.max_value() as f64;
    assert!(stats.max_abs <= 5.0 * TIGHT * peak && stats.rmse <= 2e-4 * peak.max(1.0), "{stats:?} peak {peak}");
}

#[test]
fn gpu_reference_matches_cpu_reference_for_every_light_type_and_both_models() {
    for model in [OpticalModel::SingleScattering, OpticalModel::EmissiveScattering] {
        let mut scene = scene_with(slab_under_sphere(24), vec![], 24, 24);
        scene.transfer = sweeplab::scene::presets::preset("slab-sphere").unwrap();
        scene.reference.model = model;
        scene.render.emission = 0.3;
        scene.lights = vec![
            directional(Vec3::new(0.2, -1.0, 0.1), 1.5),
            Light {
                kind: LightKind::Point { position: Vec3::new(0.1, 0.2, 0.05) },
                color: Vec3::new(1.0, 0.6, 0.3),
                intensity: 0.8,
                falloff: Falloff::InverseSquare,
            },
            Light {
                kind: LightKind::Spot {
                    position: Vec3::new(0.9, 0.9, 0.9),
                    direction: Vec3::new(-1.0, -1.0, -1.0),
                    inner_cone_deg: 10.0,
                    outer_cone_deg: 25.0,
                },
                color: Vec3::new(0.3, 0.5, 1.0),
                intensity: 2.0,
                falloff: Falloff::None,
            },
        ];
        let (gpu, cpu) = gpu_and_cpu(&scene, Technique::Reference, CpuRenderKind::Reference(model));
        let stats = compare(&gpu, &cpu).unwrap();
        let peak = cpu.max_value() as f64;
        assert!(peak > 0.05, "{model:?}: empty image");
        assert!(stats.max_abs <= TIGHT * peak && stats.rmse <= 2e-4 * peak, "{model:?}: {stats:?} peak {peak}");
    }
}

/// The chromatic variant of model (i) (coloured extinction along shadow rays)
/// on the GPU against the CPU: the same tight tolerance; it differs from the
/// grey model (i) by far more (the check can tell them apart), and model (ii)
/// with it is refused on both.
#[test]
fn gpu_chromatic_reference_matches_cpu_chromatic_reference() {
    let mut scene = spheres_scene(32, 32);
    scene.lights.push(Light {
        kind: LightKind::Point { position: Vec3::new(0.05, 0.1, 0.0) },
        color: Vec3::new(1.0, 0.8, 0.6),
        intensity: 0.5,
        falloff: Falloff::None,
    });
    scene.reference.chromatic = true;
    let kind = CpuRenderKind::Reference(OpticalModel::SingleScattering);
    let (gpu, cpu) = gpu_and_cpu(&scene, Technique::Reference, kind);
    let stats = compare(&gpu, &cpu).unwrap();
    let peak = cpu.max_value() as f64;
    assert!(peak > 0.05, "empty image");
    assert!(stats.max_abs <= TIGHT * peak && stats.rmse <= 2e-4 * peak, "{stats:?} peak {peak}");
    scene.reference.chromatic = false;
    let grey = render_cpu(&scene, kind, 32, 32).unwrap();
    let apart = compare(&grey, &cpu).unwrap();
    println!("chromatic against grey model (i): max_abs {:.3e} (GPU against CPU {:.3e})", apart.max_abs, stats.max_abs);
    assert!(apart.max_abs > 20.0 * TIGHT * peak, "chromatic and grey model (i) barely differ: {apart:?}");
    scene.reference.chromatic = true;
    scene.reference.model = OpticalModel::EmissiveScattering;
    assert!(render_cpu(&scene, CpuRenderKind::Reference(OpticalModel::EmissiveScattering), 8, 8).is_err());
    let ctx = validated_context();
    let gpu = GpuScene::upload(&ctx, &scene).unwrap();
    let mut profiler = Profiler::new(&ctx, 64).unwrap();
    assert!(render(&gpu, Technique::Reference, 8, 8, &mut profiler).is_err());
}

/// A scene whose brute-force shadow rays would take one invocation past
/// llvmpipe's 65,535 loop iterations: the chunked GPU reference must still agree.
#[test]
fn gpu_reference_agrees_where_one_invocation_would_pass_the_loop_cap() {
    let mut scene = scene_with(slab_under_sphere(40), vec![directional(Vec3::new(0.3, -1.0, 0.2), 1.5)], 12, 12);
    scene.transfer = sweeplab::scene::presets::preset("slab-sphere").unwrap();
    scene.reference.step_voxels = 0.25;
    scene.reference.shadow_step_voxels = 0.25;
    scene.reference.min_transmittance = 0.0;
    let ctx = validated_context();
    let gpu = GpuScene::upload(&ctx, &scene).unwrap();
    let plan = plan_for(&gpu);
    let unsplit = plan.max_view_samples * (1 + plan.max_shadow_samples);
    assert!(unsplit > 65_535, "scene too small to exercise the cap: {unsplit} iterations");
    assert!(plan.chunks > 1 && plan.iterations_per_dispatch(1) < 65_535, "{plan:?}");
    drop(gpu);
    drop(ctx);
    let (gpu, cpu) =
        gpu_and_cpu(&scene, Technique::Reference, CpuRenderKind::Reference(OpticalModel::SingleScattering));
    let stats = compare(&gpu, &cpu).unwrap();
    let peak = cpu.max_value() as f64;
    assert!(stats.max_abs <= TIGHT * peak, "{stats:?} peak {peak}");
}
