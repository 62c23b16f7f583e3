//! `bench sync` in the one shape the CLI runs ([`Experiment`]): the scene
//! uploaded once, the files rewritten after every round ([`RoundFiles`]), the
//! tables and charts at the end, the verdict on the terminal.

use super::progress::RoundFiles;
use super::{files, plan, SyncPlan, SyncReport};
use crate::bench::{Experiment, ExperimentError, OutFolder, RunInfo};
use crate::render::{GpuScene, VolumeTexels};
use crate::scene::Scene;
use crate::techniques::ipsvi::line_kernel;
use crate::techniques::ipsvi::IpsviSettings;
use crate::vk::subgroups::SubgroupSupport;
use crate::vk::Context;

/// The study of `plan` on `scene` ([`super::run`]).
pub struct SyncExperiment {
    pub plan: SyncPlan,
    pub scene: Scene,
    pub volume_texels: VolumeTexels,
    /// The scene or volume file the run names (`None`: the embedded default scene).
    pub scene_file: Option<String>,
}

impl Experiment for SyncExperiment {
    type Report = SyncReport;
    const FOLDER: &'static str = "bench-sync";

    fn check(&self) -> Result<(), ExperimentError> {
        plan::check(&self.plan, &self.scene.settings.get::<IpsviSettings>())
    }

    fn run(&self, ctx: &Context, run: RunInfo, out: &OutFolder) -> Result<SyncReport, ExperimentError> {
        let gpu = GpuScene::upload_with(ctx, &self.scene, self.volume_texels)?;
        let plan = &self.plan;
        let run = run
            .input("scene", self.scene_file.clone().unwrap_or_else(|| "embedded default scene".into()))
            .input("size", format!("{}x{}", plan.width, plan.height))
            .input("line_widths", format!("{:?}", plan.line_widths))
            .input("workloads", plan.workloads.iter().map(|w| w.name()).collect::<Vec<_>>().join(","))
            .input("validation", ctx.validation_enabled());
        let settings = self.scene.settings.get::<IpsviSettings>();
        // The kernel the sweep's lines run (`auto` resolved for the device): a
        // line's latency, and so what a barrier serializes, depends on it. The
        // chain workload's lines are its own shader.
        let run = if plan.workloads.iter().any(|&w| w != super::Workload::Chain) {
            let kernel = line_kernel::choose(&settings, &ctx.info.device_type, &SubgroupSupport::of(ctx))
                .map_err(ExperimentError::Invalid)?;
            run.input(super::LINE_KERNEL_INPUT, kernel.label())
        } else {
            run
        };
        let mut round_files = RoundFiles::new(out.path());
        let report = super::run(ctx, &gpu, &settings, plan, run, &mut round_files)?;
        files::write(&report, out.path())?;
        files::write_charts(&report, out.path())?;
        Ok(report)
    }

    fn print_summary(&self, report: &SyncReport) {
        println!("{}", report.verdict().join("\n"));
    }

    fn left_out(&self, report: &SyncReport) -> Option<String> {
        report.left_out_summary()
    }
}
