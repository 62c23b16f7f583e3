//! What a run of the study keeps: every configuration's raw per-round times
//! (the data every estimate is computed from, so a record read back is
//! re-estimated by the code that reads it: [`SyncReport::derive`]), each
//! workload's rounds and their orders, the chain's set-up, the traces, and the
//! derived estimates.

use super::budget::LeftOut;
use super::calibration::{self, ChainFit};
use super::chain_plan::ChainSetup;
use super::estimates::{self, StrategyRow as Row, TimestampEffect};
use super::plan::Precision;
use super::traces::TraceSummary;
use super::{Arm, Workload};
use crate::bench::estimate::Estimate;
use crate::bench::run_info::RunInfo;
use serde::{Deserialize, Serialize};

pub use super::estimates::StrategyRow;

/// A configuration's frames, summed up, with the raw times behind them.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct ConfigRow {
    pub workload: Workload,
    pub arm: String,
    pub racy: bool,
    pub line_width: u32,
    pub line_timestamps: bool,
    /// Loop trips of each line's chain (chain workload; 0 elsewhere).
    #[serde(default)]
    pub chain_trips: u32,
    pub lines: u32,
    pub blocks: u32,
    pub dispatches: u32,
    pub barriers: u32,
    /// Timed runs, and frames per run (short frames are averaged).
    pub frames: usize,
    pub frames_per_run: u32,
    pub gpu_ms: Option<Estimate>,
    pub cpu_ms: Option<Estimate>,
    pub wall_ms: Option<Estimate>,
    /// Every run's GPU and CPU time, ms, in round order (paired across a
    /// workload's configurations by index): the raw data behind every estimate.
    pub gpu_ms_runs: Vec<f64>,
    pub cpu_ms_runs: Vec<f64>,
    /// Synchronization hazards validation reported (racy arms, validation on).
    pub hazards_ignored: usize,
    /// RMSE of the last frame against barrier-global's at the same line width
    /// and workload: 0 for every strategy; for a racy arm what the missing
    /// barrier did to the image (0 where the device ran the lines in order).
    pub rmse_vs_barrier_global: Option<f64>,
}

impl ConfigRow {
    pub fn arm(&self) -> Option<Arm> {
        Arm::from_name(&self.arm)
    }
}

/// The rounds of one workload.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct WorkloadRounds {
    pub workload: Workload,
    pub rounds: usize,
    /// Each round's order of configurations (indices into `configurations`).
    pub orders: Vec<Vec<usize>>,
    /// Seconds of its timed rounds.
    pub seconds: f64,
    /// Frames its warm-up ran (configurations whose shaders had all run
    /// already, in a workload of long frames, run none).
    #[serde(default)]
    pub warm_up_frames: usize,
    /// The line widths its rounds measured (the plan's, less what was left out).
    #[serde(default)]
    pub line_widths: Vec<u32>,
    /// What it left out to fit its fewest rounds into the time budget.
    #[serde(default)]
    pub left_out: Option<LeftOut>,
}

/// The whole study as measured so far.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct SyncReport {
    pub run: RunInfo,
    /// False while the study is still running (a partial report).
    pub complete: bool,
    /// Each workload's rounds (measured one workload after the other, each
    /// with its own shuffled rounds).
    pub workloads: Vec<WorkloadRounds>,
    pub warm_up_rounds: u32,
    pub min_rounds: u32,
    pub max_rounds: u32,
    pub seed: u64,
    pub precision: Precision,
    /// Which time the verdict reads: `gpu` (timestamps).
    pub verdict_metric: String,
    pub width: u32,
    pub height: u32,
    pub line_widths: Vec<u32>,
    pub configurations: Vec<ConfigRow>,
    /// How the chain workload was set up (None where it did not run).
    #[serde(default)]
    pub chain: Option<ChainSetup>,
    /// One timestamped frame per strategy and workload (`trace_*.json`).
    #[serde(default)]
    pub traces: Vec<TraceSummary>,
    /// Seconds since the study started (set-up and warm-up included).
    pub seconds: f64,
    /// Derived from `configurations` ([`SyncReport::derive`]): per workload
    /// and arm, the slopes and the differences over no barriers.
    #[serde(default)]
    pub strategies: Vec<Row>,
    /// Derived: per workload, the per-line timestamps' effect.
    #[serde(default)]
    pub timestamps: Vec<TimestampEffect>,
    /// Derived: the chain workload's fit per arm.
    #[serde(default)]
    pub calibration: Vec<ChainFit>,
}

impl SyncReport {
    /// The line kernel the IPSVI workloads ran ([`super::LINE_KERNEL_INPUT`]);
    /// None for a record from before it was recorded.
    pub fn line_kernel(&self) -> Option<&str> {
        self.run.inputs.iter().find(|(k, _)| k == super::LINE_KERNEL_INPUT).map(|(_, v)| v.as_str())
    }

    /// What a time budget left out, workload by workload ("sweep workload:
    /// line width(s) 2, 4"); `None` where the run measured all it planned.
    pub fn left_out_summary(&self) -> Option<String> {
        let left_out: Vec<String> = self
            .workloads
            .iter()
            .filter_map(|w| w.left_out.as_ref().map(|l| format!("{} workload: {}", w.workload.name(), l.describe())))
            .collect();
        (!left_out.is_empty()).then(|| left_out.join("; "))
    }

    /// Computes every estimate from the raw per-round times, replacing what
    /// was stored: a record written by an older build is read with today's
    /// estimators.
    pub fn derive(&mut self) {
        self.strategies = estimates::strategy_rows(self);
        self.timestamps = estimates::timestamp_effects(self);
        self.calibration = calibration::fits(self);
    }

    /// The strategy rows of `workload`.
    pub fn rows_of(&self, workload: Workload) -> impl Iterator<Item = &Row> {
        self.strategies.iter().filter(move |r| r.workload == workload)
    }

    /// The row of `strategy` in `workload`.
    pub fn row(&self, workload: Workload, strategy: &str) -> Option<&Row> {
        self.rows_of(workload).find(|r| r.strategy == strategy)
    }

    /// The configurations of `workload` measured in its rounds.
    pub fn configs_of(&self, workload: Workload) -> impl Iterator<Item = &ConfigRow> {
        self.configurations.iter().filter(move |c| c.workload == workload)
    }

    /// Timed rounds per workload, e.g. `empty 30, sweep 6`.
    pub fn rounds_text(&self) -> String {
        self.workloads.iter().map(|w| format!("{} {}", w.workload.name(), w.rounds)).collect::<Vec<_>>().join(", ")
    }

    /// Timed rounds of `workload` (0 where it was not measured).
    pub fn rounds_of(&self, workload: Workload) -> usize {
        self.workloads.iter().find(|w| w.workload == workload).map_or(0, |w| w.rounds)
    }

    /// The rounds entry of `workload`.
    pub fn workload(&self, workload: Workload) -> Option<&WorkloadRounds> {
        self.workloads.iter().find(|w| w.workload == workload)
    }

    /// The per-line timestamps' effect in `workload`.
    pub fn timestamps_of(&self, workload: Workload) -> Option<&TimestampEffect> {
        self.timestamps.iter().find(|t| t.workload == workload)
    }
}
