//! `bench sync` as it runs: its files rewritten after every round (so an
//! interrupted run leaves the rows measured so far), each trace written as it
//! is taken, and one line on stderr per round saying where the rounds stand
//! and how long is left.

use super::budget::LeftOut;
use super::{files, Eta, SyncObserver, SyncReport, Workload};
use crate::bench::estimate::MIN_SAMPLES;
use crate::bench::experiments::ExperimentError;
use crate::bench::progress::format_duration;
use std::path::Path;
use std::time::Duration;

/// Writes the files after every round and shows where the rounds stand.
pub struct RoundFiles<'a> {
    out: &'a Path,
    configurations: usize,
}

impl<'a> RoundFiles<'a> {
    /// Files into `out`.
    pub fn new(out: &'a Path) -> Self {
        RoundFiles { out, configurations: 0 }
    }
}

impl SyncObserver for RoundFiles<'_> {
    fn warm_up(&mut self, workload: Workload, configurations: usize) {
        eprintln!(
            "{} workload: {configurations} configurations; a warm-up round, then shuffled timed rounds",
            workload.name()
        );
    }

    fn planned(&mut self, workload: Workload, configurations: usize, fewest: Duration, left_out: Option<&LeftOut>) {
        let (name, about) = (workload.name(), format_duration(fewest));
        self.configurations = configurations;
        left_out.inspect(|left| eprintln!("warning: {name} workload: {}", left.describe()));
        eprintln!("{name} workload: {configurations} configurations; its fewest rounds take about {about}");
    }

    fn round(&mut self, report: &SyncReport, eta: Eta) -> Result<(), ExperimentError> {
        files::write(report, self.out)?;
        let state = if eta.round >= MIN_SAMPLES {
            if report.precise_in(eta.workload) {
                "intervals as narrow as asked".to_string()
            } else {
                "intervals not yet as narrow as asked".to_string()
            }
        } else {
            format!("intervals from round {}", MIN_SAMPLES)
        };
        eprintln!(
            "{} workload: round {} done in {} ({} configurations); {state}; at most {} more round(s), about {} left",
            eta.workload.name(),
            eta.round,
            format_duration(eta.last_round),
            self.configurations,
            eta.rounds_left,
            format_duration(eta.time_left)
        );
        Ok(())
    }

    fn trace(&mut self, file: &str, trace: &serde_json::Value) -> Result<(), ExperimentError> {
        files::write_json(&self.out.join(file), trace)?;
        Ok(())
    }
}
