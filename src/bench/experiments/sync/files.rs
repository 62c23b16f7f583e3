//! The files of the synchronization study: `sync.json` (the whole report, raw
//! per-round times included, what `sweeplab report` reads), `sync.csv` / `sync.md`
//! (the verdict and one row per strategy and workload), `sync_calibration.csv`
//! (the chain fit per strategy), `sync_configurations.csv` / `.md` (one row
//! per configuration), the charts, each naming the run that produced it.
//! Written after every round, so an interrupted study keeps what it measured;
//! the traces (`trace_*.json`) are written as they are taken.

use super::calibration::ChainFit;
use super::estimates::{Serializes, StrategyRow, TimestampEffect};
use super::report::{ConfigRow, SyncReport};
use super::traces::TraceSummary;
use super::{Workload, BASELINE, CONTROL};
use crate::bench::estimate::{Estimate, Verdict};
use crate::bench::rows::{BenchRow, BenchTable};
use crate::bench::{
    plot_histogram, plot_lines, plot_points, AxisScale, BenchError, Chart, Distribution, Point, Series,
};
use std::path::Path;

/// How a difference reads: `cost`, `within noise`, `below baseline`.
pub(super) fn verdict_word(e: Option<Estimate>) -> &'static str {
    e.map_or("", |e| e.verdict().name())
}

/// How a per-boundary slope reads: `cost`, `within noise`, or `below zero`
/// (frames with more blocks were faster: not a cost, never published as one).
pub(super) fn slope_word(e: Option<Estimate>) -> &'static str {
    match e.map(|e| e.verdict()) {
        Some(Verdict::BelowBaseline) => "below zero",
        v => v.map_or("", Verdict::name),
    }
}

/// A table of one row per item, named with `report`'s run (for files that
/// stand alone) or not (for sections of `sync.md`, under its run).
fn table<T>(report: &SyncReport, named: bool, items: &[T], row: fn(&T) -> BenchRow) -> BenchTable {
    let mut table = if named { BenchTable::with_run(report.run.clone()) } else { BenchTable::new() };
    for item in items {
        table.push(row(item));
    }
    table
}

/// One row per strategy and workload.
pub fn strategy_table(report: &SyncReport) -> BenchTable {
    let mut table = table(report, true, &report.strategies, strategy_row);
    set_line_kernel(report, &mut table, report.strategies.iter().map(|r| r.workload));
    table
}

/// The line kernel beside each row of the workloads that run IPSVI lines
/// (the chain's lines are its own shader), where the record names it.
fn set_line_kernel(report: &SyncReport, table: &mut BenchTable, workloads: impl Iterator<Item = Workload>) {
    let Some(kernel) = report.line_kernel() else { return };
    for (row, workload) in table.rows.iter_mut().zip(workloads) {
        if workload != Workload::Chain {
            row.set("line_kernel", kernel);
        }
    }
}

fn strategy_row(r: &StrategyRow) -> BenchRow {
    let mut row = BenchRow::new();
    row.set("workload", r.workload.name()).set("strategy", r.strategy.as_str()).set("racy", r.racy);
    row.set("line_width", r.line_width).set("boundaries", r.boundaries);
    row.set_estimate("frame_ms", r.frame_ms);
    if r.strategy != BASELINE {
        // What the verdict reads: (a) in the empty workload, (b) in the sweep.
        let quantity = match r.workload {
            Workload::Empty => "fixed cost per boundary",
            _ => "cost per line of the sweep",
        };
        row.set("answers", quantity);
        row.set_estimate("answer_us", r.answer());
        row.set("answer_verdict", verdict_word(r.answer()));
        row.set_estimate("frame_sync_us", r.frame_sync_us);
        row.set_estimate("frame_share", r.frame_share);
    }
    row.set_estimate("boundary_us", r.boundary_us);
    row.set("boundary_verdict", slope_word(r.boundary_us));
    if let Some(v) = r.r_squared {
        row.set("r_squared", v);
    }
    row.set_estimate("sync_us", r.sync_us);
    row.set_estimate("boundary_cpu_us", r.boundary_cpu_us);
    row.set_estimate("sync_cpu_us", r.sync_cpu_us);
    row
}

/// One row per arm of the chain workload's fit.
pub fn calibration_table(report: &SyncReport) -> BenchTable {
    table(report, true, &report.calibration, calibration_row)
}

fn calibration_row(f: &ChainFit) -> BenchRow {
    let mut row = BenchRow::new();
    row.set("strategy", f.strategy.as_str());
    row.set_estimate("fixed_us", f.fixed_us);
    row.set_estimate("fraction", f.fraction);
    if let Some(r) = f.r_squared {
        row.set("r_squared", r);
    }
    row.set_estimate("fixed_over_baseline_us", f.fixed_over_baseline_us);
    row.set_estimate("fraction_over_baseline", f.fraction_over_baseline);
    row
}

/// One row per workload: the per-line timestamps' effect.
pub fn timestamps_table(report: &SyncReport) -> BenchTable {
    table(report, false, &report.timestamps, timestamps_row)
}

fn timestamps_row(t: &TimestampEffect) -> BenchRow {
    let mut row = BenchRow::new();
    row.set("workload", t.workload.name()).set("line_width", t.line_width).set("lines", t.lines);
    row.set_estimate("stamped_ms", t.stamped_ms);
    row.set_estimate("added_ms", t.added_ms);
    row.set_estimate("added_per_line_us", t.added_per_line_us());
    row.set("reference", t.reference.clone().unwrap_or_default());
    row.set_estimate("serialization_ratio", t.serialization_ratio);
    if t.workload == Workload::Sweep {
        let word = match t.serializes() {
            Serializes::Yes => "yes",
            Serializes::Partly => "partly",
            Serializes::No => "no",
            Serializes::NothingToSerialize => "nothing to serialize",
            Serializes::Unknown => "",
        };
        row.set("serializes_lines", word);
    }
    row
}

/// One row per traced frame.
pub fn traces_table(report: &SyncReport) -> BenchTable {
    table(report, false, &report.traces, trace_row)
}

fn trace_row(t: &TraceSummary) -> BenchRow {
    let mut row = BenchRow::new();
    row.set("workload", t.workload.name()).set("strategy", t.strategy.as_str()).set("file", t.file.as_str());
    row.set("line_width", t.line_width).set("chain_trips", t.chain_trips).set("lines", t.lines);
    row.set("frame_ms", t.frame_ms).set("line_median_us", t.line_median_us);
    row.set("gap_median_us", t.gap_median_us).set("gap_q1_us", t.gap_q1_us).set("gap_q3_us", t.gap_q3_us);
    row
}

/// One row per configuration.
pub fn configuration_table(report: &SyncReport) -> BenchTable {
    let mut table = BenchTable::with_run(report.run.clone());
    for c in &report.configurations {
        // The frame's barriers besides the line boundaries' (set-up, cache
        // initialization, read-back): those of the baseline, which has none
        // between lines, at the same line width and chain.
        let setup = report
            .configurations
            .iter()
            .find(|b| {
                b.arm == BASELINE
                    && (b.workload, b.line_width, b.line_timestamps, b.chain_trips)
                        == (c.workload, c.line_width, c.line_timestamps, c.chain_trips)
            })
            .map_or(0, |b| b.barriers);
        table.push(configuration_row(c, setup));
    }
    set_line_kernel(report, &mut table, report.configurations.iter().map(|c| c.workload));
    table
}

/// `boundary_barriers`: the barriers the strategy puts between line blocks
/// (0 for no barriers); `frame_barriers`: every barrier of the frame.
fn configuration_row(c: &ConfigRow, setup_barriers: u32) -> BenchRow {
    let mut row = BenchRow::new();
    row.set("workload", c.workload.name()).set("strategy", c.arm.as_str()).set("racy", c.racy);
    row.set("line_width", c.line_width).set("line_timestamps", c.line_timestamps).set("chain_trips", c.chain_trips);
    row.set("lines", c.lines).set("blocks", c.blocks).set("dispatches", c.dispatches);
    row.set("boundary_barriers", c.barriers.saturating_sub(setup_barriers)).set("frame_barriers", c.barriers);
    row.set("frames", c.frames).set("frames_per_run", c.frames_per_run);
    row.set_estimate("gpu_ms", c.gpu_ms);
    row.set_estimate("cpu_ms", c.cpu_ms);
    row.set_estimate("wall_ms", c.wall_ms);
    row.set("hazards_ignored", c.hazards_ignored);
    if let Some(e) = c.rmse_vs_barrier_global {
        row.set("rmse_vs_barrier_global", e);
    }
    row
}

/// The Markdown report: run, protocol, verdict, the tables.
pub fn markdown(report: &SyncReport) -> String {
    let mut out = String::from("# Synchronization study\n\n");
    if !report.complete {
        out.push_str(&format!("Partial: rounds so far: {}.\n\n", report.rounds_text()));
    }
    out.push_str(&report.run.markdown());
    out.push_str(&format!(
        "Protocol: per workload, {} warm-up round(s), then timed rounds of all its configurations, each in a \
         shuffled order (seed {}); rounds: {}; {:.0} s in all. Single timings are medians with exact 95 % \
         order-statistics intervals; differences are Hodges-Lehmann shifts of the per-round differences against \
         the mean of `{BASELINE}` and `{CONTROL}` (the A/A control: the baseline measured again, its own \
         difference must read within noise) with exact signed-rank intervals. Frame slopes are over the number of \
         line blocks (line widths {:?} at {}x{}), fitted round by round. The verdict reads GPU timestamps; \
         `*_cpu_us` are the same estimates from process CPU time.\n\n",
        report.warm_up_rounds,
        report.seed,
        report.rounds_text(),
        report.seconds,
        report.line_widths,
        report.width,
        report.height,
    ));
    out.push_str("## Verdict\n\n```\n");
    for line in report.verdict() {
        out.push_str(&line);
        out.push('\n');
    }
    out.push_str("```\n\n## Per strategy\n\n");
    out.push_str(&strategy_table(report).to_markdown());
    if !report.calibration.is_empty() {
        out.push_str("\n## Calibration (chain workload)\n\n");
        out.push_str(&calibration_table(report).to_markdown());
    }
    if !report.timestamps.is_empty() {
        out.push_str("\n## Per-line timestamps\n\n");
        out.push_str(&timestamps_table(report).to_markdown());
    }
    if !report.traces.is_empty() {
        out.push_str("\n## Traces (one frame each; open in https://ui.perfetto.dev)\n\n");
        out.push_str(&traces_table(report).to_markdown());
    }
    out.push_str("\n## Per configuration\n\n");
    out.push_str(&configuration_table(report).to_markdown());
    out
}

/// Writes `sync.json`, `sync.csv`, `sync_calibration.csv`, `sync.md`,
/// `sync_configurations.csv` and `sync_configurations.md` into `folder`.
pub fn write(report: &SyncReport, folder: &Path) -> Result<(), BenchError> {
    std::fs::create_dir_all(folder).map_err(|source| BenchError::Write { path: folder.to_owned(), source })?;
    write_json(&folder.join("sync.json"), report)?;
    strategy_table(report).write_csv(folder.join("sync.csv"))?;
    if !report.calibration.is_empty() {
        calibration_table(report).write_csv(folder.join("sync_calibration.csv"))?;
    }
    configuration_table(report).write_csv(folder.join("sync_configurations.csv"))?;
    write_text(&folder.join("sync_configurations.md"), &configuration_table(report).to_markdown_report())?;
    write_text(&folder.join("sync.md"), &markdown(report))
}

/// Writes `value` as pretty JSON at `path`.
pub fn write_json(path: &Path, value: &impl serde::Serialize) -> Result<(), BenchError> {
    let json = serde_json::to_string_pretty(value)
        .map_err(|e| BenchError::Write { path: path.to_owned(), source: std::io::Error::other(e) })?;
    write_text(path, &(json + "\n"))
}

fn write_text(path: &Path, text: &str) -> Result<(), BenchError> {
    std::fs::write(path, text).map_err(|source| BenchError::Write { path: path.to_owned(), source })
}

/// Reads a `sync.json` written by [`write`] (of this build or an older one)
/// and computes every estimate anew from its raw per-round times.
pub fn read(path: &Path) -> Result<SyncReport, BenchError> {
    let text = std::fs::read_to_string(path).map_err(|source| BenchError::Read { path: path.to_owned(), source })?;
    let mut report: SyncReport =
        serde_json::from_str(&text).map_err(|source| BenchError::NotSyncReport { path: path.to_owned(), source })?;
    report.derive();
    Ok(report)
}

/// A log y axis where every value and interval is above zero (costs that span
/// orders of magnitude), a linear one where any is not (within noise).
pub(super) fn y_scale(series: &[Series]) -> AxisScale {
    let positive =
        series.iter().flat_map(|s| &s.points).all(|p| p.y > 0.0 && p.interval.is_none_or(|(lo, _)| lo > 0.0));
    if positive && series.iter().any(|s| !s.points.is_empty()) {
        AxisScale::Log10
    } else {
        AxisScale::Linear
    }
}

/// The study's charts, each PNG with an SVG beside it, captioned with the run:
/// - `sync_frames_<workload>.png`: frame time over the number of blocks per
///   arm (medians with their intervals), the lines whose slopes are costs;
/// - `sync_cost_empty.png`, `sync_cost_sweep.png`: per strategy (named on
///   the axis) the verdict's estimate with its interval: (a) the fixed cost
///   per boundary, (b) the cost per sweep line (hollow: within noise);
/// - `sync_calibration.png`: per arm a boundary's time over the chain's
///   latency (medians over rounds): the lines the calibration fits;
/// - `sync_gaps_<workload>.png`: the gaps between lines of each traced frame.
pub fn write_charts(report: &SyncReport, folder: &Path) -> Result<(), BenchError> {
    let caption = report.run.caption();
    let chart = |title: String, x: &str, y: &str| Chart::new(title, x, y).caption(caption.as_str());
    for w in [Workload::Empty, Workload::Sweep].into_iter().filter(|&w| report.rounds_of(w) > 0) {
        let name = w.name();
        let frames: Vec<Series> = report
            .rows_of(w)
            .map(|arm| {
                let points = report
                    .configs_of(w)
                    .filter(|c| c.arm == arm.strategy && !c.line_timestamps)
                    .filter_map(|c| c.gpu_ms.map(|e| Point::new(c.blocks as f64, e.value).with_interval(e.lo, e.hi)))
                    .collect();
                Series::with_points(arm.strategy.as_str(), points)
            })
            .collect();
        plot_lines(
            folder.join(format!("sync_frames_{name}.png")),
            &chart(format!("{name} workload: frame time over line blocks"), "line blocks per frame", "GPU time (ms)")
                .x_scale(AxisScale::Log2),
            &frames,
        )?;
        let strategies: Vec<&StrategyRow> = report.rows_of(w).filter(|r| r.strategy != BASELINE).collect();
        let points = strategies
            .iter()
            .enumerate()
            .filter_map(|(i, r)| r.answer().map(|e| Point::new(i as f64, e.value).with_interval(e.lo, e.hi)))
            .collect();
        let (title, label) = match w {
            Workload::Empty => ("(a) fixed cost of a line boundary over no barriers, empty workload", "fixed cost"),
            _ => ("(b) cost per line of the sweep over no barriers, frames without per-line timestamps", "per line"),
        };
        let series = [Series::with_points(label, points)];
        plot_points(
            folder.join(format!("sync_cost_{name}.png")),
            &chart(format!("{title}, 95 % CI"), "strategy", "us per boundary")
                .categories(strategies.iter().map(|r| r.strategy.clone()))
                .y_scale(y_scale(&series)),
            &series,
        )?;
        let gaps: Vec<Distribution> = report
            .traces
            .iter()
            .filter(|t| t.workload == w && t.gaps_us.iter().any(|v| *v > 0.0))
            .map(|t| Distribution::new(t.strategy.as_str(), t.gaps_us.clone()))
            .collect();
        if !gaps.is_empty() {
            plot_histogram(
                folder.join(format!("sync_gaps_{name}.png")),
                &chart(format!("{name} workload: gaps between lines, one traced frame each"), "us", "gaps")
                    .x_scale(AxisScale::Log10),
                &gaps,
                24,
            )?;
        }
    }
    if !report.calibration.is_empty() {
        let lines: Vec<Series> = report
            .calibration
            .iter()
            .map(|f| {
                Series::new(
                    f.strategy.as_str(),
                    f.latencies_us.iter().copied().zip(f.per_boundary_us.iter().copied()).collect(),
                )
            })
            .collect();
        plot_lines(
            folder.join("sync_calibration.png"),
            &chart(
                "chain workload: a boundary's time over the chain's latency (slope: the serialized fraction)".into(),
                "chain latency of one line alone (us)",
                "time per line boundary (us)",
            ),
            &lines,
        )?;
    }
    Ok(())
}
