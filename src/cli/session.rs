//! A Vulkan context for one command, and the validation verdict at its end.

use super::args::ValidateMode;
use super::args::{GpuArgs, OutDirArgs, RoundsArgs};
use anyhow::Context as _;
use std::process::ExitCode;
use std::time::Duration;
use sweeplab::bench::out_folder::OutTarget;
use sweeplab::bench::{Harness, Interleaved, OutFolder, Protocol, RunInfo};
use sweeplab::render::VolumeTexels;
use sweeplab::vk::context::BEST_PRACTICES_LAYER_ENABLES;
use sweeplab::vk::validation_verdict::ValidationVerdict;
use sweeplab::vk::{Context, ContextOptions, WaitReport, WaitReporter};

pub fn open(gpu: &GpuArgs) -> anyhow::Result<Context> {
    let options = context_options(gpu);
    if options.best_practices && std::env::var_os("VK_LAYER_ENABLES").is_none() {
        // Before any Vulkan call and before this process starts threads that read
        // the environment: the layer's vendor checks are enabled this way only.
        std::env::set_var("VK_LAYER_ENABLES", BEST_PRACTICES_LAYER_ENABLES);
    }
    let ctx = Context::new(&options).context("cannot start Vulkan")?;
    eprintln!("{}", ctx.summary());
    Ok(ctx)
}

/// The context options of `--device` and `--validate`, environment applied.
pub fn context_options(gpu: &GpuArgs) -> ContextOptions {
    ContextOptions {
        device: gpu.device.clone(),
        validate: gpu.validate.is_some(),
        best_practices: gpu.validate == Some(ValidateMode::BestPractices),
        ..Default::default()
    }
    .with_env()
}

/// A submission that runs longer than this prints that it is still running.
const LONG_WAIT: Duration = Duration::from_secs(2);

/// Long renders show progress: while the host waits for a submission that has
/// run past [`LONG_WAIT`], a line on stderr every [`LONG_WAIT`] with how long
/// and what it holds (a frame is one submission, so the device cannot say how
/// far into it it is without timestamps that would perturb it).
pub fn report_long_waits(ctx: &Context) {
    ctx.set_wait_reporter(Some(WaitReporter {
        after: LONG_WAIT,
        every: LONG_WAIT,
        report: Box::new(|r: &WaitReport| eprintln!("{}", r.progress_line())),
    }));
}

/// Prints the validation messages, if any, and turns them into a failing exit code.
pub fn finish(ctx: &Context) -> ExitCode {
    let verdict = ValidationVerdict::of(ctx.take_validation_messages());
    for line in verdict.report_lines(ctx.validation_enabled()) {
        eprintln!("{line}");
    }
    if verdict.failed() {
        ExitCode::from(2)
    } else {
        ExitCode::SUCCESS
    }
}

/// What produced a bench's results: the device of `ctx`, this host and
/// build, now, and the command line (which holds every input flag).
pub fn run_info(ctx: &Context) -> RunInfo {
    let info = RunInfo::collect(ctx);
    if let Some(note) = info.load_note() {
        eprintln!("{note}");
    }
    info
}

pub fn volume_texels(gpu: &GpuArgs) -> VolumeTexels {
    if gpu.float_volume {
        VolumeTexels::Float32
    } else {
        VolumeTexels::Native
    }
}

/// `--repeat` timed rounds of every configuration, shuffled, after a warm-up
/// round; with `--max-rounds`, more until `--target-ci` is met.
pub fn interleaved(repeat: u32, rounds: &RoundsArgs) -> anyhow::Result<Interleaved> {
    let seed = rounds.seed.unwrap_or_else(Protocol::seed_from_clock);
    if !(rounds.target_ci.is_finite() && rounds.target_ci > 0.0) {
        anyhow::bail!("--target-ci: {} is not a fraction above 0 (e.g. 0.05 for 5 %)", rounds.target_ci);
    }
    match rounds.max_rounds {
        None => Interleaved::fixed(repeat, seed).map_err(|e| anyhow::anyhow!("--repeat: {e}")),
        Some(max) => Interleaved::adaptive(1, repeat, max, rounds.target_ci, seed)
            .map_err(|e| anyhow::anyhow!("--repeat/--max-rounds: {e}")),
    }
}

/// `--repeat` timed runs after `warm_up` untimed ones; 0 repeats is refused.
pub fn harness(warm_up: u32, repeat: u32) -> anyhow::Result<Harness> {
    Harness::new(warm_up, repeat).map_err(|e| anyhow::anyhow!("--repeat: {e}"))
}

/// The output folder of `--out-dir`/`--force`, or a new one under `default`
/// (the command's own, e.g. `bench-sync`); says where the run writes.
pub fn out_folder(args: &OutDirArgs, default: &str) -> anyhow::Result<OutFolder> {
    let target = match &args.out_dir {
        Some(folder) => OutTarget::Named { folder, force: args.force },
        None => OutTarget::NewUnder(std::path::Path::new(default)),
    };
    let out = OutFolder::prepare(target)?;
    eprintln!("writing into {} (marked PARTIAL until the run ends)", out.path().display());
    Ok(out)
}

/// Passes `result` on; an error is written into the folder's PARTIAL marker
/// and the terminal says what the folder keeps.
pub fn watch<T, E: Into<anyhow::Error>>(out: &OutFolder, result: Result<T, E>) -> anyhow::Result<T> {
    let result = out.watch(result.map_err(|e| anyhow::anyhow!(super::error_report::error_text(&e.into()))));
    if result.is_err() && out.holds_results() {
        eprintln!("what was measured before the error is in {} (marked PARTIAL)", out.path().display());
    }
    result
}

/// Ends a bench's folder (its PARTIAL marker goes, or with `partial` stays and
/// says why) and lists the files the run wrote there: read from the folder,
/// so the list is what the run wrote, not what it meant to.
pub fn finish_out(out: OutFolder, partial: Option<&str>) -> anyhow::Result<()> {
    let folder = out.path().to_path_buf();
    let written = match partial {
        None => out.finish()?,
        Some(why) => {
            eprintln!("partial: {why} (see {}/PARTIAL)", folder.display());
            out.finish_partial(why)?
        }
    };
    println!("wrote into {}: {}", folder.display(), written.join(", "));
    Ok(())
}
