//! One shape for every study a `sweeplab bench` command runs. A study is its
//! plan (what the flags asked for, the scene) as a value of a type that
//! implements [`Experiment`]: checked before a device is opened, run on a
//! context while it saves what it measures into the run's output folder,
//! then summed up on the terminal. The CLI runs every study with one runner
//! (`src/cli/experiment_runner.rs`), which owns the folder, the context,
//! the validation verdict and the list of files written; a study's
//! `experiment.rs` (in its folder under `experiments/`) is the only place
//! that knows what the study writes and prints.

use super::{ExperimentError, OutFolder, RunInfo};
use crate::vk::Context;

pub trait Experiment {
    /// What a run measured, as the summary and the verdicts read it.
    type Report;

    /// The folder a run without `--out-dir` goes under (a new dated folder
    /// inside it per run), e.g. `bench-sync`.
    const FOLDER: &'static str;

    /// Everything that can be refused before a device is opened (flags,
    /// settings, sizes): a run that would fail on its first frame fails here,
    /// without a context or an output folder.
    fn check(&self) -> Result<(), ExperimentError>;

    /// Measures on `ctx`. `run` names the device, build and command line;
    /// the study adds its inputs. Every file of the run goes into `out`
    /// (rows as they are measured, so an interrupted run keeps them; reports
    /// and charts at the end).
    fn run(&self, ctx: &Context, run: RunInfo, out: &OutFolder) -> Result<Self::Report, ExperimentError>;

    /// What the terminal shows of `report` (stdout); the files hold the rest.
    fn print_summary(&self, report: &Self::Report);

    /// Why a run that ended is partial: what a time budget left out.
    fn left_out(&self, _report: &Self::Report) -> Option<String> {
        None
    }

    /// What the study found failing (e.g. stability cells): the run's
    /// results stand, and the command exits with 1.
    fn failures(&self, _report: &Self::Report) -> Option<String> {
        None
    }
}
