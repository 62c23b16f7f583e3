//! Several runs (devices) side by side (`sweeplab report`): one table with a
//! row per device and strategy, each quantity in its own columns ((a) the
//! fixed cost, (b) the cost per sweep line and its share of the frame, the
//! calibration's fitted pair), and one chart per quantity, strategies named
//! on the axis, every point with its interval: (a) and (b) in one panel per
//! device and setup, each on its own y axis (a GPU's microsecond would sit on
//! the zero line of a CPU driver's milliseconds of noise), the runs of one
//! setup side by side in its panel; the calibration's fraction, comparable
//! across devices, on one axis.

use super::files::{verdict_word, y_scale};
use super::report::SyncReport;
use super::{Workload, BASELINE, CONTROL};
use crate::bench::estimate::Estimate;
use crate::bench::rows::{BenchRow, BenchTable};
use crate::bench::{plot_point_panels, plot_points, BenchError, Chart, Panel, Point, Series};
use std::path::Path;

/// The strategies any report measured, in first-seen order, the baseline and
/// control left out.
fn strategies(reports: &[SyncReport]) -> Vec<String> {
    let mut names: Vec<String> = Vec::new();
    for r in reports {
        let from_rows = r.strategies.iter().map(|s| s.strategy.as_str());
        let from_fits = r.calibration.iter().map(|f| f.strategy.as_str());
        for name in from_rows.chain(from_fits) {
            if name != BASELINE && name != CONTROL && !names.iter().any(|n| n == name) {
                names.push(name.to_string());
            }
        }
    }
    names
}

/// The scene file's stem the record ran ("" where it names none).
fn scene_stem(r: &SyncReport) -> String {
    let scene = r.run.inputs.iter().find(|(k, _)| k == "scene").map(|(_, v)| v.as_str()).unwrap_or("");
    std::path::Path::new(scene).file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default()
}

/// When the record ran, to the minute.
fn minute(r: &SyncReport) -> String {
    r.run.date.get(..16).unwrap_or(&r.run.date).replace('T', " ")
}

/// A record's label: the device, what ran (scene, size) and when (to the
/// minute), so that two runs of one device stay apart.
pub fn device_label(r: &SyncReport) -> String {
    format!("{}, {} {}x{}, {}", r.run.device, scene_stem(r), r.width, r.height, minute(r))
}

/// One row per device and arm (the baseline, the control, each strategy).
pub fn side_by_side(reports: &[SyncReport]) -> BenchTable {
    let mut table = BenchTable::new();
    for report in reports {
        let arms =
            [BASELINE.to_string(), CONTROL.to_string()].into_iter().chain(strategies(std::slice::from_ref(report)));
        for arm in arms {
            let empty = report.row(Workload::Empty, &arm);
            let sweep = report.row(Workload::Sweep, &arm);
            let fit = report.calibration.iter().find(|f| f.strategy == arm);
            if empty.is_none() && sweep.is_none() && fit.is_none() {
                continue;
            }
            let mut row = BenchRow::new();
            row.set("device", report.run.device.as_str()).set("driver", report.run.driver_version.as_str());
            row.set("commit", report.run.git_commit.as_str()).set("date", report.run.date.as_str());
            row.set("size", format!("{}x{}", report.width, report.height)).set("strategy", arm.as_str());
            row.set("line_kernel", report.line_kernel().unwrap_or("serial (not recorded)"));
            if arm == BASELINE {
                // The dispatch alone, and the frame without barriers.
                row.set_estimate("fixed_us", empty.and_then(|r| r.boundary_us));
                row.set_estimate("sweep_frame_ms", sweep.and_then(|r| r.frame_ms));
            } else {
                let fixed = empty.and_then(|r| r.fixed_cost());
                let per_line = sweep.and_then(|r| r.serialization());
                row.set_estimate("fixed_us", fixed).set("fixed_verdict", verdict_word(fixed));
                row.set_estimate("sweep_per_line_us", per_line).set("sweep_verdict", verdict_word(per_line));
                row.set_estimate("sweep_share", sweep.and_then(|r| r.frame_share));
                row.set_estimate("sweep_frame_ms", sweep.and_then(|r| r.frame_ms));
            }
            row.set_estimate("chain_fixed_us", fit.and_then(|f| f.fixed_us));
            row.set_estimate("chain_fraction", fit.and_then(|f| f.fraction));
            table.push(row);
        }
    }
    table
}

/// The Markdown of `sweeplab report`: each input named with its run, the
/// table, and per device the per-line timestamps' effect.
pub fn markdown(inputs: &[(String, SyncReport)]) -> String {
    let mut md = String::from("# bench sync, side by side\n\n");
    for (path, r) in inputs {
        md.push_str(&format!(
            "- `{path}`: {} ({} {}), {}x{}, rounds {}, {} at {}, {}; command: `{}`\n",
            r.run.device,
            r.run.driver_name,
            r.run.driver_version,
            r.width,
            r.height,
            r.rounds_text(),
            r.run.sweeplab_version,
            r.run.git_commit,
            r.run.date,
            r.run.command
        ));
    }
    let reports: Vec<SyncReport> = inputs.iter().map(|(_, r)| r.clone()).collect();
    md.push_str(
        "\nus per line boundary over no barriers with 95 % intervals: `fixed_us` is (a), the empty workload \
         (for no-barriers: the dispatch alone); `sweep_per_line_us` is (b), the sweep's frame minus the frame \
         without barriers per line, `sweep_share` its share of the frame; `chain_*` the calibration's fitted \
         fixed cost and serialized fraction.\n\n",
    );
    md.push_str(&side_by_side(&reports).to_markdown());
    md.push_str("\n## Verdicts\n\n");
    for (path, r) in inputs {
        md.push_str(&format!("### {} (`{path}`)\n\n```\n", device_label(r)));
        for line in r.verdict() {
            md.push_str(&line);
            md.push('\n');
        }
        md.push_str("```\n\n");
    }
    md
}

/// What a record measured on, its panel's title: the device and driver, the
/// scene and the size. Runs of one setup share a panel.
fn setup_label(r: &SyncReport) -> String {
    let (device, driver, version) = (&r.run.device, &r.run.driver_name, &r.run.driver_version);
    format!("{device} ({driver} {version}), {} {}x{}", scene_stem(r), r.width, r.height)
}

/// A run within its setup's panel: when, and which build.
fn run_label(r: &SyncReport) -> String {
    format!("{}, {}", minute(r), r.run.git_commit)
}

/// Each series a little apart at its strategy, so that intervals do not hide each other.
fn spread(series: usize, count: usize) -> f64 {
    (series as f64 - (count as f64 - 1.0) / 2.0) * 0.12
}

/// One series of `r` over the strategies `names`, points `apart` from the category.
fn quantity_series(
    r: &SyncReport,
    label: String,
    names: &[String],
    apart: f64,
    pick: &dyn Fn(&SyncReport, &str) -> Option<Estimate>,
) -> Series {
    let points = names
        .iter()
        .enumerate()
        .filter_map(|(i, name)| {
            let e = pick(r, name)?;
            Some(Point::new(i as f64 + apart, e.value).with_interval(e.lo, e.hi))
        })
        .collect();
    Series::with_points(label, points)
}

/// One quantity charted over the strategies: its file, title and axis
/// label, and how to read it from a report.
struct Quantity<'a> {
    file: &'a str,
    title: &'a str,
    y_label: &'a str,
    pick: &'a dyn Fn(&SyncReport, &str) -> Option<Estimate>,
}

/// One figure of `q`: a panel per setup (its own y axis, linear from 0: a
/// cost beside what it is a cost over), in it a series per run over the
/// strategies. Setups without the quantity are left out; None (nothing
/// written) where none has it.
fn quantity_panels(
    reports: &[SyncReport],
    names: &[String],
    folder: &Path,
    q: &Quantity,
) -> Result<Option<String>, BenchError> {
    let mut setups: Vec<(String, Vec<&SyncReport>)> = Vec::new();
    for r in reports {
        let setup = setup_label(r);
        match setups.iter_mut().find(|(s, _)| *s == setup) {
            Some((_, runs)) => runs.push(r),
            None => setups.push((setup, vec![r])),
        }
    }
    let panels: Vec<Panel> = setups
        .into_iter()
        .map(|(setup, runs)| {
            let series: Vec<Series> = runs
                .iter()
                .enumerate()
                .map(|(k, r)| quantity_series(r, run_label(r), names, spread(k, runs.len()), q.pick))
                .collect();
            let chart = Chart::new(setup, "strategy", q.y_label).categories(names.iter().cloned()).y_from_zero();
            Panel { chart: chart.size(900, 420), series }
        })
        .filter(|p| p.series.iter().any(|s| !s.points.is_empty()))
        .collect();
    if panels.is_empty() {
        return Ok(None);
    }
    plot_point_panels(folder.join(q.file), q.title, &panels)?;
    Ok(Some(q.file.to_string()))
}

/// One chart of `q` on one axis: per device a series over the strategies.
fn quantity_chart(reports: &[SyncReport], names: &[String], folder: &Path, q: &Quantity) -> Result<String, BenchError> {
    let series: Vec<Series> = reports
        .iter()
        .enumerate()
        .map(|(d, r)| quantity_series(r, device_label(r), names, spread(d, reports.len()), q.pick))
        .collect();
    let chart = Chart::new(q.title, "strategy", q.y_label).categories(names.iter().cloned()).y_scale(y_scale(&series));
    plot_points(folder.join(q.file), &chart, &series)?;
    Ok(q.file.to_string())
}

/// `report_fixed_cost.png` (a) and `report_sweep.png` (b), a panel per
/// setup, and, where a report has the chain workload,
/// `report_calibration.png` (the serialized fraction): the quantities apart,
/// each with its intervals.
pub fn plot_side_by_side(reports: &[SyncReport], folder: &Path) -> Result<Vec<String>, BenchError> {
    let mut written = Vec::new();
    let names = strategies(reports);
    if reports.iter().any(|r| r.rounds_of(Workload::Empty) > 0) {
        let fixed = Quantity {
            file: "report_fixed_cost.png",
            title: "(a) fixed cost of a line boundary over no barriers (empty workload), 95 % CI",
            y_label: "us per boundary",
            pick: &|r, s| r.row(Workload::Empty, s).and_then(|r| r.fixed_cost()),
        };
        written.extend(quantity_panels(reports, &names, folder, &fixed)?);
    }
    if reports.iter().any(|r| r.rounds_of(Workload::Sweep) > 0) {
        let sweep = Quantity {
            file: "report_sweep.png",
            title: "(b) cost per line of the sweep over no barriers (frames without per-line timestamps), 95 % CI",
            y_label: "us per line",
            pick: &|r, s| r.row(Workload::Sweep, s).and_then(|r| r.serialization()),
        };
        written.extend(quantity_panels(reports, &names, folder, &sweep)?);
    }
    if reports.iter().any(|r| !r.calibration.is_empty()) {
        let with_baseline: Vec<String> = std::iter::once(BASELINE.to_string()).chain(names.iter().cloned()).collect();
        let fraction = Quantity {
            file: "report_calibration.png",
            title: "calibration: the share of a line's chain latency a boundary exposes, 95 % CI",
            y_label: "serialized fraction",
            pick: &|r, s| r.calibration.iter().find(|f| f.strategy == s).and_then(|f| f.fraction),
        };
        written.push(quantity_chart(reports, &with_baseline, folder, &fraction)?);
    }
    Ok(written)
}

/// Everything `sweeplab report` writes into `folder`: `report.csv`,
/// `report.md` (each input named by its path) and the charts; returns the
/// table for the terminal.
pub fn write_report(inputs: &[(String, SyncReport)], folder: &Path) -> Result<BenchTable, BenchError> {
    let reports: Vec<SyncReport> = inputs.iter().map(|(_, r)| r.clone()).collect();
    let table = side_by_side(&reports);
    table.write_csv(folder.join("report.csv"))?;
    std::fs::write(folder.join("report.md"), markdown(inputs))
        .map_err(|e| BenchError::Write { path: folder.join("report.md"), source: e })?;
    plot_side_by_side(&reports, folder)?;
    Ok(table)
}
