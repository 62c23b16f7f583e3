//! `sweeplab report A.json B.json ...`: `bench sync` runs from several devices
//! side by side (one table, one chart per quantity), every record re-estimated
//! by this build's estimators.

use super::args::ReportArgs;
use super::session;
use std::process::ExitCode;
use sweeplab::bench::experiments::sync::{compare, files};

pub fn run(args: &ReportArgs) -> anyhow::Result<ExitCode> {
    let mut inputs = Vec::new();
    for path in &args.inputs {
        inputs.push((path.display().to_string(), files::read(path)?));
    }
    let out_folder = session::out_folder(&args.out, "report")?;
    let table = compare::write_report(&inputs, out_folder.path())?;
    println!("{}", table.to_markdown());
    session::finish_out(out_folder, None)?;
    Ok(ExitCode::SUCCESS)
}
