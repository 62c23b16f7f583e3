//! Figures for the light volume's coherence and error on the CT engine at a
//! reduced size, run by hand (not in CI: minutes on lavapipe, and timings on a
//! shared CPU are only indicative):
//!
//! SWEEPLAB_DATA=../shared/data cargo test --release --test lightvolume_measure -- --ignored --nocapture
//!
//! Prints, for DR*1/4 (`LV_SCALE` to change it): the time per added light of
//! figure 10's setup (1, 10 and 20 directional lights of one direction),
//! coherent against sequential, with the default propagation (shared medium)
//! and the per-light integration; the entire update with 4 and 10 lights
//! spread around the volume, coherent against sequential; and the image error
//! at 64x64 of each propagation against the ground truth of its own model.
mod common;

use common::*;
use glam::Vec3;
use std::path::Path;
use sweeplab::lightvolume::{LightVolumeRenderer, UpdateKind};
use sweeplab::linear_image::LinearImage;
use sweeplab::metrics::compare;
use sweeplab::render::{render, GpuScene, Technique};
use sweeplab::scene::scene_file::load_scene;
use sweeplab::scene::settings_table::read_table;
use sweeplab::scene::{Falloff, Light, LightKind, Scene};
use sweeplab::vk::{Context, Profiler};

/// Timed repeats; the least is kept (the CPU is shared: interference only adds).
const REPEAT: usize = 5;

fn engine() -> Scene {
    load_scene(Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/scenes/engine.toml")), &[]).expect("engine scene")
}

fn with_settings(scene: &Scene, table: &str) -> Scene {
    let mut s = scene.clone();
    s.settings.lightvolume = read_table(toml::from_str::<toml::Value>(table).unwrap()).unwrap();
    s
}

fn directional(direction: Vec3, color: Vec3, intensity: f32) -> Light {
    Light { kind: LightKind::Directional { direction }, color, intensity, falloff: Falloff::None }
}

/// Figure 10: `count` directional lights within ~2.5 degrees of one direction
/// (the -y and +x groups).
fn one_direction(count: usize) -> Vec<Light> {
    (0..count)
        .map(|i| {
            let angle = i as f32 * 2.399_963;
            let radius = 0.04 * ((i + 1) as f32 / count as f32).sqrt();
            let d = Vec3::new(0.35 + radius * angle.cos(), -1.0, 0.25 + radius * angle.sin());
            directional(d, Vec3::ONE, 1.0 / count as f32)
        })
        .collect()
}

/// A coloured set spread around the volume, then white lights from the upper
/// hemisphere (as `bench lights` uses for Table 1).
fn spread(count: usize) -> Vec<Light> {
    let mut all = vec![
        directional(Vec3::new(0.45, -1.0, 0.3), Vec3::ONE, 1.0),
        directional(Vec3::new(-0.5, -1.0, -0.2), Vec3::new(1.0, 0.85, 0.6), 0.8),
        Light {
            kind: LightKind::Point { position: Vec3::new(0.95, 0.55, -0.35) },
            color: Vec3::new(1.0, 0.6, 0.25),
            intensity: 1.2,
            falloff: Falloff::None,
        },
        directional(Vec3::new(0.25, -0.55, -1.0), Vec3::new(0.6, 0.75, 1.0), 0.7),
        Light {
            kind: LightKind::Spot {
                position: Vec3::new(-0.4, 1.1, 0.6),
                direction: Vec3::new(0.4, -1.1, -0.6),
                inner_cone_deg: 20.0,
                outer_cone_deg: 35.0,
            },
            color: Vec3::new(0.9, 1.0, 0.8),
            intensity: 1.0,
            falloff: Falloff::None,
        },
        directional(Vec3::new(-1.0, -0.35, 0.5), Vec3::new(1.0, 0.7, 0.9), 0.5),
    ];
    for i in all.len()..count {
        let azimuth = i as f32 * 2.399_963;
        all.push(directional(Vec3::new(azimuth.cos(), -1.2, azimuth.sin()), Vec3::ONE, 0.4));
    }
    all.truncate(count);
    all
}

/// Least GPU time (ms) of an entire update of `lights`, and its pass count.
fn entire_update_ms(ctx: &Context, scene: &Scene, lights: &[Light]) -> (f64, usize) {
    let gpu = GpuScene::upload(ctx, scene).unwrap();
    let mut renderer = LightVolumeRenderer::new(&gpu).unwrap();
    let mut profiler = Profiler::new(ctx, 512).unwrap();
    let on: Vec<Option<Light>> = lights.iter().copied().map(Some).collect();
    let mut times = Vec::new();
    let mut passes = 0;
    // The first update records the passes and compiles the shaders: untimed.
    for i in 0..=REPEAT {
        renderer.invalidate();
        profiler.reset();
        let frame = renderer.update(&on, &mut profiler).unwrap();
        let profile = profiler.resolve(ctx.memory.device_local_peak()).unwrap();
        assert_eq!(frame.update.plan.kind, UpdateKind::Entire);
        passes = frame.groups().len();
        if i > 0 {
            times.push(profile.pass_ms(UpdateKind::Entire.scope_name()));
        }
    }
    (times.into_iter().fold(f64::INFINITY, f64::min), passes)
}

fn relative_rmse(test: &LinearImage, reference: &LinearImage) -> f64 {
    compare(test, reference).unwrap().rmse / reference.max_value() as f64
}

#[test]
#[ignore = "minutes on lavapipe: run by hand for the figures in docs/lightvolume.md"]
fn coherence_and_error_on_the_engine() {
    let ctx = validated_context();
    let scale: u32 = std::env::var("LV_SCALE").ok().and_then(|s| s.parse().ok()).unwrap_or(4);
    let base = engine();
    let propagations = [("shared medium (default)", "shared_medium = true"), ("per light", "shared_medium = false")];

    println!("engine {}, DR*1/{scale}", base.volume.dims);
    for (name, setting) in propagations {
        let mut per_mode = Vec::new();
        for coherent in [true, false] {
            let scene = with_settings(&base, &format!("scale = {scale}\ncoherent = {coherent}\n{setting}\n"));
            let times: Vec<(usize, f64)> =
                [1, 10, 20].iter().map(|&n| (n, entire_update_ms(&ctx, &scene, &one_direction(n)).0)).collect();
            // 1 to 10 lights stay in one pass per group; 20 split into two
            // (pass_lights = 16), which adds a pass's shared work.
            let slope10 = (times[1].1 - times[0].1) / 9.0;
            let slope20 = (times[2].1 - times[0].1) / 19.0;
            println!(
                "  figure 10, {name}, coherent {coherent}: {times:.1?} ms; per added light {slope10:.2} ms (1-10), \
                 {slope20:.2} ms (1-20)"
            );
            per_mode.push((slope10, slope20));
        }
        println!(
            "  {name}: sequential / coherent per added light {:.2}x (1-10), {:.2}x (1-20)",
            per_mode[1].0 / per_mode[0].0,
            per_mode[1].1 / per_mode[0].1
        );
        for n in [4, 10] {
            let [(coh, coh_passes), (seq, seq_passes)] = [true, false].map(|coherent| {
                let scene = with_settings(&base, &format!("scale = {scale}\ncoherent = {coherent}\n{setting}\n"));
                entire_update_ms(&ctx, &scene, &spread(n))
            });
            println!(
                "  entire update, {name}, {n} lights: coherent {coh:.1} ms ({coh_passes} passes), sequential {seq:.1} \
                 ms ({seq_passes} passes): {:.2}x",
                seq / coh
            );
        }
    }

    // Error at 64x64 with four spread lights, each propagation against the
    // ground truth of the model it approximates.
    let size = 64;
    let mut lit = base.clone();
    lit.lights = spread(4);
    lit.reference.step_voxels = lit.render.step_voxels;
    lit.reference.shadow_step_voxels = 1.0;
    let mut profiler = Profiler::new(&ctx, 512).unwrap();
    let mut references = Vec::new();
    for chromatic in [false, true] {
        lit.reference.chromatic = chromatic;
        let gpu = GpuScene::upload(&ctx, &lit).unwrap();
        references.push(render(&gpu, Technique::Reference, size, size, &mut profiler).unwrap().image);
    }
    let unshaded = {
        let gpu = GpuScene::upload(&ctx, &lit).unwrap();
        render(&gpu, Technique::Dvr, size, size, &mut profiler).unwrap().image
    };
    println!("  unshaded DVR against model (i): relative rmse {:.4}", relative_rmse(&unshaded, &references[0]));
    for chromatic in [false, true] {
        for (name, setting) in propagations {
            let scene = with_settings(&lit, &format!("scale = {scale}\nchromatic = {chromatic}\n{setting}\n"));
            let gpu = GpuScene::upload(&ctx, &scene).unwrap();
            let image = render(&gpu, Technique::LightVolume, size, size, &mut profiler).unwrap().image;
            let model = if chromatic { "chromatic model (i)" } else { "model (i)" };
            let stats = compare(&image, &references[chromatic as usize]).unwrap();
            println!(
                "  {size}x{size}, chromatic {chromatic}, {name}: against {model} rmse {:.4e} (relative {:.4})",
                stats.rmse,
                relative_rmse(&image, &references[chromatic as usize])
            );
        }
    }
    assert_validation_clean(&ctx);
}
