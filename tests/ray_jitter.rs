//! `render.jitter`: off, every ray caster samples the midpoints of its steps
//! exactly as before jitter existed; on, each pixel samples at its own phase,
//! and the CPU and GPU references take the same phases.
use crate::common;

use common::*;
use glam::Vec3;
use std::path::{Path, PathBuf};
use sweeplab::metrics::compare;
use sweeplab::reference::cpu::{render_cpu, CpuRenderKind};
use sweeplab::render::{GpuScene, VolumeTexels};
use sweeplab::scene::synthetic::noise;
use sweeplab::techniques::load_scene;
use sweeplab::techniques::{render, Technique};
use sweeplab::vk::Profiler;

fn repo(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(path)
}

fn png_bytes(path: &Path) -> Vec<u8> {
    image::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display())).to_rgba8().into_raw()
}

/// The PNGs in tests/golden were written by `sweeplab render --scene
/// tests/scenes/noise.toml --size 40x32 --set camera.distance=3.0 --technique
/// T` built from the code before jitter existed (midpoint samples; the
/// distance given, as the automatic framing has changed since): jitter off
/// must give the same bytes, jitter on must not. The IPSVI PNG was rewritten
/// (jitter off) when texel-ray writes of the default write rule moved to the
/// line plane's crossing (54 of 1280 pixels changed, by at most 4 of 255);
/// the build before that change still gave the old PNG's bytes with jitter off.
/// It was rewritten again when the defaults became `write_rule =
/// "every-sample"` and `read_fronts = "auto"` (per texel on this 0.11 px
/// cache): 149 pixels changed, by at most 18 of 255, and the error against
/// the reference fell from 4.0e-3 to 2.5e-3 RMSE; with the old defaults named
/// the build reproduced the old PNG's bytes.
#[test]
fn jitter_off_reproduces_the_midpoint_images_and_jitter_on_changes_them() {
    let ctx = validated_context();
    let dir = std::env::temp_dir().join(format!("sweeplab-jitter-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for technique in [Technique::Dvr, Technique::Phong, Technique::Reference, Technique::Ipsvi, Technique::LightVolume]
    {
        let golden = png_bytes(&repo(&format!("tests/golden/noise-{technique}-midpoints.png")));
        for jitter in [false, true] {
            let overrides = [
                "render.width=40".into(),
                "render.height=32".into(),
                "camera.distance=3.0".into(),
                format!("render.jitter={jitter}"),
            ];
            let scene = load_scene(&repo("tests/scenes/noise.toml"), &overrides).unwrap();
            let gpu = GpuScene::upload(&ctx, &scene).unwrap();
            let mut profiler = Profiler::new(&ctx, 4096).unwrap();
            let out = render(&gpu, technique, 40, 32, &mut profiler).unwrap();
            let path = dir.join(format!("{technique}-{jitter}.png"));
            out.image.save_png(&path).unwrap();
            let bytes = png_bytes(&path);
            if jitter {
                let differing = bytes.iter().zip(&golden).filter(|(a, b)| a != b).count();
                assert!(differing > golden.len() / 20, "{technique}: jitter changed only {differing} bytes");
            } else {
                assert!(bytes == golden, "{technique}: jitter off differs from the midpoint image");
            }
        }
    }
    std::fs::remove_dir_all(&dir).ok();
    assert_validation_clean(&ctx);
}

/// With jitter on, the GPU reference and the CPU f64 reference march the same
/// jittered samples: they agree to float rounding, as they do at midpoints
/// (tests/gpu_vs_cpu.rs); the CPU at midpoints does not.
#[test]
fn cpu_and_gpu_references_agree_with_jitter_on() {
    let mut scene = scene_with(noise(24, 7), vec![directional(Vec3::new(-1.0, -1.0, -0.5), 2.0)], 32, 32);
    scene.transfer = sweeplab::scene::presets::preset("grayscale-ramp").unwrap();
    scene.render.jitter = true;
    let ctx = validated_context();
    let gpu_image = {
        let gpu = GpuScene::upload_with(&ctx, &scene, VolumeTexels::Float32).unwrap();
        let mut profiler = Profiler::new(&ctx, 4096).unwrap();
        render(&gpu, Technique::Reference, 32, 32, &mut profiler).unwrap().image
    };
    assert_validation_clean(&ctx);
    let kind = CpuRenderKind::reference_of(&scene);
    let cpu = render_cpu(&scene, kind, 32, 32).unwrap();
    let peak = cpu.max_value() as f64;
    assert!(peak > 0.1, "the test image must show something ({peak})");
    let same = compare(&gpu_image, &cpu).unwrap();
    // Float rounding only (gpu_vs_cpu.rs's TIGHT bound).
    assert!(same.max_abs <= 2e-3 * peak, "{same:?} peak {peak}");
    scene.render.jitter = false;
    let midpoints = compare(&gpu_image, &render_cpu(&scene, kind, 32, 32).unwrap()).unwrap();
    assert!(midpoints.max_abs > 10.0 * same.max_abs, "jittered {same:?} vs midpoints {midpoints:?}");
}
