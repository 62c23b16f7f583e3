//! Profiler sanity: scopes nest, children sum to at most their parent, misuse
//! fails loudly, detail scopes appear only on request.
use crate::common;

use common::*;
use glam::Vec3;
use sweeplab::render::GpuScene;
use sweeplab::techniques::{render, Technique};
use sweeplab::vk::commands::submit_and_wait;
use sweeplab::vk::Profiler;

fn chunked_scene() -> sweeplab::scene::Scene {
    let mut scene = scene_with(sphere_volume(24, 9.0), vec![directional(Vec3::new(-1.0, -1.0, -0.5), 2.0)], 16, 16);
    scene.reference.shadow_step_voxels = 0.05;
    scene.reference.step_voxels = 0.25;
    scene
}

#[test]
fn detail_scopes_nest_and_sum_to_at_most_the_parent() {
    let ctx = validated_context();
    let scene = chunked_scene();
    let gpu = GpuScene::upload(&ctx, &scene).unwrap();
    let mut profiler = Profiler::new(&ctx, 1024).unwrap();
    assert!(profiler.timestamps_supported(), "lavapipe supports timestamps");
    profiler.set_detail(true);
    let out = render(&gpu, Technique::Reference, 16, 16, &mut profiler).unwrap();
    let scopes = &out.profile.scopes;
    let parent = scopes.iter().position(|s| s.name == "reference").expect("reference scope");
    let children: Vec<_> = scopes.iter().filter(|s| s.parent == Some(parent)).collect();
    assert_eq!(children.len() as u32, out.dispatches, "one detail scope per chunk dispatch");
    assert!(children.iter().all(|c| c.depth == scopes[parent].depth + 1 && c.path == "reference/reference_chunk"));
    let sum: f64 = children.iter().map(|c| c.duration_ns).sum();
    assert!(
        sum <= scopes[parent].duration_ns * (1.0 + 1e-9),
        "children {sum} ns > parent {} ns",
        scopes[parent].duration_ns
    );
    for c in &children {
        assert!(
            c.start_ns >= scopes[parent].start_ns
                && c.start_ns + c.duration_ns <= scopes[parent].start_ns + scopes[parent].duration_ns + 1.0
        );
    }
    let pass = out.profile.passes.iter().find(|p| p.path == "reference/reference_chunk").unwrap();
    assert_eq!(pass.count, out.dispatches);
    assert!(out.profile.gpu_ms_total > 0.0);

    profiler.set_detail(false);
    let out = render(&gpu, Technique::Reference, 16, 16, &mut profiler).unwrap();
    assert!(
        out.profile.scopes.iter().all(|s| s.name != "reference_chunk"),
        "detail scopes recorded while detail is off"
    );
    // A long frame after a short one: the profiler resets only the queries the
    // last frame wrote (the whole pool before its first frame), so the ones
    // past the short frame must still be in their reset state; validation
    // says where a query is written unreset.
    profiler.set_detail(true);
    let again = render(&gpu, Technique::Reference, 16, 16, &mut profiler).unwrap();
    assert_eq!(again.profile.scopes.len(), scopes.len(), "the detail frame again");
    drop(gpu);
    assert_validation_clean(&ctx);
}

#[test]
fn ending_scopes_out_of_order_is_an_error() {
    let ctx = validated_context();
    let mut profiler = Profiler::new(&ctx, 8).unwrap();
    let result = submit_and_wait(&ctx, "misuse", |rec| {
        let outer = profiler.begin(rec, "outer")?;
        let inner = profiler.begin(rec, "inner")?;
        let wrong = profiler.end(rec, outer);
        assert!(wrong.is_err(), "ending the outer scope first must fail");
        profiler.end(rec, inner)?;
        Ok(())
    });
    // The outer scope stays open: the frame cannot be resolved.
    assert!(result.is_ok());
    assert!(profiler.resolve(0).is_err());
}

#[test]
fn capacity_overflow_is_an_error_not_a_panic() {
    let ctx = validated_context();
    let mut profiler = Profiler::new(&ctx, 2).unwrap();
    let overflow = submit_and_wait(&ctx, "overflow", |rec| {
        for _ in 0..3 {
            let t = profiler.begin(rec, "s")?;
            profiler.end(rec, t)?;
        }
        Ok(())
    });
    assert!(overflow.is_err());
}

/// Calibrated timestamps (lavapipe has VK_EXT_calibrated_timestamps) put the
/// frame on the host's CLOCK_MONOTONIC: its scopes lie between the host time
/// read before recording and after resolving, and the trace uses that clock.
#[test]
fn calibrated_timestamps_put_gpu_scopes_on_the_host_timeline() {
    use sweeplab::vk::calibration::host_monotonic_ns;
    let ctx = validated_context();
    assert!(ctx.calibrator.is_some(), "lavapipe has calibrated timestamps");
    let scene = chunked_scene();
    let gpu = GpuScene::upload(&ctx, &scene).unwrap();
    let mut profiler = Profiler::new(&ctx, 1024).unwrap();
    let before = host_monotonic_ns() as f64;
    let out = render(&gpu, Technique::Reference, 16, 16, &mut profiler).unwrap();
    let after = host_monotonic_ns() as f64;
    let origin = out.profile.host_origin_ns.expect("a host origin from the calibration");
    let last_end = out.profile.scopes.iter().map(|s| origin + s.start_ns + s.duration_ns).fold(0.0, f64::max);
    // A microsecond of slack for the calibration's own deviation.
    assert!(origin >= before - 1e3 && last_end <= after + 1e3, "{before} <= {origin} .. {last_end} <= {after}");
    let trace = out.profile.chrome_trace();
    assert_eq!(trace["otherData"]["clock"], "CLOCK_MONOTONIC");
    let ts = trace["traceEvents"][0]["ts"].as_f64().unwrap();
    assert!((ts * 1e3 - origin).abs() < 1e3, "trace ts {ts} us against origin {origin} ns");
    assert_validation_clean(&ctx);
}

/// A validated context names its layer's version (every validated run's
/// header prints it beside the driver's API version) and enables no device
/// extension that layer does not know, so a layer older than the driver
/// cannot fail a run with a warning about the engine's own choice.
#[test]
fn a_validated_context_names_its_layer_and_enables_only_extensions_it_knows() {
    use std::ffi::CString;
    use sweeplab::vk::layer_extensions::layer_knows;
    let ctx = validated_context();
    let layer = ctx.validation_layer.clone().expect("the layer's version");
    assert!(ctx.summary().contains(&format!("validation on (layer {layer})")), "{}", ctx.summary());
    let parts: Vec<u32> = layer.split('.').map(|p| p.parse().unwrap()).collect();
    let version = ash::vk::make_api_version(0, parts[0], parts[1], parts[2]);
    assert!(!ctx.device_extensions.is_empty(), "lavapipe offers calibration and push descriptors");
    for name in &ctx.device_extensions {
        let c = CString::new(name.as_str()).unwrap();
        assert!(layer_knows(&c, Some(version)), "{name} enabled, unknown to the layer {layer}");
    }
    if ctx.calibrator.is_some() {
        assert!(
            ctx.device_extensions.iter().any(|n| n.contains("calibrated_timestamps")),
            "{:?}",
            ctx.device_extensions
        );
    }
    assert!(ctx.take_validation_messages().is_empty(), "creating the device warned");
}
