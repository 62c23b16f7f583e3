//! The calibration fit of the chain workload: per arm, time per line boundary
//! = fixed cost + serialized fraction x chain latency.
//!
//! Per round and chain length L: the chain's latency x(L) is one line alone
//! at L minus one line alone with no chain (the chain's own time, no overlap
//! possible); a boundary's time y(L) is the arm's frame of N lines minus one
//! line alone at L, over the N - 1 boundaries. The least-squares line through
//! a round's (x, y) gives its fraction (slope: about 0 where the device
//! overlaps consecutive lines, about 1 where a line waits for the one before)
//! and its fixed cost (intercept: the boundary with no chain, a dispatch and
//! the strategy's own work); the medians over rounds with their intervals,
//! and for a strategy its differences from the baseline round by round
//! (Hodges-Lehmann shifts). Taking x from the same round's frames lets a
//! round in which the machine ran slower slow both alike.

use super::report::{ConfigRow, SyncReport};
use super::{Arm, Workload, ALONE, BASELINE};
use crate::bench::estimate::{median_estimate, median_of, Estimate};
use crate::bench::shift::shift_estimate;
use crate::bench::stats::fit_line;
use serde::{Deserialize, Serialize};

/// One arm's fitted line.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct ChainFit {
    pub strategy: String,
    /// A boundary's time with no chain, us (the intercept).
    pub fixed_us: Option<Estimate>,
    /// The share of a line's chain latency a boundary exposes (the slope).
    pub fraction: Option<Estimate>,
    /// Of the line through the medians over rounds.
    pub r_squared: Option<f64>,
    /// Over the baseline, round by round (None for the baseline).
    pub fixed_over_baseline_us: Option<Estimate>,
    pub fraction_over_baseline: Option<Estimate>,
    /// Each chain length's latency and a boundary's time, medians over rounds, us.
    pub latencies_us: Vec<f64>,
    pub per_boundary_us: Vec<f64>,
}

/// One round's fit of one arm: (slope, intercept), and its points.
struct RoundFit {
    slope: f64,
    intercept: f64,
    points: Vec<(f64, f64)>,
}

fn config<'a>(report: &'a SyncReport, arm: &str, trips: u32) -> Option<&'a ConfigRow> {
    report.configs_of(Workload::Chain).find(|c| c.arm == arm && c.chain_trips == trips)
}

/// Every round's fit of `arm` over the chain lengths `trips` (the first 0).
fn round_fits(report: &SyncReport, arm: &str, trips: &[u32]) -> Vec<RoundFit> {
    let rows: Option<Vec<(&ConfigRow, &ConfigRow)>> =
        trips.iter().map(|&t| Some((config(report, arm, t)?, config(report, ALONE, t)?))).collect();
    let (Some(rows), Some(zero)) = (rows, config(report, ALONE, 0)) else {
        return Vec::new();
    };
    let rounds = rows.iter().map(|(a, b)| a.gpu_ms_runs.len().min(b.gpu_ms_runs.len())).min().unwrap_or(0);
    let rounds = rounds.min(zero.gpu_ms_runs.len());
    (0..rounds)
        .filter_map(|r| {
            let points: Vec<(f64, f64)> = rows
                .iter()
                .map(|(frame, alone)| {
                    let boundaries = frame.lines.saturating_sub(1).max(1) as f64;
                    let x = (alone.gpu_ms_runs[r] - zero.gpu_ms_runs[r]) * 1e3;
                    let y = (frame.gpu_ms_runs[r] - alone.gpu_ms_runs[r]) * 1e3 / boundaries;
                    (x, y)
                })
                .collect();
            let fit = fit_line(&points)?;
            Some(RoundFit { slope: fit.slope, intercept: fit.intercept, points })
        })
        .collect()
}

/// The chain workload's fit per arm (the baseline first); empty where the
/// chain did not run or has fewer than two chain lengths.
pub fn fits(report: &SyncReport) -> Vec<ChainFit> {
    let Some(setup) = &report.chain else { return Vec::new() };
    let trips = &setup.trips;
    if trips.len() < 2 || trips[0] != 0 {
        return Vec::new();
    }
    let mut arms: Vec<&str> = Vec::new();
    for c in report.configs_of(Workload::Chain) {
        if c.arm != ALONE && !arms.contains(&c.arm.as_str()) {
            arms.push(&c.arm);
        }
    }
    let base = round_fits(report, BASELINE, trips);
    arms.iter()
        .map(|&arm| {
            let fits = round_fits(report, arm, trips);
            let slopes: Vec<f64> = fits.iter().map(|f| f.slope).collect();
            let intercepts: Vec<f64> = fits.iter().map(|f| f.intercept).collect();
            let over = |pick: fn(&RoundFit) -> f64| {
                (arm != BASELINE && base.len() == fits.len())
                    .then(|| {
                        let d: Vec<f64> = fits.iter().zip(&base).map(|(s, b)| pick(s) - pick(b)).collect();
                        shift_estimate(&d).ok()
                    })
                    .flatten()
            };
            let medians: Vec<(f64, f64)> = (0..trips.len())
                .map(|i| {
                    let mut xs: Vec<f64> = fits.iter().map(|f| f.points[i].0).collect();
                    let mut ys: Vec<f64> = fits.iter().map(|f| f.points[i].1).collect();
                    xs.sort_by(f64::total_cmp);
                    ys.sort_by(f64::total_cmp);
                    (median_of(&xs), median_of(&ys))
                })
                .collect();
            ChainFit {
                strategy: arm.to_string(),
                fixed_us: median_estimate(&intercepts).ok(),
                fraction: median_estimate(&slopes).ok(),
                r_squared: fit_line(&medians).map(|f| f.r_squared),
                fixed_over_baseline_us: over(|f| f.intercept),
                fraction_over_baseline: over(|f| f.slope),
                latencies_us: medians.iter().map(|p| p.0).collect(),
                per_boundary_us: medians.iter().map(|p| p.1).collect(),
            }
        })
        .collect()
}

/// Whether `arm` names a strategy (not the baseline).
pub fn is_strategy(fit: &ChainFit) -> bool {
    matches!(Arm::from_name(&fit.strategy), Some(Arm::Strategy(_)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bench::estimate::tests::noise;
    use crate::bench::experiments::sync::chain_plan::ChainSetup;
    use crate::bench::experiments::sync::plan::Precision;
    use crate::bench::run_info::RunInfo;

    fn row(arm: &str, trips: u32, lines: u32, runs: Vec<f64>) -> ConfigRow {
        ConfigRow {
            workload: Workload::Chain,
            arm: arm.into(),
            racy: arm == BASELINE,
            line_width: 1,
            line_timestamps: false,
            chain_trips: trips,
            lines,
            blocks: lines,
            dispatches: lines,
            barriers: 0,
            frames: runs.len(),
            frames_per_run: 1,
            gpu_ms: None,
            cpu_ms: None,
            wall_ms: None,
            cpu_ms_runs: runs.clone(),
            gpu_ms_runs: runs,
            hazards_ignored: 0,
            rmse_vs_barrier_global: None,
        }
    }

    fn report(configurations: Vec<ConfigRow>, trips: Vec<u32>, lines: u32) -> SyncReport {
        SyncReport {
            run: RunInfo::default(),
            complete: true,
            workloads: Vec::new(),
            warm_up_rounds: 1,
            min_rounds: 6,
            max_rounds: 6,
            seed: 1,
            precision: Precision::default(),
            verdict_metric: "gpu".into(),
            width: 64,
            height: 64,
            line_widths: vec![1],
            configurations,
            chain: Some(ChainSetup {
                lines,
                invocations: 64,
                steps_per_trip: 64,
                trips,
                line_latency_us: 100.0,
                line_latency_from: "test".into(),
                trip_ns: 100.0,
                max_multiple: 4.0,
                reduced: None,
            }),
            traces: Vec::new(),
            seconds: 0.0,
            strategies: Vec::new(),
            timestamps: Vec::new(),
            calibration: Vec::new(),
        }
    }

    /// Fabricated rounds of a device where a barrier exposes a line's whole
    /// chain and costs 1.1 us of its own, and lines without barriers overlap
    /// but for 2 % of the chain (a dispatch of 0.2 us), each round with its
    /// own slowdown and every frame its own jitter: the fit finds both pairs
    /// of constants inside its intervals, with r^2 near 1.
    #[test]
    fn the_fit_recovers_known_constants_from_noisy_rounds() {
        let (lines, trips) = (16u32, vec![0u32, 500, 1000, 2000, 4000]);
        let trip_us = 0.13;
        let (dispatch_us, barrier_us, overlap_fraction) = (0.2, 1.1, 0.02);
        let mut rng = noise(31);
        let mut rows: Vec<ConfigRow> = Vec::new();
        let mut runs = std::collections::BTreeMap::<(String, u32), Vec<f64>>::new();
        for _ in 0..12 {
            let slow = 1.0 + 0.05 * (rng() + 1.0);
            for &t in &trips {
                let chain_us = t as f64 * trip_us * slow;
                let jitter = |r: &mut dyn FnMut() -> f64| 1.0 + 0.003 * r();
                let alone = (5.0 + dispatch_us + chain_us) * jitter(&mut rng);
                let boundaries = (lines - 1) as f64;
                let racy = alone + boundaries * (dispatch_us + overlap_fraction * chain_us) * jitter(&mut rng);
                let barrier = alone + boundaries * (dispatch_us + barrier_us + chain_us) * jitter(&mut rng);
                for (arm, us) in [(ALONE, alone), (BASELINE, racy), ("barrier-global", barrier)] {
                    runs.entry((arm.to_string(), t)).or_default().push(us * 1e-3);
                }
            }
        }
        for ((arm, t), r) in runs {
            rows.push(row(&arm, t, if arm == ALONE { 1 } else { lines }, r));
        }
        let fits = fits(&report(rows, trips, lines));
        assert_eq!(fits.len(), 2, "the baseline and the strategy");
        let base = fits.iter().find(|f| f.strategy == BASELINE).unwrap();
        let barrier = fits.iter().find(|f| f.strategy == "barrier-global").unwrap();
        let holds = |e: Option<Estimate>, v: f64, slack: f64| e.is_some_and(|e| e.lo - slack <= v && v <= e.hi + slack);
        assert!(holds(base.fraction, overlap_fraction, 0.01), "{base:?}");
        assert!(holds(barrier.fraction, 1.0, 0.01), "{barrier:?}");
        assert!(holds(base.fixed_us, dispatch_us, 0.3), "{base:?}");
        assert!(holds(barrier.fixed_us, dispatch_us + barrier_us, 0.3), "{barrier:?}");
        assert!(holds(barrier.fraction_over_baseline, 1.0 - overlap_fraction, 0.01), "{barrier:?}");
        assert!(holds(barrier.fixed_over_baseline_us, barrier_us, 0.3), "{barrier:?}");
        assert!(barrier.r_squared.unwrap() > 0.999 && base.r_squared.unwrap() > 0.9, "{fits:?}");
        assert!(barrier.fraction.unwrap().half_width() < 0.05, "a narrow interval: {barrier:?}");
        assert!(is_strategy(barrier) && !is_strategy(base));
    }

    #[test]
    fn no_fit_without_two_lengths_or_the_lines_alone() {
        let rows = vec![row(BASELINE, 0, 16, vec![1.0; 6]), row(ALONE, 0, 1, vec![0.1; 6])];
        assert!(fits(&report(rows.clone(), vec![0], 16)).is_empty());
        let no_alone = vec![row(BASELINE, 0, 16, vec![1.0; 6]), row(BASELINE, 10, 16, vec![2.0; 6])];
        let f = fits(&report(no_alone, vec![0, 10], 16));
        assert!(f.iter().all(|f| f.fraction.is_none()), "{f:?}");
    }
}
