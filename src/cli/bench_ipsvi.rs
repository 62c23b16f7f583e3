//! `sweeplab bench ipsvi`: the arguments and the scene, then the experiment
//! (`sweeplab::bench::experiments::ipsvi`, or `ipsvi::breakdown` with
//! `--breakdown`).

use super::args::BenchIpsviArgs;
use super::render_cmd::PROFILER_CAPACITY;
use super::{scene_args, session};
use std::process::ExitCode;
use sweeplab::bench::experiments::ipsvi::{self as ipsvi_bench, IpsviPlan, DEFAULT_GROUP_BYTES};
use sweeplab::bench::Interleaved;
use sweeplab::techniques::ipsvi::IpsviSettings;

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
        kernels: args.kernels.clone(),
    };
    plan.check()?;
    let scene = scene_args::load(&args.scene)?;
    plan.configurations(&scene.settings.get::<IpsviSettings>())?;
    let out_folder = session::out_folder(&args.out, "bench-ipsvi")?;
    let ctx = session::open(&args.gpu)?;
    let measured = ipsvi_bench::run(&ctx, &scene, &plan, session::run_info(&ctx), &out_folder, PROFILER_CAPACITY);
    let report = session::watch(&out_folder, measured)?;
    report.print_summary();
    session::finish_out(out_folder, None)?;
    Ok(session::finish(&ctx))
}

/// The shared rounds of `args`, within --max-minutes when given.
pub fn rounds(args: &BenchIpsviArgs) -> anyhow::Result<Interleaved> {
    let rounds = session::interleaved(args.repeat, &args.rounds)?;
    let Some(minutes) = args.max_minutes else { return Ok(rounds) };
    rounds.within_minutes(minutes).map_err(|e| anyhow::anyhow!("--max-minutes: {e}"))
}
