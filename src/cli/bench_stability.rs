//! `sweeplab bench stability`: the arguments, then the experiment
//! (`sweeplab::bench::experiments::stability_bench`): every case x technique,
//! the convergence of each technique over the step, and a heat map.

use super::args::BenchStabilityArgs;
use super::session;
use std::process::ExitCode;
use sweeplab::bench::experiments::stability_bench::{self, StabilityPlan};
use sweeplab::bench::OutFolder;

pub fn run(args: &BenchStabilityArgs) -> anyhow::Result<ExitCode> {
    // One untimed frame per cell first: llvmpipe compiles shader variants on first use.
    let harness = session::harness(1, args.repeat)?;
    sweeplab::bench::experiments::image_sizes::check_sizes("--size", &[args.size])?;
    let dir = std::env::temp_dir().join(format!("sweeplab-bench-stability-{}", std::process::id()));
    let plan = StabilityPlan::choose(args.size, &args.cases, &args.techniques, harness, dir)?;
    let out_folder = OutFolder::prepare(&args.out)?;
    let ctx = session::open(&args.gpu)?;
    let report = stability_bench::run(&ctx, &plan, session::run_info(&ctx), &out_folder)?;
    report.write(&args.out)?;
    report.print_summary();
    println!(
        "wrote {}/stability.csv, stability.json, stability.md (the full table), stability_convergence.csv, \
         stability_convergence.json, stability.png and .svg",
        args.out.display()
    );
    out_folder.finish()?;
    let code = session::finish(&ctx);
    if report.failed > 0 {
        eprintln!("{} cell(s) or convergence row(s) FAILED", report.failed);
        return Ok(ExitCode::from(1));
    }
    Ok(code)
}
