//! `sweeplab report A.json B.json ...`: `bench sync` runs from several devices
//! side by side (one table, one chart).

use super::args::ReportArgs;
use anyhow::Context as _;
use std::process::ExitCode;
use sweeplab::bench::experiments::sync::Workload;
use sweeplab::bench::experiments::sync_report;

pub fn run(args: &ReportArgs) -> anyhow::Result<ExitCode> {
    let reports = args.inputs.iter().map(|p| sync_report::read(p)).collect::<Result<Vec<_>, _>>()?;
    let out_folder = super::session::out_folder(&args.out, "report")?;
    let out = out_folder.path();
    let table = sync_report::side_by_side(&reports);
    table.write_csv(out.join("report.csv"))?;
    let mut md = String::from("# bench sync, side by side\n\n");
    for (path, r) in args.inputs.iter().zip(&reports) {
        md.push_str(&format!(
            "- `{}`: {} ({} {}), {}x{}, rounds {}, {} at {}, {}\n",
            path.display(),
            r.run.device,
            r.run.driver_name,
            r.run.driver_version,
            r.width,
            r.height,
            r.rounds_text(),
            r.run.sweeplab_version,
            r.run.git_commit,
            r.run.date
        ));
    }
    md.push('\n');
    md.push_str(&table.to_markdown());
    std::fs::write(out.join("report.md"), &md).context("writing report.md")?;
    for workload in Workload::ALL {
        if reports.iter().any(|r| r.rounds_of(workload) > 0) {
            sync_report::plot_side_by_side(&reports, workload, &out.join(format!("report_{}.png", workload.name())))?;
        }
    }
    println!("{}", table.to_markdown());
    println!("wrote {}/report.md, report.csv and report_<workload>.png (and .svg)", out.display());
    out_folder.finish()?;
    Ok(ExitCode::SUCCESS)
}
