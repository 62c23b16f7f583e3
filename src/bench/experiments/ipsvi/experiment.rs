//! `bench ipsvi` and `bench ipsvi --breakdown` in the one shape the CLI runs
//! ([`Experiment`]): the plan and the scene it measures.

use super::breakdown::{self, BreakdownPlan, BreakdownReport};
use super::{IpsviPlan, IpsviReport};
use crate::bench::{Experiment, ExperimentError, OutFolder, RunInfo};
use crate::scene::Scene;
use crate::techniques::ipsvi::IpsviSettings;
use crate::vk::{Context, Profiler};

/// The error-against-time grid of [`super::run`].
pub struct IpsviExperiment {
    pub plan: IpsviPlan,
    pub scene: Scene,
}

impl Experiment for IpsviExperiment {
    type Report = IpsviReport;
    const FOLDER: &'static str = "bench-ipsvi";

    fn check(&self) -> Result<(), ExperimentError> {
        self.plan.check()?;
        self.plan.configurations(&self.scene.settings.get::<IpsviSettings>()).map(drop)
    }

    fn run(&self, ctx: &Context, run: RunInfo, out: &OutFolder) -> Result<IpsviReport, ExperimentError> {
        super::run(ctx, &self.scene, &self.plan, run, out, Profiler::FRAME_CAPACITY)
    }

    fn print_summary(&self, report: &IpsviReport) {
        report.print_summary();
    }
}

/// Where one frame's time goes ([`breakdown::run`]).
pub struct BreakdownExperiment {
    pub plan: BreakdownPlan,
    pub scene: Scene,
}

impl Experiment for BreakdownExperiment {
    type Report = BreakdownReport;
    const FOLDER: &'static str = "bench-ipsvi";

    fn check(&self) -> Result<(), ExperimentError> {
        self.plan.check(&self.scene.settings.get::<IpsviSettings>())
    }

    fn run(&self, ctx: &Context, run: RunInfo, out: &OutFolder) -> Result<BreakdownReport, ExperimentError> {
        breakdown::run(ctx, &self.scene, &self.plan, run, out, Profiler::FRAME_CAPACITY)
    }

    fn print_summary(&self, report: &BreakdownReport) {
        report.print_summary();
    }
}
