//! `bench ao` in the one shape the CLI runs ([`Experiment`]).

use super::{configurations, print_summary, AoPlan, AoReport};
use crate::bench::{Experiment, ExperimentError, OutFolder, RunInfo};
use crate::scene::Scene;
use crate::techniques::ao::AoSettings;
use crate::vk::{Context, Profiler};

/// Every AO configuration of `plan` on `scene` ([`super::run`]).
pub struct AoExperiment {
    pub plan: AoPlan,
    pub scene: Scene,
}

impl Experiment for AoExperiment {
    type Report = AoReport;
    const FOLDER: &'static str = "bench-ao";

    fn check(&self) -> Result<(), ExperimentError> {
        configurations(&self.plan, &self.scene.settings.get::<AoSettings>()).map(drop)
    }

    fn run(&self, ctx: &Context, run: RunInfo, out: &OutFolder) -> Result<AoReport, ExperimentError> {
        super::run(ctx, &self.scene, &self.plan, run, out, Profiler::FRAME_CAPACITY)
    }

    fn print_summary(&self, report: &AoReport) {
        print_summary(&report.table);
    }
}
