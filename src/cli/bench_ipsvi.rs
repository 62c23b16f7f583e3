//! `sweeplab bench ipsvi`: its flags as the study's plan
//! (`sweeplab::bench::experiments::ipsvi`, or `ipsvi::breakdown` with
//! `--breakdown`), run by the one runner.

use super::args::BenchIpsviArgs;
use super::{experiment_runner, scene_args, session};
use std::process::ExitCode;
use sweeplab::bench::experiments::ipsvi::breakdown::BreakdownPlan;
use sweeplab::bench::experiments::ipsvi::{BreakdownExperiment, IpsviExperiment, IpsviPlan, DEFAULT_GROUP_BYTES};
use sweeplab::bench::Interleaved;

pub fn run(args: &BenchIpsviArgs) -> anyhow::Result<ExitCode> {
    let scene = scene_args::load(&args.scene)?;
    if args.breakdown {
        let plan = BreakdownPlan {
            sizes: args.sizes.clone(),
            line_widths: args.line_widths.clone(),
            interleaved: rounds(args)?,
            volume_texels: session::volume_texels(&args.gpu),
            kernels: args.kernels.clone(),
        };
        return experiment_runner::run(&BreakdownExperiment { plan, scene }, &args.out, &args.gpu);
    }
    let plan = IpsviPlan {
        sizes: args.sizes.clone(),
        line_widths: args.line_widths.clone(),
        cache_sizes: args.cache_sizes.clone(),
        one_at_a_time: args.one_at_a_time,
        half_angle_slices: args.half_angle_slices.clone(),
        interleaved: rounds(args)?,
        volume_texels: session::volume_texels(&args.gpu),
        group_bytes: DEFAULT_GROUP_BYTES,
        kernels: args.kernels.clone(),
    };
    experiment_runner::run(&IpsviExperiment { plan, scene }, &args.out, &args.gpu)
}

/// The shared rounds of `args`, within --max-minutes when given.
fn rounds(args: &BenchIpsviArgs) -> anyhow::Result<Interleaved> {
    let rounds = session::interleaved(args.repeat, &args.rounds)?;
    let Some(minutes) = args.max_minutes else { return Ok(rounds) };
    rounds.within_minutes(minutes).map_err(|e| anyhow::anyhow!("--max-minutes: {e}"))
}
