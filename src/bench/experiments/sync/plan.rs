//! What a run of the study measures: image size, strategies, line widths,
//! workloads, the protocol and the time budget; the configurations of the
//! sweep and empty workloads (the chain's come from [`super::chain_plan`]
//! once the sweep has measured a line's latency); the checks made before any
//! GPU work.

use super::{Arm, ConfigKey, Workload};
use crate::bench::experiments::ExperimentError;
use crate::bench::protocol::Protocol;
use crate::scene::settings_table::SettingsTable as _;
use crate::techniques::ipsvi::{IpsviSettings, IpsviStudy, SyncStrategy};
use serde::{Deserialize, Serialize};
use std::time::Duration;

/// Short frames (the empty workload) are run several times per run, so that
/// a run lasts at least this long and scheduler jitter averages out.
pub const MIN_RUN: Duration = Duration::from_millis(25);

/// The interval asked for: a half-width of at most `relative` times the
/// estimate or at most `absolute_us`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Precision {
    pub relative: f64,
    pub absolute_us: f64,
}

impl Default for Precision {
    fn default() -> Self {
        Precision { relative: 0.25, absolute_us: 3.0 }
    }
}

/// What to measure.
#[derive(Clone, Debug)]
pub struct SyncPlan {
    /// Image size, pixels.
    pub width: u32,
    pub height: u32,
    /// Strategies compared with the baseline (`racy` is the baseline itself).
    pub strategies: Vec<SyncStrategy>,
    pub line_widths: Vec<u32>,
    pub workloads: Vec<Workload>,
    /// The baseline's frames at the narrowest line width also with a timestamp
    /// around every line (the timestamps' own effect), and one traced frame
    /// per strategy and workload (the Perfetto traces).
    pub line_timestamps: bool,
    pub protocol: Protocol,
    pub precision: Precision,
    /// Rounds stop once the next would end past this (never before the
    /// protocol's fewest rounds).
    pub time_budget: Option<Duration>,
    /// Frames shorter than this are averaged, several to a run ([`MIN_RUN`]).
    pub min_run: Duration,
}

impl SyncPlan {
    pub fn narrowest(&self) -> u32 {
        self.line_widths.iter().copied().min().unwrap_or(1)
    }

    /// The arms every workload of lines measures: the baseline, its A/A
    /// control, each strategy.
    pub fn arms(&self) -> Vec<Arm> {
        let mut arms = vec![Arm::NoBarriers, Arm::NoBarriersAgain];
        arms.extend(self.strategies.iter().filter(|s| !s.is_racy()).map(|&s| Arm::Strategy(s)));
        arms
    }
}

/// The configurations of `workload` (sweep or empty) in a fixed order: arm,
/// line width; then the baseline with per-line timestamps at the narrowest
/// width. The chain's depend on what the sweep measured ([`super::chain_plan`]).
pub fn configurations(plan: &SyncPlan, workload: Workload) -> Vec<ConfigKey> {
    if workload == Workload::Chain {
        return Vec::new();
    }
    let mut keys = Vec::new();
    for arm in plan.arms() {
        for &line_width in &plan.line_widths {
            keys.push(ConfigKey::lines(workload, arm, line_width, false));
        }
    }
    if plan.line_timestamps {
        keys.push(ConfigKey::lines(workload, Arm::NoBarriers, plan.narrowest(), true));
    }
    keys
}

/// Checks `plan` before any GPU work.
pub fn check(plan: &SyncPlan, base: &IpsviSettings) -> Result<(), ExperimentError> {
    let bad = |what: String| Err(ExperimentError::Invalid(what));
    if plan.line_widths.len() < 2 {
        return bad("a per-boundary cost is a slope: give at least two line widths (e.g. 1,2,4,8,16,32)".into());
    }
    if plan.workloads.is_empty() {
        return bad("give at least one workload (empty, sweep, chain)".into());
    }
    for &line_width in &plan.line_widths {
        IpsviSettings { line_width, ..base.clone() }.validate().map_err(|e| ExperimentError::Invalid(e.to_string()))?;
    }
    Ok(())
}

/// The order the workloads run in: the sweep first (its fewest rounds take
/// most of the budget and cannot be shortened, and the chain's lengths come
/// from its line latency), then the chain, then the empty workload, whose
/// short rounds use what is left; reports keep [`Workload::ALL`]'s order.
pub fn execution_order(workloads: &[Workload]) -> Vec<Workload> {
    let mut order = workloads.to_vec();
    order.sort_by_key(|w| match w {
        Workload::Sweep => 0,
        Workload::Chain => 1,
        Workload::Empty => 2,
    });
    order.dedup();
    order
}

/// Of the time budget, the share each workload that runs later keeps for
/// itself: the empty workload's near-zero costs narrow with rounds (on
/// lavapipe about 150 rounds for a 3 us half-width, a third of a 10-minute
/// budget), the chain needs its fewest rounds of chains a few sweep lines long.
pub fn later_share(workload: Workload) -> f64 {
    match workload {
        Workload::Sweep => 0.0,
        Workload::Chain => 0.15,
        Workload::Empty => 0.30,
    }
}

/// A configuration's IPSVI settings and study. Every line width does the same
/// work: the claim pass, which a frame leaves out at line width 1 where it
/// cannot change the image (`IpsviSettings::records_claims`), stays in at every
/// width, or the slope over blocks would carry the pass's cost.
pub fn settings_for(
    base: &IpsviSettings,
    line_width: u32,
    sync: SyncStrategy,
    workload: Workload,
) -> (IpsviSettings, IpsviStudy) {
    let study =
        IpsviStudy { breakdown_step: workload.breakdown_step(), keep_redundant_claims: true, ..IpsviStudy::default() };
    (IpsviSettings { line_width, sync, merge_sweeps: false, ..base.clone() }, study)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_sweep_runs_first_then_the_chain_then_the_empty_workload() {
        let all = execution_order(&[Workload::Empty, Workload::Chain, Workload::Sweep]);
        assert_eq!(all, [Workload::Sweep, Workload::Chain, Workload::Empty]);
        assert_eq!(execution_order(&[Workload::Empty]), [Workload::Empty]);
        let kept: f64 = [Workload::Chain, Workload::Empty].into_iter().map(later_share).sum();
        assert!(kept < 0.5, "the sweep keeps most of the budget");
    }

    #[test]
    fn every_line_width_records_the_same_passes() {
        // The sample write pass, which leaves the claim pass out at line width 1.
        let base =
            IpsviSettings { write_pass: crate::techniques::ipsvi::WritePass::Sample, ..IpsviSettings::default() };
        assert!(!base.records_claims(), "line width 1 leaves the claim pass out of a frame");
        for line_width in [1, 2, 32] {
            let (s, study) = settings_for(&base, line_width, SyncStrategy::BarrierGlobal, Workload::Sweep);
            assert!(s.claims_recorded(study.keep_redundant_claims), "line width {line_width}");
        }
    }

    #[test]
    fn only_the_baseline_runs_with_per_line_timestamps_in_the_rounds() {
        let plan = SyncPlan {
            width: 8,
            height: 8,
            strategies: vec![SyncStrategy::BarrierGlobal, SyncStrategy::Submits],
            line_widths: vec![1, 4],
            workloads: vec![Workload::Sweep],
            line_timestamps: true,
            protocol: Protocol::new(1, 6, 6, 1).unwrap(),
            precision: Precision::default(),
            time_budget: None,
            min_run: MIN_RUN,
        };
        let keys = configurations(&plan, Workload::Sweep);
        assert_eq!(keys.len(), 4 * 2 + 1);
        let stamped: Vec<&ConfigKey> = keys.iter().filter(|k| k.line_timestamps).collect();
        assert_eq!(stamped.len(), 1);
        assert_eq!((stamped[0].arm, stamped[0].line_width), (Arm::NoBarriers, 1));
        assert!(configurations(&plan, Workload::Chain).is_empty(), "planned from what the sweep measured");
    }
}
