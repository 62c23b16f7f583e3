//! `sweeplab bench table1`: the arguments, then the experiment
//! (`sweeplab::bench::experiments::table1`).

use super::args::BenchTable1Args;
use super::render_cmd::PROFILER_CAPACITY;
use super::session;
use anyhow::Context as _;
use std::process::ExitCode;
use sweeplab::bench::experiments::table1::{self as table1_bench, Table1Plan};

pub fn run(args: &BenchTable1Args) -> anyhow::Result<ExitCode> {
    let interleaved = session::interleaved(args.repeat, &args.rounds)?;
    sweeplab::bench::experiments::image_sizes::check_sizes("--sizes", &args.sizes)?;
    let mut plan = Table1Plan::paper(args.sizes.clone(), interleaved, args.set.clone()).only(&args.data_sets)?;
    plan.kernels = args.kernels.clone();
    let out_folder = session::out_folder(&args.out, "bench-table1")?;
    let ctx = session::open(&args.gpu)?;
    let measured = table1_bench::run(&ctx, &plan, session::run_info(&ctx), &out_folder, PROFILER_CAPACITY);
    let table = session::watch(&out_folder, measured)?;
    let out = out_folder.path();
    table.write_csv(out.join("table1.csv"))?;
    table.write_json(out.join("table1.json"))?;
    std::fs::write(out.join("table1.md"), table.to_markdown_report()).context("writing table1.md")?;
    table1_bench::print_summary(&table);
    session::finish_out(out_folder, None)?;
    Ok(session::finish(&ctx))
}
