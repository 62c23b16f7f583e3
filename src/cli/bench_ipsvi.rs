//! `sweeplab bench ipsvi`: the arguments and the scene, then the experiment
//! (`sweeplab::bench::experiments::ipsvi_bench`, or `ipsvi_breakdown` with
//! `--breakdown`).

use super::args::BenchIpsviArgs;
use super::render_cmd::PROFILER_CAPACITY;
use super::{scene_args, session};
use std::process::ExitCode;
use sweeplab::bench::experiments::ipsvi_bench::{self, IpsviPlan, DEFAULT_GROUP_BYTES};
use sweeplab::bench::Interleaved;
use sweeplab::ipsvi::{IpsviSettings, LineKernel};

pub fn run(args: &BenchIpsviArgs) -> anyhow::Result<ExitCode> {
    if args.breakdown {
        return super::bench_breakdown::run(args);
    }
    let plan = IpsviPlan {
        sizes: args.sizes.clone(),
        line_widths: args.line_widths.clone(),
        cache_sizes: args.cache_sizes.clone(),
        one_at_a_time: args.one_at_a_time,
        half_angle_slices: args.half_angle_slices.clone(),
        interleaved: rounds(args)?,
        volume_texels: session::volume_texels(&args.gpu),
        group_bytes: DEFAULT_GROUP_BYTES,
        kernels: kernels(args)?,
    };
    plan.check()?;
    let scene = scene_args::load(&args.scene)?;
    plan.configurations(&scene.settings.get::<IpsviSettings>())?;
    let out_folder = session::out_folder(&args.out, "bench-ipsvi")?;
    let ctx = session::open(&args.gpu)?;
    let measured = ipsvi_bench::run(&ctx, &scene, &plan, session::run_info(&ctx), &out_folder, PROFILER_CAPACITY);
    let report = session::watch(&out_folder, measured)?;
    report.print_summary();
    println!(
        "wrote {}/ipsvi.csv, ipsvi.json, ipsvi.md (the full table) and ipsvi_<size>_error_vs_time.png (and .svg)",
        out_folder.path().display()
    );
    out_folder.finish()?;
    Ok(session::finish(&ctx))
}

/// The shared rounds of `args`, within --max-minutes when given.
pub fn rounds(args: &BenchIpsviArgs) -> anyhow::Result<Interleaved> {
    let rounds = session::interleaved(args.repeat, &args.rounds)?;
    let Some(minutes) = args.max_minutes else { return Ok(rounds) };
    rounds.within_minutes(minutes).map_err(|e| anyhow::anyhow!("--max-minutes: {e}"))
}

/// `--kernels` by name.
pub fn kernels(args: &BenchIpsviArgs) -> anyhow::Result<Vec<LineKernel>> {
    args.kernels.iter().map(|k| k.parse::<LineKernel>().map_err(|e| anyhow::anyhow!("--kernels: {e}"))).collect()
}
