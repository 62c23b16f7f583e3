//! `sweeplab bench lights`: the arguments, then the experiment
//! (`sweeplab::bench::experiments::lights`).

use super::args::BenchLightsArgs;
use super::render_cmd::PROFILER_CAPACITY;
use super::{scene_args, session};
use std::process::ExitCode;
use sweeplab::bench::experiments::lights::{self as lights_bench, LightsPlan};

/// The error rows' image without `--size`.
const DEFAULT_ERROR_IMAGE: u32 = 256;

pub fn run(args: &BenchLightsArgs) -> anyhow::Result<ExitCode> {
    let image = match &args.scene.size {
        Some(size) => scene_args::parse_size(size)?,
        None => (DEFAULT_ERROR_IMAGE, DEFAULT_ERROR_IMAGE),
    };
    let plan = LightsPlan {
        scales: args.scales.clone(),
        light_counts: args.light_counts.clone(),
        scaling_counts: args.scaling_counts.clone(),
        scaling_scale: args.scaling_scale,
        error_scales: args.error_scales.clone(),
        incremental_passes: args.incremental_passes.clone(),
        rounds: session::interleaved(args.repeat, &args.rounds)?,
        image,
        volume_texels: session::volume_texels(&args.gpu),
    };
    plan.check()?;
    let scene = scene_args::load(&args.scene)?;
    let out_folder = session::out_folder(&args.out, "bench-lights")?;
    let ctx = session::open(&args.gpu)?;
    let measured = lights_bench::run(&ctx, &scene, &plan, session::run_info(&ctx), &out_folder, PROFILER_CAPACITY);
    let report = session::watch(&out_folder, measured)?;
    report.print_summary();
    session::finish_out(out_folder, None)?;
    Ok(session::finish(&ctx))
}
