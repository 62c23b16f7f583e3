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
use sweeplab::bench::{Protocol, RunInfo};
use sweeplab::ipsvi::IpsviSettings;
use sweeplab::ipsvi::SyncStrategy;
use sweeplab::render::GpuScene;

/// `--quick`: about a minute on lavapipe.
const QUICK_SIZE: &str = "64x64";
const QUICK_LINE_WIDTHS: [u32; 4] = [1, 4, 16, 32];
const QUICK_MINUTES: f64 = 1.5;
const DEFAULT_SIZE: &str = "256x256";
const DEFAULT_LINE_WIDTHS: [u32; 6] = [1, 2, 4, 8, 16, 32];
const DEFAULT_MINUTES: f64 = 10.0;

/// What `--quick` sets, and which of its presets the command line gave
/// itself (those win): "--quick: 64x64, the empty workload, line widths
/// 1,4,16,32, at most 1.5 min; --line-widths 1,2 given: used instead".
fn quick_note(args: &BenchSyncArgs) -> String {
    let given: Vec<&str> = [
        ("--size", args.scene.size.is_some()),
        ("--workloads", args.workloads.is_some()),
        ("--line-widths", args.line_widths.is_some()),
        ("--max-minutes", args.max_minutes.is_some()),
    ]
    .into_iter()
    .filter_map(|(flag, given)| given.then_some(flag))
    .collect();
    let mut note = format!(
        "--quick: {QUICK_SIZE}, the empty workload, line widths {}, at most {QUICK_MINUTES} min",
        QUICK_LINE_WIDTHS.map(|w| w.to_string()).join(",")
    );
    if !given.is_empty() {
        note += &format!("; {} given: used instead", given.join(", "));
    }
    note
}

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
    // A preset of --quick never replaces a value given on the command line.
    let minutes = args.max_minutes.unwrap_or(if args.quick { QUICK_MINUTES } else { DEFAULT_MINUTES });
    if !(minutes > 0.0 && minutes.is_finite()) {
        anyhow::bail!("--max-minutes: give minutes above 0, e.g. 10");
    }
    let line_widths = match &args.line_widths {
        Some(given) => given.clone(),
        None if args.quick => QUICK_LINE_WIDTHS.to_vec(),
        None => DEFAULT_LINE_WIDTHS.to_vec(),
    };
    let seed = args.seed.unwrap_or_else(Protocol::seed_from_clock);
    let protocol = Protocol::new(args.warm_up, args.repeat, args.max_rounds, seed).context("--repeat")?;
    Ok(SyncPlan {
        width,
        height,
        strategies,
        line_widths,
        workloads,
        line_timestamps: !args.no_line_timestamps,
        protocol,
        precision: sync::Precision { relative: args.target_ci, absolute_us: args.target_ci_us },
        time_budget: Some(Duration::from_secs_f64(minutes * 60.0)),
        min_run: sync::MIN_RUN,
    })
}

pub fn run(args: &BenchSyncArgs) -> anyhow::Result<ExitCode> {
    if args.quick {
        eprintln!("{}", quick_note(args));
    }
    let mut scene_args = args.scene.clone();
    if scene_args.size.is_none() {
        scene_args.size = Some(if args.quick { QUICK_SIZE } else { DEFAULT_SIZE }.to_string());
    }
    let scene = scene_args::load(&scene_args)?;
    let (width, height) = (scene.render.width, scene.render.height);
    let plan = plan(args, width, height)?;
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
    println!(
        "wrote {}/sync.md (verdict and tables), sync.json, sync.csv, sync_calibration.csv, \
         sync_configurations.csv, trace_<workload>_<strategy>.json (Perfetto), sync_frames_<workload>.png, \
         sync_cost_<workload>.png, sync_calibration.png, sync_gaps_<workload>.png (and .svg)",
        out.display()
    );
    // A time budget that left configurations out ends a partial run.
    let left_out: Vec<String> = report
        .workloads
        .iter()
        .filter_map(|w| w.left_out.as_ref().map(|l| format!("{} workload: {}", w.workload.name(), l.describe())))
        .collect();
    if left_out.is_empty() {
        out_folder.finish()?;
    } else {
        eprintln!("partial: {} (see {}/PARTIAL)", left_out.join("; "), out.display());
        out_folder.finish_partial(&left_out.join("; "))?;
    }
    Ok(session::finish(&ctx))
}
