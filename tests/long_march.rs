//! View marches longer than llvmpipe's 65,535 loop iterations per
//! invocation. DVR, Phong and the light volume's ray cast split them across
//! dispatches, so a tiny `render.step` converges instead of going black; a step
//! whose rays would outgrow f32 sample indices is refused by name.
use crate::common;

use common::*;
use glam::Vec3;
use sweeplab::linear_image::LinearImage;
use sweeplab::metrics::compare;
use sweeplab::reference::cpu::{render_cpu, CpuRenderKind};
use sweeplab::render::view_chunks::{diagonal_voxels, smallest_view_step, ViewChunks};
use sweeplab::render::{GpuScene, RenderError, VolumeTexels};
use sweeplab::scene::synthetic::noise;
use sweeplab::scene::Scene;
use sweeplab::techniques::half_angle::HalfAngleSettings;
use sweeplab::techniques::{render, Technique};
use sweeplab::vk::Profiler;

/// 16^3 voxels: the diagonal is 27.7 voxels, so this step takes about 139,000
/// samples along the longest ray, twice past the cap.
const PAST_THE_CAP: f32 = 2e-4;

fn noise_scene(size: u32) -> Scene {
    let mut scene = scene_with(noise(16, 7), vec![directional(Vec3::new(-1.0, -1.0, -0.5), 2.0)], size, size);
    scene.transfer = sweeplab::scene::presets::preset("grayscale-ramp").unwrap();
    scene
}

fn gpu_render(scene: &Scene, technique: Technique) -> Result<LinearImage, RenderError> {
    let ctx = validated_context();
    let image = {
        let gpu = GpuScene::upload_with(&ctx, scene, VolumeTexels::Float32).unwrap();
        let mut profiler = Profiler::new(&ctx, 4096).unwrap();
        render(&gpu, technique, scene.render.width, scene.render.height, &mut profiler).map(|o| o.image)
    };
    assert_validation_clean(&ctx);
    image
}

#[test]
fn the_plan_splits_past_the_cap_and_not_before() {
    let scene = noise_scene(8);
    let d = diagonal_voxels(&scene);
    assert_eq!(ViewChunks::new(d, 0.5, 1).chunks, 1, "an ordinary step is one dispatch");
    let plan = ViewChunks::new(d, PAST_THE_CAP as f64, 1);
    assert!(plan.chunks >= 3 && plan.samples_per_chunk < 65_535, "{plan:?}");
    assert!(plan.chunks * plan.samples_per_chunk >= plan.max_view_samples);
}

#[test]
fn dvr_and_phong_past_the_loop_cap_match_the_cpu_march() {
    let mut scene = noise_scene(8);
    scene.render.step_voxels = PAST_THE_CAP;
    for (technique, kind) in [(Technique::Dvr, CpuRenderKind::Dvr), (Technique::Phong, CpuRenderKind::Phong)] {
        let gpu = gpu_render(&scene, technique).unwrap();
        let cpu = render_cpu(&scene, kind, 8, 8).unwrap();
        let stats = compare(&gpu, &cpu).unwrap();
        let peak = cpu.max_value() as f64;
        assert!(peak > 0.1, "the test image must show something ({peak})");
        println!("{technique} at step {PAST_THE_CAP}: {stats:?} peak {peak}");
        // f32 against f64 over 139,000 compositing steps: rounding of the
        // per-step opacity, not a truncated march (which loses half the ray).
        assert!(stats.max_abs <= 0.02 * peak, "{technique}: {stats:?} peak {peak}");
    }
}

#[test]
fn the_light_volume_past_the_loop_cap_converges_to_its_ordinary_step() {
    let mut scene = noise_scene(8);
    let coarse = gpu_render(&scene, Technique::LightVolume).unwrap();
    scene.render.step_voxels = PAST_THE_CAP;
    let fine = gpu_render(&scene, Technique::LightVolume).unwrap();
    let stats = compare(&fine, &coarse).unwrap();
    println!("lightvolume step {PAST_THE_CAP} against 0.5: {stats:?}");
    assert!(stats.psnr > 30.0, "{stats:?}");
}

#[test]
fn a_step_past_f32_sample_indices_is_refused_by_name() {
    let mut scene = noise_scene(8);
    let smallest = smallest_view_step(&scene);
    scene.render.step_voxels = (smallest * 0.5) as f32;
    for technique in [Technique::Dvr, Technique::Phong, Technique::LightVolume] {
        let e = gpu_render(&scene, technique).expect_err("refused").to_string();
        assert!(e.contains("render.step") && e.contains(technique.name()) && e.contains("smallest step"), "{e}");
    }
}

#[test]
fn ipsvi_and_half_angle_refuse_a_step_they_cannot_march_before_any_gpu_work() {
    let mut scene = noise_scene(8);
    for step in [1e-4f32, 1e6] {
        scene.render.step_voxels = step;
        let e = Technique::HalfAngle.check(&scene).expect_err("half-angle refuses").to_string();
        assert!(e.contains("render.step") && e.contains("half-angle") && e.contains("smallest step"), "{e}");
    }
    scene.settings.get_mut::<HalfAngleSettings>().slice_step = Some(0.5);
    assert!(Technique::HalfAngle.check(&scene).is_ok(), "its own slice_step decides");
    scene.render.step_voxels = 1e-4;
    let e = Technique::Ipsvi.check(&scene).expect_err("ipsvi refuses").to_string();
    assert!(e.contains("render.step") && e.contains("ipsvi") && e.contains("smallest step"), "{e}");
    scene.render.step_voxels = 0.5;
    for t in Technique::all() {
        assert!(t.check(&scene).is_ok(), "{t} takes an ordinary step");
    }
}

/// The barrier between view chunks is load-bearing: the chunks ping-pong
/// between the output and a state image, so recorded without it,
/// synchronization validation reports the hazard (with it, clean).
#[test]
fn view_chunks_without_their_barrier_are_reported_by_sync_validation() {
    use sweeplab::render::raycast::{render_with, Shading};
    use sweeplab::render::view_chunks::ChunkSync;
    let mut scene = noise_scene(8);
    scene.render.step_voxels = PAST_THE_CAP;
    let ctx = validated_context();
    let gpu = GpuScene::upload_with(&ctx, &scene, VolumeTexels::Float32).unwrap();
    let mut profiler = Profiler::new(&ctx, 256).unwrap();
    profiler.reset();
    let frame = render_with(&gpu, Shading::Unshaded, (8, 8), &mut profiler, ChunkSync::Barrier).unwrap();
    assert!(frame.dispatches >= 3, "several chunks: {} dispatches", frame.dispatches);
    assert_validation_clean(&ctx);
    profiler.reset();
    render_with(&gpu, Shading::Unshaded, (8, 8), &mut profiler, ChunkSync::RacyNoBarrier).unwrap();
    let messages = ctx.take_validation_messages();
    assert!(
        messages.iter().any(|m| m.contains("SYNC-HAZARD") && m.contains("view chunk state")),
        "racy view chunks were not reported: {messages:?}"
    );
}
