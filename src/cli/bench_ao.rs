//! `sweeplab bench ao`: its flags as the study's plan and scene (the study's
//! own scene without `--scene`/`--volume`), run by the one runner
//! (`sweeplab::bench::experiments::ao`).

use super::args::BenchAoArgs;
use super::{experiment_runner, scene_args, session};
use std::process::ExitCode;
use sweeplab::bench::experiments::ao::{self as ao_bench, AoExperiment, AoPlan};
use sweeplab::scene::Scene;

fn load_scene(args: &BenchAoArgs) -> anyhow::Result<Scene> {
    let mut scene = if args.scene.scene.is_none() && args.scene.volume.is_none() {
        ao_bench::default_scene(&args.scene.set)?
    } else {
        scene_args::load(&args.scene)?
    };
    let size = args.scene.size.as_deref().map(scene_args::parse_size).transpose()?;
    (scene.render.width, scene.render.height) = size.unwrap_or((ao_bench::DEFAULT_IMAGE, ao_bench::DEFAULT_IMAGE));
    Ok(scene)
}

pub fn run(args: &BenchAoArgs) -> anyhow::Result<ExitCode> {
    let plan = AoPlan {
        radii: args.radii.clone(),
        bits: args.bits.clone(),
        packed_dims: args.packed_dims.clone(),
        clusters: args.clusters.clone(),
        metrics: args.metrics.clone(),
        reference_pairs: args.reference_pairs,
        rounds: session::interleaved(args.repeat, &args.rounds)?,
        data_set: ao_bench::data_set_name(args.scene.scene.as_deref().or(args.scene.volume.as_deref())),
    };
    let scene = load_scene(args)?;
    experiment_runner::run(&AoExperiment { plan, scene }, &args.out, &args.gpu)
}
