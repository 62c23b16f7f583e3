//! `sweeplab report A.json B.json ...`: `bench sync` runs from several devices
//! side by side (one table, one chart per quantity), every record re-estimated
//! by this build's estimators.

use super::args::ReportArgs;
use anyhow::Context as _;
use std::process::ExitCode;
use sweeplab::bench::experiments::sync::{compare, files};

pub fn run(args: &ReportArgs) -> anyhow::Result<ExitCode> {
    let reports = args.inputs.iter().map(|p| files::read(p)).collect::<Result<Vec<_>, _>>()?;
    std::fs::create_dir_all(&args.out).with_context(|| format!("creating {}", args.out.display()))?;
    let table = compare::side_by_side(&reports);
    table.write_csv(args.out.join("report.csv"))?;
    let named: Vec<(String, _)> =
        args.inputs.iter().map(|p| p.display().to_string()).zip(reports.iter().cloned()).collect();
    std::fs::write(args.out.join("report.md"), compare::markdown(&named)).context("writing report.md")?;
    let charts = compare::plot_side_by_side(&reports, &args.out)?;
    println!("{}", table.to_markdown());
    println!("wrote {}/report.md, report.csv and {} (and .svg)", args.out.display(), charts.join(", "));
    Ok(ExitCode::SUCCESS)
}
