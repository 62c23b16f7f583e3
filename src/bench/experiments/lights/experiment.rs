//! `bench lights` in the one shape the CLI runs ([`Experiment`]).

use super::{LightsPlan, Report};
use crate::bench::{Experiment, ExperimentError, OutFolder, RunInfo};
use crate::scene::Scene;
use crate::vk::{Context, Profiler};

/// Every part of `bench lights` on `scene` ([`super::run`]).
pub struct LightsExperiment {
    pub plan: LightsPlan,
    pub scene: Scene,
}

impl Experiment for LightsExperiment {
    type Report = Report;
    const FOLDER: &'static str = "bench-lights";

    fn check(&self) -> Result<(), ExperimentError> {
        self.plan.check()
    }

    fn run(&self, ctx: &Context, run: RunInfo, out: &OutFolder) -> Result<Report, ExperimentError> {
        super::run(ctx, &self.scene, &self.plan, run, out, Profiler::FRAME_CAPACITY)
    }

    fn print_summary(&self, report: &Report) {
        report.print_summary();
    }
}
