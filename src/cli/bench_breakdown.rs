//! `sweeplab bench ipsvi --breakdown`: the arguments and the scene, then the
//! experiment (`sweeplab::bench::experiments::ipsvi::breakdown`).

use super::args::BenchIpsviArgs;
use super::render_cmd::PROFILER_CAPACITY;
use super::{scene_args, session};
use std::process::ExitCode;
use sweeplab::bench::experiments::ipsvi::breakdown::{self as ipsvi_breakdown, BreakdownPlan};
use sweeplab::techniques::ipsvi::IpsviSettings;

pub fn run(args: &BenchIpsviArgs) -> anyhow::Result<ExitCode> {
    let plan = BreakdownPlan {
        sizes: args.sizes.clone(),
        line_widths: args.line_widths.clone(),
        interleaved: super::bench_ipsvi::rounds(args)?,
        volume_texels: session::volume_texels(&args.gpu),
        kernels: args.kernels.clone(),
    };
    let scene = scene_args::load(&args.scene)?;
    plan.check(&scene.settings.get::<IpsviSettings>())?;
    let out_folder = session::out_folder(&args.out, "bench-ipsvi")?;
    let ctx = session::open(&args.gpu)?;
    let measured = ipsvi_breakdown::run(&ctx, &scene, &plan, session::run_info(&ctx), &out_folder, PROFILER_CAPACITY);
    let report = session::watch(&out_folder, measured)?;
    report.print_summary();
    session::finish_out(out_folder, None)?;
    Ok(session::finish(&ctx))
}
