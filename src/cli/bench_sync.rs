//! `sweeplab bench sync`: arguments to `sync::SyncOptions`, the study
//! (`sweeplab::bench::experiments::sync`, its files written after every round
//! by `sync::progress`), and the verdict.

use super::args::BenchSyncArgs;
use super::{scene_args, session};
use anyhow::Context as _;
use std::process::ExitCode;
use sweeplab::bench::experiments::sync::progress::RoundFiles;
use sweeplab::bench::experiments::sync::{self, files, SyncOptions};
use sweeplab::bench::RunInfo;
use sweeplab::render::GpuScene;
use sweeplab::techniques::ipsvi::IpsviSettings;

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
    let (width, height) = (scene.render.width, scene.render.height);
    let plan = options.plan(width, height)?;
    sync::check(&plan, &scene.settings.get::<IpsviSettings>())?;
    let out_folder = session::out_folder(&args.out, "bench-sync")?;
    let ctx = session::open(&args.gpu)?;
    let gpu = GpuScene::upload_with(&ctx, &scene, session::volume_texels(&args.gpu)).context("uploading the scene")?;
    let volume = scene_args.volume.as_ref().or(scene_args.scene.as_ref()).map(|p| p.display().to_string());
    let run_info = RunInfo::collect(&ctx)
        .input("scene", volume.unwrap_or_else(|| "embedded default scene".into()))
        .input("size", format!("{width}x{height}"))
        .input("line_widths", format!("{:?}", plan.line_widths))
        .input("workloads", plan.workloads.iter().map(|w| w.name()).collect::<Vec<_>>().join(","))
        .input("validation", ctx.validation_enabled());
    let out = out_folder.path();
    let mut files = RoundFiles::new(out);
    let measured = sync::run(&ctx, &gpu, &scene.settings.get::<IpsviSettings>(), &plan, run_info, &mut files);
    let report = session::watch(&out_folder, measured)?;
    files::write(&report, out)?;
    files::write_charts(&report, out)?;
    drop(gpu);
    println!("{}", report.verdict().join("\n"));
    if ctx.validation_enabled() {
        println!("(validation on: these times include the layers' work and say nothing about the device)");
    }
    // A time budget that left configurations out ends a partial run.
    session::finish_out(out_folder, report.left_out_summary().as_deref())?;
    Ok(session::finish(&ctx))
}
