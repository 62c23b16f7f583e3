//! The study as a user asks for it (`sweeplab bench sync`'s flags, parsed by
//! the CLI) turned into a [`SyncPlan`]: `--quick`'s presets, the defaults,
//! and every value checked, with the flag named where one is refused.

use super::plan::{Precision, SyncPlan, MIN_RUN};
use super::Workload;
use crate::bench::experiments::ExperimentError;
use crate::bench::protocol::Protocol;
use crate::techniques::ipsvi::SyncStrategy;
use std::time::Duration;

/// `--quick`: about a minute on lavapipe.
pub const QUICK_SIZE: &str = "64x64";
const QUICK_LINE_WIDTHS: [u32; 4] = [1, 4, 16, 32];
const QUICK_MINUTES: f64 = 1.5;
pub const DEFAULT_SIZE: &str = "256x256";
const DEFAULT_LINE_WIDTHS: [u32; 6] = [1, 2, 4, 8, 16, 32];
const DEFAULT_MINUTES: f64 = 10.0;

/// The flags, as given (`None`: not on the command line).
#[derive(Clone, Debug, Default)]
pub struct SyncOptions {
    pub strategies: Vec<String>,
    pub workloads: Option<Vec<String>>,
    pub line_widths: Option<Vec<u32>>,
    pub size_given: bool,
    pub max_minutes: Option<f64>,
    pub quick: bool,
    pub warm_up: u32,
    pub repeat: u32,
    pub max_rounds: u32,
    pub target_ci: f64,
    pub target_ci_us: f64,
    pub seed: Option<u64>,
    pub line_timestamps: bool,
}

fn parse_list<T: std::str::FromStr<Err = String>>(flag: &str, values: &[String]) -> Result<Vec<T>, ExperimentError> {
    values
        .iter()
        .map(|s| s.trim().parse().map_err(|e: String| ExperimentError::Invalid(format!("{flag}: {e}"))))
        .collect()
}

impl SyncOptions {
    /// The image size without `--size`.
    pub fn default_size(&self) -> &'static str {
        if self.quick {
            QUICK_SIZE
        } else {
            DEFAULT_SIZE
        }
    }

    /// What `--quick` sets, and which of its presets the command line gave
    /// itself (those win): "--quick: 64x64, the empty workload, line widths
    /// 1,4,16,32, at most 1.5 min; --line-widths given: used instead".
    pub fn quick_note(&self) -> String {
        let given: Vec<&str> = [
            ("--size", self.size_given),
            ("--workloads", self.workloads.is_some()),
            ("--line-widths", self.line_widths.is_some()),
            ("--max-minutes", self.max_minutes.is_some()),
        ]
        .into_iter()
        .filter_map(|(flag, given)| given.then_some(flag))
        .collect();
        let mut note = format!(
            "--quick: {QUICK_SIZE}, the empty workload, line widths {}, at most {QUICK_MINUTES} min",
            QUICK_LINE_WIDTHS.map(|w| w.to_string()).join(",")
        );
        if !given.is_empty() {
            note += &format!("; {} given: used instead", given.join(", "));
        }
        note
    }

    /// The plan at `width` x `height`; a preset of `--quick` never replaces a
    /// value given on the command line.
    pub fn plan(&self, width: u32, height: u32) -> Result<SyncPlan, ExperimentError> {
        let invalid = |text: &str| Err(ExperimentError::Invalid(text.to_string()));
        let strategies: Vec<SyncStrategy> = parse_list("--strategies", &self.strategies)?;
        if let Some(racy) = strategies.iter().find(|s| s.is_racy()) {
            return Err(ExperimentError::Invalid(format!(
                "--strategies: {} is the baseline (no barriers), measured in every run; leave it out",
                racy.name()
            )));
        }
        let workloads: Vec<Workload> = match &self.workloads {
            Some(names) => parse_list("--workloads", names)?,
            None if self.quick => vec![Workload::Empty],
            None => Workload::ALL.to_vec(),
        };
        let positive = |v: f64| v.is_finite() && v > 0.0;
        if !positive(self.target_ci) || !(positive(self.target_ci_us) || self.target_ci_us == 0.0) {
            return invalid(
                "--target-ci and --target-ci-us: give a fraction above 0 (e.g. 0.25) and microseconds (e.g. 3)",
            );
        }
        let minutes = self.max_minutes.unwrap_or(if self.quick { QUICK_MINUTES } else { DEFAULT_MINUTES });
        if !(minutes > 0.0 && minutes.is_finite()) {
            return invalid("--max-minutes: give minutes above 0, e.g. 10");
        }
        let line_widths = match &self.line_widths {
            Some(given) => given.clone(),
            None if self.quick => QUICK_LINE_WIDTHS.to_vec(),
            None => DEFAULT_LINE_WIDTHS.to_vec(),
        };
        let seed = self.seed.unwrap_or_else(Protocol::seed_from_clock);
        let protocol = Protocol::new(self.warm_up, self.repeat, self.max_rounds, seed)
            .map_err(|e| ExperimentError::Invalid(format!("--repeat: {e}")))?;
        Ok(SyncPlan {
            width,
            height,
            strategies,
            line_widths,
            workloads,
            line_timestamps: self.line_timestamps,
            protocol,
            precision: Precision { relative: self.target_ci, absolute_us: self.target_ci_us },
            time_budget: Some(Duration::from_secs_f64(minutes * 60.0)),
            min_run: MIN_RUN,
        })
    }
}
