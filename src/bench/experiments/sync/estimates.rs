//! The quantities of the sweep and empty workloads, computed from the raw
//! per-round times of a report's configurations (so a record of an older build
//! is read with these estimators):
//!
//! - per arm, the slope of frame time over line blocks (`boundary_us`) and,
//!   for a strategy, its difference from the baseline's, round by round
//!   (`sync_us`, the frame slopes), where two or more line widths ran;
//! - per arm at the narrowest line width, the frame, and for a strategy its
//!   frame minus the baseline's per line boundary (`frame_sync_us`) and as a
//!   share of its frame (`frame_share`);
//! - per workload, the baseline's frame with per-line timestamps minus
//!   without, and that against what the reference strategy's barriers add
//!   (whether the timestamps serialize the lines).
//!
//! Each is one estimator of one quantity; none is joined with another.
//! Differences are Hodges-Lehmann shifts of the per-round differences against
//! the mean of the baseline's two copies (`no-barriers`, `no-barriers-again`;
//! the control itself against the first alone), with the exact signed-rank
//! interval; single timings and ratios are medians with the sign-test interval.

use super::report::{ConfigRow, SyncReport};
use super::{Arm, Workload, BASELINE, CONTROL};
use crate::bench::estimate::{median_estimate, paired_slope_difference, slope_per_round, Estimate};
use crate::bench::shift::shift_estimate;
use crate::techniques::ipsvi::SyncStrategy;
use serde::{Deserialize, Serialize};

/// One arm in one workload (sweep or empty).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct StrategyRow {
    pub workload: Workload,
    pub strategy: String,
    pub racy: bool,
    /// Slope of GPU frame time over line blocks: one boundary's time, us
    /// (None with a single line width).
    pub boundary_us: Option<Estimate>,
    pub r_squared: Option<f64>,
    /// The fitted frame time at 0 blocks, ms (the work itself).
    pub intercept_ms: Option<f64>,
    /// `boundary_us` minus the baseline's, round by round (frame slopes).
    pub sync_us: Option<Estimate>,
    /// The same two from process CPU time (what lavapipe spends on the host).
    pub boundary_cpu_us: Option<Estimate>,
    pub sync_cpu_us: Option<Estimate>,
    /// The narrowest line width, and its line boundaries (blocks) per frame.
    #[serde(default)]
    pub line_width: u32,
    #[serde(default)]
    pub boundaries: u32,
    /// The frame at that width without per-line timestamps, ms.
    #[serde(default)]
    pub frame_ms: Option<Estimate>,
    /// That frame minus the baseline's, per line boundary, us.
    #[serde(default)]
    pub frame_sync_us: Option<Estimate>,
    /// That difference as a share of the strategy's frame (0 to 1).
    #[serde(default)]
    pub frame_share: Option<Estimate>,
}

impl StrategyRow {
    /// (a) what a boundary of this strategy costs over none with nothing in
    /// flight (read in the empty workload): the frame slopes' difference,
    /// or with one line width the frame difference per boundary.
    pub fn fixed_cost(&self) -> Option<Estimate> {
        self.sync_us.or(self.frame_sync_us)
    }

    /// (b) what it adds per line of the sweep (read in the sweep workload):
    /// the frame difference per boundary at the narrowest width.
    pub fn serialization(&self) -> Option<Estimate> {
        self.frame_sync_us
    }

    /// The estimate the verdict reads for this row's workload.
    pub fn answer(&self) -> Option<Estimate> {
        match self.workload {
            Workload::Empty => self.fixed_cost(),
            Workload::Sweep | Workload::Chain => self.serialization(),
        }
    }
}

/// The per-line timestamps' effect in one workload: the baseline's frame with
/// a timestamp around every line against the same frame without.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct TimestampEffect {
    pub workload: Workload,
    pub line_width: u32,
    pub lines: u32,
    /// The baseline's frame with the timestamps, ms.
    pub stamped_ms: Option<Estimate>,
    /// With minus without, paired by round, ms.
    pub added_ms: Option<Estimate>,
    /// The strategy whose serialization the timestamps are held against
    /// (barrier-global where measured).
    pub reference: Option<String>,
    /// Whether the reference's frame difference is a cost (lines that
    /// overlap without barriers), which a ratio needs.
    pub reference_serializes: bool,
    /// (timestamped - plain) / (reference - plain), round by round: about 1
    /// or more where the timestamps alone serialize the lines as a barrier does.
    pub serialization_ratio: Option<Estimate>,
}

/// How the timestamps' effect reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Serializes {
    /// The lines do not overlap without barriers here: nothing to serialize.
    NothingToSerialize,
    Yes,
    Partly,
    No,
    /// Too few rounds, or no reference strategy.
    Unknown,
}

/// The ratio at or above which the timestamps count as serializing the lines:
/// they take at least half of what a barrier after every line adds.
pub const SERIALIZES_AT: f64 = 0.5;
/// Below this ratio (its whole interval) they do not.
pub const DOES_NOT_SERIALIZE_BELOW: f64 = 0.1;

impl TimestampEffect {
    pub fn serializes(&self) -> Serializes {
        if self.reference.is_some() && !self.reference_serializes {
            return Serializes::NothingToSerialize;
        }
        match self.serialization_ratio {
            Some(r) if r.lo >= SERIALIZES_AT => Serializes::Yes,
            Some(r) if r.hi < DOES_NOT_SERIALIZE_BELOW => Serializes::No,
            Some(_) => Serializes::Partly,
            None => Serializes::Unknown,
        }
    }

    /// The timestamps' cost per line, us.
    pub fn added_per_line_us(&self) -> Option<Estimate> {
        self.added_ms.map(|e| e.scaled(1e3 / self.lines.max(1) as f64))
    }
}

/// The runs of one configuration of `workload`: arm, line width, timestamps.
fn find<'a>(report: &'a SyncReport, workload: Workload, arm: &str, width: u32, stamped: bool) -> Option<&'a ConfigRow> {
    report
        .configs_of(workload)
        .find(|c| c.arm == arm && c.line_width == width && c.line_timestamps == stamped && c.chain_trips == 0)
}

/// The line widths `arm` ran without timestamps in `workload`, ascending.
fn widths(report: &SyncReport, workload: Workload, arm: &str) -> Vec<u32> {
    let mut w: Vec<u32> =
        report.configs_of(workload).filter(|c| c.arm == arm && !c.line_timestamps).map(|c| c.line_width).collect();
    w.sort_unstable();
    w.dedup();
    w
}

/// Per round, (blocks, time in us) over the arm's line widths, from `value`'s runs.
fn points(
    report: &SyncReport,
    workload: Workload,
    arm: &str,
    value: fn(&ConfigRow) -> &Vec<f64>,
) -> Vec<Vec<(f64, f64)>> {
    let rows: Vec<&ConfigRow> =
        widths(report, workload, arm).into_iter().filter_map(|w| find(report, workload, arm, w, false)).collect();
    let rounds = rows.iter().map(|c| value(c).len()).min().unwrap_or(0);
    (0..rounds).map(|r| rows.iter().map(|c| (c.blocks as f64, value(c)[r] * 1e3)).collect()).collect()
}

/// The baseline's runs at one configuration, round by round: the mean of its
/// two copies where the control ran (and `arm` is not the control itself).
fn baseline_runs(report: &SyncReport, workload: Workload, arm: &str, width: u32) -> Option<Vec<f64>> {
    let base = find(report, workload, BASELINE, width, false)?;
    let again = find(report, workload, CONTROL, width, false).filter(|_| arm != CONTROL);
    Some(match again {
        Some(a) => base.gpu_ms_runs.iter().zip(&a.gpu_ms_runs).map(|(x, y)| 0.5 * (x + y)).collect(),
        None => base.gpu_ms_runs.clone(),
    })
}

/// Every arm's row in the sweep and empty workloads, in the report's order.
pub fn strategy_rows(report: &SyncReport) -> Vec<StrategyRow> {
    let mut rows = Vec::new();
    for workload in [Workload::Empty, Workload::Sweep] {
        let mut arms: Vec<&str> = Vec::new();
        for c in report.configs_of(workload) {
            if !arms.contains(&c.arm.as_str()) {
                arms.push(&c.arm);
            }
        }
        if !arms.contains(&BASELINE) {
            continue;
        }
        for arm in arms {
            rows.push(strategy_row(report, workload, arm));
        }
    }
    rows
}

fn strategy_row(report: &SyncReport, workload: Workload, arm: &str) -> StrategyRow {
    let is_base = arm == BASELINE;
    let gpu = points(report, workload, arm, |c| &c.gpu_ms_runs);
    let cpu = points(report, workload, arm, |c| &c.cpu_ms_runs);
    let slope_difference = |arm_points: &[Vec<(f64, f64)>], value: fn(&ConfigRow) -> &Vec<f64>| {
        if is_base {
            return None;
        }
        let base = points(report, workload, BASELINE, value);
        let again = points(report, workload, CONTROL, value);
        let baselines: Vec<&[Vec<(f64, f64)>]> =
            if arm == CONTROL || again.is_empty() { vec![&base] } else { vec![&base, &again] };
        paired_slope_difference(&baselines, arm_points).ok()
    };
    let fit = slope_per_round(&gpu).ok();
    let narrowest = widths(report, workload, arm).first().copied().unwrap_or(1);
    let here = find(report, workload, arm, narrowest, false);
    let (frame_sync_us, frame_share) = match (here, baseline_runs(report, workload, arm, narrowest)) {
        (Some(c), Some(base)) if !is_base => {
            let n = c.gpu_ms_runs.len().min(base.len());
            let per_boundary = 1e3 / c.blocks.max(1) as f64;
            let d: Vec<f64> = (0..n).map(|r| (c.gpu_ms_runs[r] - base[r]) * per_boundary).collect();
            let share: Vec<f64> = (0..n).map(|r| (c.gpu_ms_runs[r] - base[r]) / c.gpu_ms_runs[r]).collect();
            (shift_estimate(&d).ok(), median_estimate(&share).ok())
        }
        _ => (None, None),
    };
    StrategyRow {
        workload,
        strategy: arm.to_string(),
        racy: Arm::from_name(arm).is_none_or(Arm::racy),
        boundary_us: fit.map(|f| f.slope),
        r_squared: fit.map(|f| f.r_squared),
        intercept_ms: fit.map(|f| f.intercept * 1e-3),
        sync_us: slope_difference(&gpu, |c| &c.gpu_ms_runs),
        boundary_cpu_us: slope_per_round(&cpu).ok().map(|f| f.slope),
        sync_cpu_us: slope_difference(&cpu, |c| &c.cpu_ms_runs),
        line_width: narrowest,
        boundaries: here.map_or(0, |c| c.blocks),
        frame_ms: here.and_then(|c| median_estimate(&c.gpu_ms_runs).ok()),
        frame_sync_us,
        frame_share,
    }
}

/// The strategy the timestamps' effect is held against: barrier-global where
/// measured, else the first strategy of the workload.
fn reference_strategy(report: &SyncReport, workload: Workload) -> Option<String> {
    let strategies: Vec<&ConfigRow> =
        report.configs_of(workload).filter(|c| matches!(c.arm(), Some(Arm::Strategy(_)))).collect();
    strategies
        .iter()
        .find(|c| c.arm == SyncStrategy::BarrierGlobal.name())
        .or(strategies.first())
        .map(|c| c.arm.clone())
}

/// Per workload with timestamped baseline frames, what the timestamps add.
pub fn timestamp_effects(report: &SyncReport) -> Vec<TimestampEffect> {
    let mut out = Vec::new();
    for workload in [Workload::Empty, Workload::Sweep] {
        let Some(stamped) = report.configs_of(workload).find(|c| c.arm == BASELINE && c.line_timestamps) else {
            continue;
        };
        let width = stamped.line_width;
        let Some(plain) = find(report, workload, BASELINE, width, false) else { continue };
        let n = stamped.gpu_ms_runs.len().min(plain.gpu_ms_runs.len());
        let added: Vec<f64> = (0..n).map(|r| stamped.gpu_ms_runs[r] - plain.gpu_ms_runs[r]).collect();
        let reference = reference_strategy(report, workload);
        let reference_row = reference.as_deref().and_then(|name| find(report, workload, name, width, false));
        let reference_serializes = reference
            .as_deref()
            .and_then(|name| report.row(workload, name).and_then(|r| r.frame_sync_us))
            .is_some_and(|e| e.lo > 0.0);
        let ratio = reference_row.filter(|_| reference_serializes).and_then(|r| {
            let m = n.min(r.gpu_ms_runs.len());
            let ratios: Vec<f64> =
                (0..m).map(|i| added[i] / (r.gpu_ms_runs[i] - plain.gpu_ms_runs[i]).max(f64::MIN_POSITIVE)).collect();
            median_estimate(&ratios).ok()
        });
        out.push(TimestampEffect {
            workload,
            line_width: width,
            lines: stamped.blocks,
            stamped_ms: median_estimate(&stamped.gpu_ms_runs).ok(),
            added_ms: shift_estimate(&added).ok(),
            reference,
            reference_serializes,
            serialization_ratio: ratio,
        });
    }
    out
}
