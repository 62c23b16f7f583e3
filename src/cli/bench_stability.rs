//! `sweeplab bench stability`: the arguments, then the experiment
//! (`sweeplab::bench::experiments::stability::bench`): every case x technique,
//! the convergence of each technique over the step, and a heat map.

use super::args::BenchStabilityArgs;
use super::session;
use std::process::ExitCode;
use sweeplab::bench::experiments::stability::bench::{self as stability_bench, StabilityPlan};

pub fn run(args: &BenchStabilityArgs) -> anyhow::Result<ExitCode> {
    // One untimed frame per cell first: llvmpipe compiles shader variants on first use.
    let harness = session::harness(1, args.repeat)?;
    sweeplab::bench::experiments::image_sizes::check_sizes("--size", &[args.size])?;
    let dir = std::env::temp_dir().join(format!("sweeplab-bench-stability-{}", std::process::id()));
    let plan = StabilityPlan::choose(args.size, &args.cases, &args.techniques, harness, dir)?;
    let out_folder = session::out_folder(&args.out, "bench-stability")?;
    let ctx = session::open(&args.gpu)?;
    let measured = stability_bench::run(&ctx, &plan, session::run_info(&ctx), &out_folder);
    let report = session::watch(&out_folder, measured)?;
    report.write(out_folder.path())?;
    report.print_summary();
    session::finish_out(out_folder, None)?;
    let code = session::finish(&ctx);
    if report.failed > 0 {
        eprintln!(
            "{} FAILED",
            sweeplab::plural::count(report.failed as u64, "cell or convergence row", "cells or convergence rows")
        );
        return Ok(ExitCode::from(1));
    }
    Ok(code)
}
