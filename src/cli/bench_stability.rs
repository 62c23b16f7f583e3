//! `sweeplab bench stability`: its flags as the study's plan, run by the one
//! runner (`sweeplab::bench::experiments::stability`): every case x
//! technique, the convergence of each technique over the step, and a heat map.

use super::args::BenchStabilityArgs;
use super::{experiment_runner, session};
use std::process::ExitCode;
use sweeplab::bench::experiments::stability::bench::StabilityPlan;
use sweeplab::bench::experiments::stability::StabilityExperiment;

pub fn run(args: &BenchStabilityArgs) -> anyhow::Result<ExitCode> {
    // One untimed frame per cell first: llvmpipe compiles shader variants on first use.
    let harness = session::harness(1, args.repeat)?;
    let dir = std::env::temp_dir().join(format!("sweeplab-bench-stability-{}", std::process::id()));
    let plan = StabilityPlan::choose(args.size, &args.cases, &args.techniques, harness, dir)?;
    experiment_runner::run(&StabilityExperiment { plan }, &args.out, &args.gpu)
}
