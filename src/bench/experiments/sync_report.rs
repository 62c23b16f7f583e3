//! The files of the synchronization study: `sync.json` (the whole report, raw
//! frames included, what `sweeplab report` reads), `sync.csv` / `sync.md` (one
//! row per strategy and workload: per-boundary cost and sync cost with their
//! intervals), `sync_configurations.csv` / `.md` (one row per configuration),
//! each naming the run that produced it. Written after every round, so an
//! interrupted study keeps what it measured.

use super::sync::{ConfigRow, StrategyRow, SyncReport, BASELINE, CONTROL};
use crate::bench::estimate::{Estimate, Verdict};
use crate::bench::rows::{BenchRow, BenchTable};
use crate::bench::{
    plot_histogram, plot_lines, plot_points, AxisScale, BenchError, Chart, Distribution, Point, Series,
};
use std::path::Path;

/// How a sync cost reads: `cost`, `within noise`, `below baseline`.
fn verdict_word(e: Option<Estimate>) -> &'static str {
    e.map_or("", |e| e.verdict().name())
}

/// How a per-boundary slope reads: `cost`, `within noise`, or `below zero`
/// (frames with more blocks were faster: not a cost, never published as one).
fn slope_word(e: Option<Estimate>) -> &'static str {
    match e.map(|e| e.verdict()) {
        Some(Verdict::BelowBaseline) => "below zero",
        v => v.map_or("", Verdict::name),
    }
}

/// One row per strategy and workload.
pub fn strategy_table(report: &SyncReport) -> BenchTable {
    let mut table = BenchTable::with_run(report.run.clone());
    for r in &report.strategies {
        table.push(strategy_row(r));
    }
    table
}

fn strategy_row(r: &StrategyRow) -> BenchRow {
    let mut row = BenchRow::new();
    row.set("workload", r.workload.name()).set("strategy", r.strategy.as_str()).set("racy", r.racy);
    row.set_estimate("boundary_us", r.boundary_us);
    row.set("boundary_verdict", slope_word(r.boundary_us));
    if let Some(v) = r.r_squared {
        row.set("r_squared", v);
    }
    if let Some(v) = r.intercept_ms {
        row.set("intercept_ms", v);
    }
    row.set_estimate("sync_us", r.sync_us);
    if r.strategy != BASELINE {
        // The verdict's estimate (`StrategyRow::verdict_sync_us`) and how it reads.
        row.set_estimate("verdict_sync_us", r.verdict_sync_us());
        row.set("sync_verdict", verdict_word(r.verdict_sync_us()));
    }
    row.set_estimate("boundary_cpu_us", r.boundary_cpu_us);
    row.set_estimate("sync_cpu_us", r.sync_cpu_us);
    if let Some(g) = &r.line_gaps {
        row.set("gap_median_us", g.gap_median_us).set("gap_q1_us", g.gap_q1_us).set("gap_q3_us", g.gap_q3_us);
        row.set("line_median_us", g.line_median_us);
        row.set_estimate("in_frame_sync_us", g.in_frame_sync_us);
        if let Some(agree) = r.estimates_agree() {
            row.set("estimates_agree", agree);
        }
        row.set_estimate("timestamp_perturbation_ms", g.perturbation_ms);
    }
    row
}

/// One row per configuration.
pub fn configuration_table(report: &SyncReport) -> BenchTable {
    let mut table = BenchTable::with_run(report.run.clone());
    for c in &report.configurations {
        // The frame's barriers besides the line boundaries' (set-up, cache
        // initialization, read-back): those of the baseline, which has none
        // between lines, at the same line width.
        let setup = report
            .configurations
            .iter()
            .find(|b| {
                b.arm == BASELINE
                    && (b.workload, b.line_width, b.line_timestamps) == (c.workload, c.line_width, c.line_timestamps)
            })
            .map_or(0, |b| b.barriers);
        table.push(configuration_row(c, setup));
    }
    table
}

/// `boundary_barriers`: the barriers the strategy puts between line blocks
/// (0 for no barriers); `frame_barriers`: every barrier of the frame.
fn configuration_row(c: &ConfigRow, setup_barriers: u32) -> BenchRow {
    let mut row = BenchRow::new();
    row.set("workload", c.workload.name()).set("strategy", c.arm.as_str()).set("racy", c.racy);
    row.set("line_width", c.line_width).set("line_timestamps", c.line_timestamps);
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

/// The Markdown report: run, verdict, the strategy table, how to read it.
pub fn markdown(report: &SyncReport) -> String {
    let strategies = strategy_table(report);
    let mut out = String::from("# Synchronization study\n\n");
    if !report.complete {
        out.push_str(&format!("Partial: rounds so far: {}.\n\n", report.rounds_text()));
    }
    out.push_str(&report.run.markdown());
    out.push_str(&format!(
        "Protocol: per workload, {} warm-up round(s), then timed rounds of all its configurations, \
         each in a shuffled order (seed {}); rounds: {}; {:.0} s in all. Estimates are medians with exact 95 % order-statistics intervals; costs \
         are slopes of frame time over the number of line blocks (line widths {:?} at {}x{}), fitted \
         round by round and compared round by round with the mean of `{BASELINE}` and `{CONTROL}` \
         (Hodges-Lehmann shifts with exact signed-rank intervals). `{CONTROL}` is the baseline \
         measured again (A/A control): its cost against `{BASELINE}` alone must be within noise. The verdict reads GPU \
         timestamps; `*_cpu_us` are the same estimates from process CPU time.{}\n\n",
        report.warm_up_rounds,
        report.seed,
        report.rounds_text(),
        report.seconds,
        report.line_widths,
        report.width,
        report.height,
        left_out_text(report)
    ));
    out.push_str("## Verdict\n\n```\n");
    for line in report.verdict() {
        out.push_str(&line);
        out.push('\n');
    }
    out.push_str("```\n\n## Per strategy\n\n");
    out.push_str(&strategies.to_markdown());
    out.push_str("\n## Per configuration\n\n");
    out.push_str(&configuration_table(report).to_markdown());
    out
}

/// ` The sweep workload measured line widths [1, 4, 32]: ...` for each
/// workload that left configurations out to fit the time budget.
fn left_out_text(report: &SyncReport) -> String {
    report
        .workloads
        .iter()
        .filter_map(|w| {
            w.left_out.as_ref().map(|left| {
                format!(
                    " The {} workload measured line widths {:?}: {}.",
                    w.workload.name(),
                    w.line_widths,
                    left.describe()
                )
            })
        })
        .collect()
}

/// Writes `sync.json`, `sync.csv`, `sync.md`, `sync_configurations.csv`,
/// `sync_configurations.md` and, per strategy with per-line timestamps,
/// `lines_<workload>_<strategy>.json` (its gaps) into `folder`.
pub fn write(report: &SyncReport, folder: &Path) -> Result<(), BenchError> {
    std::fs::create_dir_all(folder).map_err(|source| BenchError::Write { path: folder.to_owned(), source })?;
    let path = folder.join("sync.json");
    let json = serde_json::to_string_pretty(report)
        .map_err(|e| BenchError::Write { path: path.clone(), source: std::io::Error::other(e) })?;
    write_text(&path, &(json + "\n"))?;
    strategy_table(report).write_csv(folder.join("sync.csv"))?;
    configuration_table(report).write_csv(folder.join("sync_configurations.csv"))?;
    write_text(&folder.join("sync_configurations.md"), &configuration_table(report).to_markdown_report())?;
    write_text(&folder.join("sync.md"), &markdown(report))?;
    for r in &report.strategies {
        if let Some(g) = &r.line_gaps {
            let path = folder.join(format!("lines_{}_{}.json", r.workload.name(), r.strategy));
            // Named like every other output: the run, then what the gaps are of.
            let named = serde_json::json!({
                "run": &report.run,
                "workload": r.workload.name(),
                "strategy": &r.strategy,
                "line_gaps": g,
            });
            let json = serde_json::to_string_pretty(&named)
                .map_err(|e| BenchError::Write { path: path.clone(), source: std::io::Error::other(e) })?;
            write_text(&path, &json)?;
        }
    }
    Ok(())
}

fn write_text(path: &Path, text: &str) -> Result<(), BenchError> {
    std::fs::write(path, text).map_err(|source| BenchError::Write { path: path.to_owned(), source })
}

/// Several runs (devices) side by side: one row per device, workload and
/// strategy, with the per-boundary cost and the sync cost over no barriers.
pub fn side_by_side(reports: &[SyncReport]) -> BenchTable {
    let mut table = BenchTable::new();
    for report in reports {
        for r in &report.strategies {
            let mut row = BenchRow::new();
            row.set("device", report.run.device.as_str()).set("driver", report.run.driver_version.as_str());
            row.set("commit", report.run.git_commit.as_str()).set("date", report.run.date.as_str());
            row.set("size", format!("{}x{}", report.width, report.height)).set("rounds", report.rounds_of(r.workload));
            row.set("workload", r.workload.name()).set("strategy", r.strategy.as_str());
            row.set_estimate("boundary_us", r.boundary_us);
            row.set("boundary_verdict", slope_word(r.boundary_us));
            row.set_estimate("sync_us", r.sync_us);
            row.set_estimate("in_frame_sync_us", r.line_gaps.as_ref().and_then(|g| g.in_frame_sync_us));
            if r.strategy != BASELINE {
                row.set_estimate("verdict_sync_us", r.verdict_sync_us());
                row.set("sync_verdict", verdict_word(r.verdict_sync_us()));
            }
            table.push(row);
        }
    }
    table
}

/// Reads a `sync.json` written by [`write`].
pub fn read(path: &Path) -> Result<SyncReport, BenchError> {
    let text = std::fs::read_to_string(path).map_err(|source| BenchError::Read { path: path.to_owned(), source })?;
    serde_json::from_str(&text).map_err(|source| BenchError::NotSyncReport { path: path.to_owned(), source })
}

/// The study's charts, each PNG with an SVG beside it, captioned with the run:
/// - `sync_frames_<workload>.png`: frame time over the number of blocks per
///   strategy (medians with their intervals): the lines whose slopes are the
///   per-boundary costs;
/// - `sync_cost_<workload>.png`: each strategy's sync cost over no barriers,
///   both estimates (frame slopes, paired in the frame) with their intervals
///   (a hollow marker: within noise);
/// - `sync_gaps_<workload>.png`: the gaps between consecutive line dispatches
///   of one timestamped frame per strategy.
pub fn write_charts(report: &SyncReport, folder: &Path) -> Result<(), BenchError> {
    let caption = report.run.caption();
    for w in report.workloads.iter().map(|w| w.workload) {
        let name = w.name();
        let arms: Vec<&StrategyRow> = report.rows_of(w).collect();
        let frames: Vec<Series> = arms
            .iter()
            .map(|arm| {
                let points = report
                    .configurations
                    .iter()
                    .filter(|c| c.workload == w && c.arm == arm.strategy && !c.line_timestamps)
                    .filter_map(|c| c.gpu_ms.map(|e| Point::new(c.blocks as f64, e.value).with_interval(e.lo, e.hi)))
                    .collect();
                Series::with_points(arm.strategy.as_str(), points)
            })
            .collect();
        let chart = |title: String, x: &str, y: &str| Chart::new(title, x, y).caption(caption.as_str());
        plot_lines(
            folder.join(format!("sync_frames_{name}.png")),
            &chart(format!("{name} workload: frame time over line blocks"), "line blocks per frame", "GPU time (ms)")
                .x_scale(AxisScale::Log2),
            &frames,
        )?;
        // Both estimates of each strategy side by side, the frame slopes' left
        // of the strategy's number, the in-frame pairing's right of it.
        let strategies: Vec<&StrategyRow> = arms.iter().copied().filter(|r| r.strategy != BASELINE).collect();
        let estimator = |label: &str, offset: f64, pick: fn(&StrategyRow) -> Option<Estimate>| {
            let points = strategies
                .iter()
                .enumerate()
                .filter_map(|(i, r)| {
                    pick(r).map(|e| Point::new(i as f64 + 1.0 + offset, e.value).with_interval(e.lo, e.hi))
                })
                .collect();
            Series::with_points(label, points)
        };
        let costs = [
            estimator("frame slopes (sync_us)", -0.12, |r| r.sync_us),
            estimator("paired in the frame (in_frame_sync_us)", 0.12, |r| {
                r.line_gaps.as_ref().and_then(|g| g.in_frame_sync_us)
            }),
        ];
        let x_label = strategies
            .iter()
            .enumerate()
            .map(|(i, r)| format!("{} {}", i + 1, r.strategy))
            .collect::<Vec<_>>()
            .join(", ");
        plot_points(
            folder.join(format!("sync_cost_{name}.png")),
            &chart(
                format!("{name} workload: sync cost per boundary over no barriers, 95 % CI"),
                &x_label,
                "us per boundary",
            ),
            &costs,
        )?;
        let gaps: Vec<Distribution> = arms
            .iter()
            .filter_map(|r| r.line_gaps.as_ref().map(|g| (r, g)))
            .filter(|(_, g)| g.last_gaps_us.iter().any(|v| *v > 0.0))
            .map(|(r, g)| Distribution::new(r.strategy.as_str(), g.last_gaps_us.clone()))
            .collect();
        if !gaps.is_empty() {
            plot_histogram(
                folder.join(format!("sync_gaps_{name}.png")),
                &chart(format!("{name} workload: gaps between line dispatches, one frame"), "us", "gaps")
                    .x_scale(AxisScale::Log10),
                &gaps,
                24,
            )?;
        }
    }
    Ok(())
}

/// `report.png`: per device (one series each), every strategy's sync cost
/// over no barriers in `workload` (the verdict's estimate), with its interval.
pub fn plot_side_by_side(
    reports: &[SyncReport],
    workload: super::sync::Workload,
    path: &Path,
) -> Result<(), BenchError> {
    let mut strategies: Vec<String> = Vec::new();
    for r in reports {
        for s in r.rows_of(workload).filter(|s| s.strategy != BASELINE) {
            if !strategies.contains(&s.strategy) {
                strategies.push(s.strategy.clone());
            }
        }
    }
    // Each device a little apart at its strategy, so that intervals do not hide each other.
    let spread = |d: usize| (d as f64 - (reports.len() as f64 - 1.0) / 2.0) * 0.1;
    let series: Vec<Series> = reports
        .iter()
        .enumerate()
        .map(|(d, r)| {
            let points = strategies
                .iter()
                .enumerate()
                .filter_map(|(i, name)| {
                    let e = r.rows_of(workload).find(|s| &s.strategy == name)?.verdict_sync_us()?;
                    Some(Point::new(i as f64 + 1.0 + spread(d), e.value).with_interval(e.lo, e.hi))
                })
                .collect();
            Series::with_points(format!("{} ({}), {}", r.run.device, r.run.driver_version, r.run.date), points)
        })
        .collect();
    let x_label = strategies.iter().enumerate().map(|(i, s)| format!("{} {s}", i + 1)).collect::<Vec<_>>().join(", ");
    plot_points(
        path,
        &Chart::new(
            format!("{} workload: sync cost per boundary over no barriers, 95 % CI", workload.name()),
            x_label,
            "us per boundary",
        ),
        &series,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn estimate(lo: f64, hi: f64) -> Option<Estimate> {
        Some(Estimate { value: (lo + hi) / 2.0, lo, hi, n: 10 })
    }

    #[test]
    fn a_slope_below_zero_is_never_called_a_cost() {
        assert_eq!(slope_word(estimate(-3998.0, -71.7)), "below zero");
        assert_eq!(slope_word(estimate(-2236.0, 1985.0)), "within noise");
        assert_eq!(slope_word(estimate(35.9, 41.7)), "cost");
        assert_eq!(slope_word(None), "");
    }
}
