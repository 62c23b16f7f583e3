//! `sweeplab bench table1`: its flags as the study's plan, run by the one
//! runner (`sweeplab::bench::experiments::table1`).

use super::args::BenchTable1Args;
use super::{experiment_runner, session};
use std::process::ExitCode;
use sweeplab::bench::experiments::table1::{Table1Experiment, Table1Plan};

pub fn run(args: &BenchTable1Args) -> anyhow::Result<ExitCode> {
    let interleaved = session::interleaved(args.repeat, &args.rounds)?;
    let mut plan = Table1Plan::paper(args.sizes.clone(), interleaved, args.set.clone()).only(&args.data_sets)?;
    plan.kernels = Table1Plan::kernels_at(&args.kernels, &args.segments);
    plan.errors = !args.no_errors;
    experiment_runner::run(&Table1Experiment { plan }, &args.out, &args.gpu)
}
