//! `sweeplab bench sync`: its flags as `sync::SyncOptions`, turned into the
//! study's plan at the scene's size, run by the one runner
//! (`sweeplab::bench::experiments::sync`).

use super::args::BenchSyncArgs;
use super::{experiment_runner, scene_args, session};
use std::process::ExitCode;
use sweeplab::bench::experiments::sync::{SyncExperiment, SyncOptions};

/// The flags as the library's options.
fn options(args: &BenchSyncArgs) -> SyncOptions {
    SyncOptions {
        strategies: args.strategies.clone(),
        workloads: args.workloads.clone(),
        line_widths: args.line_widths.clone(),
        size_given: args.scene.size.is_some(),
        max_minutes: args.max_minutes,
        quick: args.quick,
        warm_up: args.warm_up,
        repeat: args.repeat,
        max_rounds: args.max_rounds,
        target_ci: args.target_ci,
        target_ci_us: args.target_ci_us,
        seed: args.seed,
        line_timestamps: !args.no_line_timestamps,
    }
}

pub fn run(args: &BenchSyncArgs) -> anyhow::Result<ExitCode> {
    let options = options(args);
    if args.quick {
        eprintln!("{}", options.quick_note());
    }
    let mut scene_args = args.scene.clone();
    if scene_args.size.is_none() {
        scene_args.size = Some(options.default_size().to_string());
    }
    let scene = scene_args::load(&scene_args)?;
    let experiment = SyncExperiment {
        plan: options.plan(scene.render.width, scene.render.height)?,
        volume_texels: session::volume_texels(&args.gpu),
        scene_file: scene_args.volume.as_ref().or(scene_args.scene.as_ref()).map(|p| p.display().to_string()),
        scene,
    };
    experiment_runner::run(&experiment, &args.out, &args.gpu)
}
