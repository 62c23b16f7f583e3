//! `sweeplab report A.json B.json ...`: `bench sync` runs from several devices
//! side by side (one table, one chart per quantity), every record re-estimated
//! by this build's estimators.

use super::args::ReportArgs;
use anyhow::Context as _;
use std::process::ExitCode;
use sweeplab::bench::experiments::sync::{compare, files};

pub fn run(args: &ReportArgs) -> anyhow::Result<ExitCode> {
    let reports = args.inputs.iter().map(|p| files::read(p)).collect::<Result<Vec<_>, _>>()?;
    let out_folder = super::session::out_folder(&args.out, "report")?;
    let out = out_folder.path();
    let table = compare::side_by_side(&reports);
    table.write_csv(out.join("report.csv"))?;
    let named: Vec<(String, _)> =
        args.inputs.iter().map(|p| p.display().to_string()).zip(reports.iter().cloned()).collect();
    std::fs::write(out.join("report.md"), compare::markdown(&named)).context("writing report.md")?;
    let charts = compare::plot_side_by_side(&reports, out)?;
    println!("{}", table.to_markdown());
    println!("wrote {}/report.md, report.csv and {} (and .svg)", out.display(), charts.join(", "));
    out_folder.finish()?;
    Ok(ExitCode::SUCCESS)
}
