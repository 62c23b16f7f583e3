//! `sweeplab bench ao`: the arguments and the scene (the Cornell box without
//! `--scene`/`--volume`), then the experiment
//! (`sweeplab::bench::experiments::ao`).

use super::args::BenchAoArgs;
use super::render_cmd::PROFILER_CAPACITY;
use super::{scene_args, session};
use std::process::ExitCode;
use sweeplab::bench::experiments::ao::{self as ao_bench, AoPlan};
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
    ao_bench::configurations(&plan, &scene.settings.get())?;
    let out_folder = session::out_folder(&args.out, "bench-ao")?;
    let ctx = session::open(&args.gpu)?;
    let measured = ao_bench::run(&ctx, &scene, &plan, session::run_info(&ctx), &out_folder, PROFILER_CAPACITY);
    let report = session::watch(&out_folder, measured)?;
    ao_bench::print_summary(&report.table);
    session::finish_out(out_folder, None)?;
    Ok(session::finish(&ctx))
}
