//! Fitting a workload's fewest rounds into the time budget of `bench sync`.
//!
//! The protocol's fewest rounds (six, for an interval of a median) cannot be
//! shortened, so where six rounds of every configuration would run past the
//! budget, the workload measures fewer configurations instead of overrunning:
//! first the interior line widths (a slope needs the narrowest and the widest;
//! the ones between only check that frame time is a line), keeping the one
//! nearest the middle longest; then, in the sweep workload, the widest, after
//! which its costs come from frame differences at the narrowest width alone
//! (no slope). The empty workload keeps its narrowest and widest: its answer
//! is a slope, and its frames are short.
//! The narrowest line width, the A/A control and the baseline's per-line
//! timestamp frames always stay: they are what the verdict's serialization,
//! its control and the timestamps' effect read. What was left out, and why,
//! goes into the report and the verdict.

use super::{ConfigKey, Workload};
use serde::{Deserialize, Serialize};
use std::time::Duration;

/// What a workload left out to fit its fewest rounds into the budget.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LeftOut {
    /// The fewest rounds the prediction is for.
    pub rounds: u32,
    pub line_widths: Vec<u32>,
    /// Whether the A/A control was left out (records of an older rule; the
    /// control now always stays).
    #[serde(default)]
    pub control: bool,
    /// Whether a single line width was kept (costs from frame differences at
    /// it, no slopes).
    #[serde(default)]
    pub one_width: bool,
    /// The fewest rounds of every configuration, predicted from the warm-up, s.
    pub all_rounds_s: f64,
    /// The fewest rounds of what is kept, predicted, s.
    pub kept_rounds_s: f64,
    /// What the budget left this workload when its rounds began, s.
    pub time_left_s: f64,
}

impl LeftOut {
    /// E.g. `line width(s) 2, 8, 16 left out to fit the time budget: 6 rounds
    /// of every configuration take about 22.1 min, 7.5 min were left`.
    pub fn describe(&self) -> String {
        let mut parts = Vec::new();
        if !self.line_widths.is_empty() {
            let widths: Vec<String> = self.line_widths.iter().map(|w| w.to_string()).collect();
            parts.push(format!("line width(s) {}", widths.join(", ")));
        }
        if self.control {
            parts.push("the A/A control".to_string());
        }
        let mut text = format!(
            "{} left out to fit the time budget: {} rounds of every configuration take about {:.1} min, \
             {:.1} min were left (--max-minutes sets the budget)",
            parts.join(" and "),
            self.rounds,
            self.all_rounds_s / 60.0,
            self.time_left_s / 60.0
        );
        if self.one_width {
            text += "; with one line width left, costs are frame differences at it (no slopes)";
        }
        if self.kept_rounds_s > self.time_left_s {
            // The narrowest line width, the control and the timestamped frames
            // cannot go: say that the run ends late rather than let it surprise.
            text += &format!(
                "; what is kept still takes about {:.1} min, so the run ends past its budget \
                 (fewer strategies, a smaller --size or a larger --max-minutes fit)",
                self.kept_rounds_s / 60.0
            );
        }
        text
    }
}

/// The configurations to keep (indices into the keys given to [`fit`]) and
/// what was left out (None where everything fits).
#[derive(Clone, Debug, PartialEq)]
pub struct Fit {
    pub kept: Vec<usize>,
    pub left_out: Option<LeftOut>,
    /// The fewest rounds of what is kept, predicted, s.
    pub kept_rounds_s: f64,
}

/// Keeps as many of one workload's configurations (`keys`, each run taking
/// `run_s` seconds as the warm-up measured) as let `rounds` rounds and
/// `extra_s` more (the traced frames after them) end within `time_left`,
/// dropping line widths in the order the module describes. Where even the
/// smallest set does not fit, the smallest set is kept (the rounds then run
/// past the budget, and the ETA says so).
pub fn fit(keys: &[ConfigKey], run_s: &[f64], rounds: u32, extra_s: f64, time_left: Duration) -> Fit {
    assert_eq!(keys.len(), run_s.len(), "one time per configuration");
    let seconds = |kept: &[bool]| -> f64 {
        rounds as f64 * kept.iter().zip(run_s).filter(|(k, _)| **k).map(|(_, s)| s.max(0.0)).sum::<f64>() + extra_s
    };
    let mut kept = vec![true; keys.len()];
    let all_rounds_s = seconds(&kept);
    let budget = time_left.as_secs_f64();
    let mut dropped = Vec::new();
    for width in drop_order(keys, keys.first().is_some_and(|k| k.workload != Workload::Empty)) {
        if seconds(&kept) <= budget {
            break;
        }
        for (i, key) in keys.iter().enumerate() {
            if key.line_width == width {
                kept[i] = false;
            }
        }
        dropped.push(width);
    }
    let kept_rounds_s = seconds(&kept);
    let widths_left = {
        let mut w: Vec<u32> = (0..keys.len()).filter(|&i| kept[i]).map(|i| keys[i].line_width).collect();
        w.sort_unstable();
        w.dedup();
        w.len()
    };
    dropped.sort_unstable();
    let left_out = (!dropped.is_empty()).then_some(LeftOut {
        rounds,
        line_widths: dropped,
        control: false,
        one_width: widths_left == 1,
        all_rounds_s,
        kept_rounds_s,
        time_left_s: budget,
    });
    Fit { kept: (0..keys.len()).filter(|&i| kept[i]).collect(), left_out, kept_rounds_s }
}

/// Interior line widths, least wanted first (the one nearest the middle, in
/// log scale, last; the narrower on a tie), then (`drop_widest`) the widest.
/// The narrowest always stays.
fn drop_order(keys: &[ConfigKey], drop_widest: bool) -> Vec<u32> {
    let mut widths: Vec<u32> = keys.iter().map(|k| k.line_width).collect();
    widths.sort_unstable();
    widths.dedup();
    if widths.len() < 2 {
        return Vec::new();
    }
    let (narrowest, widest) = (widths[0] as f64, widths[widths.len() - 1] as f64);
    let middle = (narrowest.log2() + widest.log2()) / 2.0;
    let mut interior = widths[1..widths.len() - 1].to_vec();
    interior.sort_by(|a, b| {
        let d = |w: u32| ((w as f64).log2() - middle).abs();
        d(*a).total_cmp(&d(*b)).then(a.cmp(b))
    });
    let mut order: Vec<u32> = interior.into_iter().rev().collect();
    if drop_widest {
        order.push(widths[widths.len() - 1]);
    }
    order
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bench::experiments::sync::Arm;
    use crate::techniques::ipsvi::SyncStrategy;

    fn keys(widths: &[u32]) -> Vec<ConfigKey> {
        let arms = [Arm::NoBarriers, Arm::NoBarriersAgain, Arm::Strategy(SyncStrategy::BarrierGlobal)];
        let mut keys = Vec::new();
        for arm in arms {
            for &line_width in widths {
                keys.push(ConfigKey::lines(Workload::Sweep, arm, line_width, false));
            }
        }
        keys.push(ConfigKey::lines(Workload::Sweep, Arm::NoBarriers, widths[0], true));
        keys
    }

    #[test]
    fn everything_is_kept_where_it_fits() {
        let k = keys(&[1, 2, 4, 8, 16, 32]);
        let f = fit(&k, &vec![1.0; k.len()], 6, 2.0, Duration::from_secs(6 * k.len() as u64 + 2));
        assert_eq!(f.kept.len(), k.len());
        assert_eq!(f.left_out, None);
    }

    #[test]
    fn interior_widths_go_first_then_the_widest_and_the_control_always_stays() {
        let k = keys(&[1, 2, 4, 8, 16, 32]);
        let run = vec![1.0; k.len()];
        let left = |budget_s: u64| {
            let f = fit(&k, &run, 1, 0.0, Duration::from_secs(budget_s));
            let kept_widths: std::collections::BTreeSet<u32> = f.kept.iter().map(|&i| k[i].line_width).collect();
            let control = f.kept.iter().any(|&i| k[i].arm == Arm::NoBarriersAgain);
            let stamped = f.kept.iter().any(|&i| k[i].line_timestamps);
            assert!(control && stamped, "the control and the timestamped baseline stay");
            (f.left_out.clone(), kept_widths.into_iter().collect::<Vec<_>>(), f.kept_rounds_s)
        };
        // 19 configurations; dropping a line width saves 3.
        let (out, widths, s) = left(16);
        assert_eq!((widths.as_slice(), s), (&[1, 2, 4, 8, 32][..], 16.0));
        assert_eq!(out.unwrap().line_widths, [16]);
        let (_, widths, s) = left(10);
        assert_eq!((widths.as_slice(), s), (&[1, 4, 32][..], 10.0), "4 is nearest the middle of 1..32");
        let (out, widths, s) = left(7);
        assert_eq!((widths.as_slice(), s), (&[1, 32][..], 7.0));
        assert!(!out.unwrap().one_width);
        // Nothing fits: the narrowest width alone (its arms and the timestamped frames).
        let (out, widths, s) = left(0);
        assert_eq!((widths.as_slice(), s), (&[1][..], 4.0));
        let out = out.unwrap();
        assert!(out.one_width && out.line_widths == [2, 4, 8, 16, 32] && !out.control, "{out:?}");
        assert!(out.describe().contains("frame differences at it"), "{}", out.describe());
    }

    #[test]
    fn the_empty_workload_keeps_its_slope() {
        let k: Vec<ConfigKey> =
            keys(&[1, 4, 32]).into_iter().map(|k| ConfigKey { workload: Workload::Empty, ..k }).collect();
        let f = fit(&k, &vec![1.0; k.len()], 1, 0.0, Duration::ZERO);
        let widths: std::collections::BTreeSet<u32> = f.kept.iter().map(|&i| k[i].line_width).collect();
        assert_eq!(widths.into_iter().collect::<Vec<_>>(), [1, 32]);
        assert!(!f.left_out.unwrap().one_width);
    }

    #[test]
    fn the_traced_frames_count_against_the_budget() {
        let k = keys(&[1, 32]);
        let f = fit(&k, &vec![1.0; k.len()], 1, 3.0, Duration::from_secs(k.len() as u64 + 1));
        assert_eq!(f.left_out.unwrap().line_widths, [32], "the extra seconds made it not fit");
    }

    #[test]
    fn the_description_names_what_was_left_out_and_the_times() {
        let out = LeftOut {
            rounds: 6,
            line_widths: vec![2, 8],
            control: false,
            one_width: false,
            all_rounds_s: 1326.0,
            kept_rounds_s: 400.0,
            time_left_s: 450.0,
        };
        let text = out.describe();
        assert!(text.starts_with("line width(s) 2, 8 left out"), "{text}");
        assert!(text.contains("6 rounds of every configuration take about 22.1 min, 7.5 min were left"), "{text}");
        assert!(!text.contains("past its budget"), "{text}");
        let late = LeftOut { kept_rounds_s: 540.0, ..out }.describe();
        assert!(late.contains("what is kept still takes about 9.0 min, so the run ends past its budget"), "{late}");
    }
}
