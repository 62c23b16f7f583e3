//! `sweeplab bench ipsvi --breakdown`: the arguments and the scene, then the
//! experiment (`sweeplab::bench::experiments::ipsvi_breakdown`).

use super::args::BenchIpsviArgs;
use super::render_cmd::PROFILER_CAPACITY;
use super::{scene_args, session};
use std::process::ExitCode;
use sweeplab::bench::experiments::ipsvi_breakdown::{self, BreakdownPlan};
use sweeplab::ipsvi::IpsviSettings;

pub fn run(args: &BenchIpsviArgs) -> anyhow::Result<ExitCode> {
    let plan = BreakdownPlan {
        sizes: args.sizes.clone(),
        line_widths: args.line_widths.clone(),
        interleaved: super::bench_ipsvi::rounds(args)?,
        volume_texels: session::volume_texels(&args.gpu),
        kernels: super::bench_ipsvi::kernels(args)?,
    };
    let scene = scene_args::load(&args.scene)?;
    plan.check(&scene.settings.get::<IpsviSettings>())?;
    let out_folder = session::out_folder(&args.out, "bench-ipsvi")?;
    let ctx = session::open(&args.gpu)?;
    let measured = ipsvi_breakdown::run(&ctx, &scene, &plan, session::run_info(&ctx), &out_folder, PROFILER_CAPACITY);
    let report = session::watch(&out_folder, measured)?;
    report.print_summary();
    println!(
        "wrote {}/ipsvi_breakdown.csv, ipsvi_breakdown.json, ipsvi_breakdown.md (the full tables), ipsvi_breakdown.png \
         and .svg, ipsvi_line_widths.csv, ipsvi_line_widths.json, ipsvi_line_widths.md",
        out_folder.path().display()
    );
    out_folder.finish()?;
    Ok(session::finish(&ctx))
}
