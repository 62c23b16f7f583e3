//! `sweeplab bench lights`: its flags as the study's plan, run by the one
//! runner (`sweeplab::bench::experiments::lights`).

use super::args::BenchLightsArgs;
use super::{experiment_runner, scene_args, session};
use std::process::ExitCode;
use sweeplab::bench::experiments::lights::{LightsExperiment, LightsPlan};

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
    let scene = scene_args::load(&args.scene)?;
    experiment_runner::run(&LightsExperiment { plan, scene }, &args.out, &args.gpu)
}
