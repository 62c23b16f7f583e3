//! `sweeplab bench sync`: arguments to a [`SyncPlan`], the study
//! (`sweeplab::bench::experiments::sync`, its files written after every round
//! by `sync::progress`), and the verdict.

use super::args::BenchSyncArgs;
use super::{scene_args, session};
use anyhow::Context as _;
use std::process::ExitCode;
use std::time::Duration;
use sweeplab::bench::experiments::sync::progress::RoundFiles;
use sweeplab::bench::experiments::sync::{self, files, SyncPlan, Workload};
use sweeplab::bench::{OutFolder, Protocol, RunInfo};
use sweeplab::ipsvi::IpsviSettings;
use sweeplab::ipsvi::SyncStrategy;
use sweeplab::render::GpuScene;

/// `--quick`: about a minute on lavapipe.
const QUICK_SIZE: &str = "64x64";
const QUICK_LINE_WIDTHS: [u32; 4] = [1, 4, 16, 32];
const QUICK_MINUTES: f64 = 1.5;
const DEFAULT_SIZE: &str = "256x256";

fn parse_list<T: std::str::FromStr<Err = String>>(flag: &str, values: &[String]) -> anyhow::Result<Vec<T>> {
    values.iter().map(|s| s.trim().parse().map_err(|e: String| anyhow::anyhow!("{flag}: {e}"))).collect()
}

fn plan(args: &BenchSyncArgs, width: u32, height: u32) -> anyhow::Result<SyncPlan> {
    let strategies: Vec<SyncStrategy> = parse_list("--strategies", &args.strategies)?;
    if let Some(racy) = strategies.iter().find(|s| s.is_racy()) {
        anyhow::bail!(
            "--strategies: {} is the baseline (no barriers), measured in every run; leave it out",
            racy.name()
        );
    }
    let workloads: Vec<Workload> = match &args.workloads {
        Some(names) => parse_list("--workloads", names)?,
        None if args.quick => vec![Workload::Empty],
        None => Workload::ALL.to_vec(),
    };
    let positive = |v: f64| v.is_finite() && v > 0.0;
    if !positive(args.target_ci) || !(positive(args.target_ci_us) || args.target_ci_us == 0.0) {
        anyhow::bail!("--target-ci and --target-ci-us: give a fraction above 0 (e.g. 0.25) and microseconds (e.g. 3)");
    }
    if !(args.max_minutes > 0.0 && args.max_minutes.is_finite()) {
        anyhow::bail!("--max-minutes: give minutes above 0, e.g. 10");
    }
    let minutes = if args.quick { args.max_minutes.min(QUICK_MINUTES) } else { args.max_minutes };
    let seed = args.seed.unwrap_or_else(Protocol::seed_from_clock);
    let protocol = Protocol::new(args.warm_up, args.min_rounds, args.max_rounds, seed).context("--min-rounds")?;
    Ok(SyncPlan {
        width,
        height,
        strategies,
        line_widths: if args.quick { QUICK_LINE_WIDTHS.to_vec() } else { args.line_widths.clone() },
        workloads,
        line_timestamps: !args.no_line_timestamps,
        protocol,
        precision: sync::Precision { relative: args.target_ci, absolute_us: args.target_ci_us },
        time_budget: Some(Duration::from_secs_f64(minutes * 60.0)),
        min_run: sync::MIN_RUN,
    })
}

pub fn run(args: &BenchSyncArgs) -> anyhow::Result<ExitCode> {
    let mut scene_args = args.scene.clone();
    if scene_args.size.is_none() {
        scene_args.size = Some(if args.quick { QUICK_SIZE } else { DEFAULT_SIZE }.to_string());
    }
    let scene = scene_args::load(&scene_args)?;
    let (width, height) = (scene.render.width, scene.render.height);
    let plan = plan(args, width, height)?;
    sync::check(&plan, &scene.settings.get::<IpsviSettings>())?;
    let out_folder = OutFolder::prepare(&args.out)?;
    let ctx = session::open(&args.gpu)?;
    let gpu = GpuScene::upload_with(&ctx, &scene, session::volume_texels(&args.gpu)).context("uploading the scene")?;
    let volume = scene_args.volume.as_ref().or(scene_args.scene.as_ref()).map(|p| p.display().to_string());
    let run_info = RunInfo::collect(&ctx)
        .input("scene", volume.unwrap_or_else(|| "embedded default scene".into()))
        .input("size", format!("{width}x{height}"))
        .input("line_widths", format!("{:?}", plan.line_widths))
        .input("workloads", plan.workloads.iter().map(|w| w.name()).collect::<Vec<_>>().join(","))
        .input("validation", ctx.validation_enabled());
    let mut files = RoundFiles::new(&args.out);
    let report = sync::run(&ctx, &gpu, &scene.settings.get::<IpsviSettings>(), &plan, run_info, &mut files)?;
    files::write(&report, &args.out)?;
    files::write_charts(&report, &args.out)?;
    drop(gpu);
    println!("{}", report.verdict().join("\n"));
    if ctx.validation_enabled() {
        println!("(validation on: these times include the layers' work and say nothing about the device)");
    }
    println!(
        "wrote {}/sync.md (verdict and tables), sync.json, sync.csv, sync_calibration.csv, \
         sync_configurations.csv, trace_<workload>_<strategy>.json (Perfetto), sync_frames_<workload>.png, \
         sync_cost_<workload>.png, sync_calibration.png, sync_gaps_<workload>.png (and .svg)",
        args.out.display()
    );
    out_folder.finish()?;
    Ok(session::finish(&ctx))
}
