//! Figure 10's cost per added light in CPU time, run by hand (ignored):
//! lavapipe runs the shaders on the CPU, so the process's CPU time per entire
//! update is what the pass costs, and unlike GPU (wall) time it does not grow
//! when other processes share the cores. Engine DR*1/4, directional lights of
//! one direction (`scaling_lights`), coherent and sequential, no validation.
//!
//! cargo test --release --test suite lightvolume_cpu_cost:: -- --ignored --nocapture
use crate::common;

use sweeplab::bench::experiments::lights::measure::{lightvolume_scene, scaling_lights};
use sweeplab::render::GpuScene;
use sweeplab::scene::loaders::data_dir;
use sweeplab::scene::Light;
use sweeplab::techniques::lightvolume::{CostEstimate, LightVolumeRenderer};
use sweeplab::techniques::scene_for_volume_file;
use sweeplab::vk::{Context, Profiler};

/// Entire updates per measurement; the least of `ROUNDS` measurements counts.
const UPDATES: usize = 6;
const ROUNDS: usize = 5;
const FEW: u32 = 1;
const MANY: u32 = 16;

fn cpu_seconds() -> f64 {
    common::cpu_seconds("/proc/self/stat")
}

/// CPU ms per entire update of `lights` (least of the rounds).
fn cpu_ms_per_update(ctx: &Context, scene: &sweeplab::scene::Scene, lights: &[Light], coherent: bool) -> f64 {
    let scene = lightvolume_scene(scene, 4, coherent, CostEstimate::Entire, |_| {});
    let gpu = GpuScene::upload(ctx, &scene).unwrap();
    let mut renderer = LightVolumeRenderer::new(&gpu).unwrap();
    let mut profiler = Profiler::new(ctx, 1024).unwrap();
    let state: Vec<Option<Light>> = lights.iter().copied().map(Some).collect();
    let mut update = |renderer: &mut LightVolumeRenderer| {
        renderer.invalidate();
        profiler.reset();
        renderer.update(&state, &mut profiler).unwrap();
    };
    update(&mut renderer); // records the passes, compiles the shaders
    (0..ROUNDS)
        .map(|_| {
            let start = cpu_seconds();
            for _ in 0..UPDATES {
                update(&mut renderer);
            }
            (cpu_seconds() - start) * 1e3 / UPDATES as f64
        })
        .fold(f64::INFINITY, f64::min)
}

#[test]
#[ignore = "measurement, run by hand"]
fn cpu_time_per_added_light_coherent_and_sequential() {
    let path = data_dir().join("engine.vti");
    let scene = scene_for_volume_file(&path, &[]).unwrap();
    let ctx = common::unvalidated_context();
    let mut slopes = Vec::new();
    // LV_COST_COHERENT_ONLY=1: the coherent slope alone (quicker, for comparing builds).
    let modes: &[bool] = if std::env::var("LV_COST_COHERENT_ONLY").is_ok() { &[true] } else { &[true, false] };
    for &coherent in modes {
        let few = cpu_ms_per_update(&ctx, &scene, &scaling_lights(FEW), coherent);
        let many = cpu_ms_per_update(&ctx, &scene, &scaling_lights(MANY), coherent);
        let slope = (many - few) / (MANY - FEW) as f64;
        println!(
            "{}: {FEW} light {few:.1} CPU ms, {MANY} lights {many:.1}: {slope:.2} CPU ms per added light",
            if coherent { "coherent" } else { "sequential" }
        );
        slopes.push(slope);
    }
    if let [coherent, sequential] = slopes[..] {
        println!("sequential / coherent per added light: {:.2}x", sequential / coherent);
    }
}
