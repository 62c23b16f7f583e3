//! The one runner of every `sweeplab bench` study ([`Experiment`]): the
//! study checked before anything opens, its output folder (new per run, or
//! `--out-dir`), the Vulkan context, the run with an error kept in the
//! folder's PARTIAL marker, the summary, the files the run wrote (read from
//! the folder), the validation verdict and the exit code.

use super::args::{GpuArgs, OutDirArgs};
use super::session;
use std::process::ExitCode;
use sweeplab::bench::Experiment;

pub fn run<E: Experiment>(experiment: &E, out: &OutDirArgs, gpu: &GpuArgs) -> anyhow::Result<ExitCode> {
    experiment.check()?;
    let out_folder = session::out_folder(out, E::FOLDER)?;
    let ctx = session::open(gpu)?;
    let measured = experiment.run(&ctx, session::run_info(&ctx), &out_folder);
    let report = session::watch(&out_folder, measured)?;
    experiment.print_summary(&report);
    if ctx.validation_enabled() {
        println!("(validation on: these times include the layers' work and say nothing about the device)");
    }
    // A time budget that left configurations out ends a partial run.
    session::finish_out(out_folder, experiment.left_out(&report).as_deref())?;
    let code = session::finish(&ctx);
    if let Some(failed) = experiment.failures(&report) {
        eprintln!("{failed} FAILED");
        return Ok(ExitCode::from(1));
    }
    Ok(code)
}
