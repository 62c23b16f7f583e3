//! `bench stability` in the one shape the CLI runs ([`Experiment`]): a cell
//! or convergence row that fails fails the command, after its files are written.

use super::bench::{self, StabilityPlan, StabilityReport};
use crate::bench::{Experiment, ExperimentError, OutFolder, RunInfo};
use crate::plural::count;
use crate::vk::Context;

/// Every case x technique of `plan`, then each technique's convergence ([`bench::run`]).
pub struct StabilityExperiment {
    pub plan: StabilityPlan,
}

impl Experiment for StabilityExperiment {
    type Report = StabilityReport;
    const FOLDER: &'static str = "bench-stability";

    /// The plan was checked when it was chosen (`StabilityPlan::choose`).
    fn check(&self) -> Result<(), ExperimentError> {
        Ok(())
    }

    fn run(&self, ctx: &Context, run: RunInfo, out: &OutFolder) -> Result<StabilityReport, ExperimentError> {
        let report = bench::run(ctx, &self.plan, run, out)?;
        report.write(out.path())?;
        Ok(report)
    }

    fn print_summary(&self, report: &StabilityReport) {
        report.print_summary();
    }

    fn failures(&self, report: &StabilityReport) -> Option<String> {
        (report.failed > 0).then(|| count(report.failed as u64, "cell or convergence row", "cells or convergence rows"))
    }
}
