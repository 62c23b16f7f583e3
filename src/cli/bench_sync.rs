//! `sweeplab bench sync`: what each way of synchronizing the IPSVI sweep costs.

use super::args::BenchSyncArgs;
use super::render_cmd::{write_json, PROFILER_CAPACITY};
use super::{bench_args, scene_args, session};
use anyhow::Context as _;
use std::process::ExitCode;
use sweeplab::bench::{
    ipsvi_frame, median, plot_error_vs_time, plot_histogram, plot_lines, AxisScale, BenchRow, BenchTable, Chart,
    Distribution, Harness, Measurement, OutFolder, ProfiledFrame, Progress, Series,
};
use sweeplab::ipsvi::renderer::{plans, IpsviRenderer};
use sweeplab::ipsvi::{IpsviSettings, SyncStrategy};
use sweeplab::linear_image::LinearImage;
use sweeplab::metrics::compare;
use sweeplab::render::GpuScene;
use sweeplab::vk::{Context, Profiler};

/// The `strategy` of the baseline rows: each line width's frame with no
/// synchronization between its blocks (strategy `racy`): the same dispatches,
/// the same work, so what a strategy adds over it is what it costs. (The
/// earlier baseline, all of a sweep's lines in one dispatch, did different
/// work and gave negative overheads.)
pub const BASELINE: &str = "no-barriers";

/// What a strategy costs per line over the baseline of its line width, us.
fn per_line_overhead_us(strategy_ms: f64, baseline_ms: f64, lines: u32) -> f64 {
    (strategy_ms - baseline_ms) * 1e3 / lines.max(1) as f64
}

/// The baseline frames have no barriers, so synchronization validation reports
/// their hazards by design: those are dropped (and counted in the row); any
/// other validation message is an error.
fn drop_hazards_by_design(ctx: &Context) -> anyhow::Result<usize> {
    let messages = ctx.take_validation_messages();
    let (hazards, other): (Vec<String>, Vec<String>) = messages.into_iter().partition(|m| m.contains("SYNC-HAZARD"));
    if !other.is_empty() {
        anyhow::bail!("validation reported the no-barriers baseline: {}", other.join("\n"));
    }
    Ok(hazards.len())
}

/// Median GPU time of the harness's frames on one renderer; the last frame's
/// image and profile.
fn frames(
    ctx: &Context,
    gpu: &GpuScene,
    s: &IpsviSettings,
    size: u32,
    profiler: &mut Profiler,
    harness: &Harness,
) -> anyhow::Result<Measurement<ProfiledFrame>> {
    // One renderer for all frames: the secondary strategy replays what it recorded.
    let mut renderer = IpsviRenderer::new(gpu, s, size, size)?;
    Ok(harness.measure(|| ipsvi_frame(ctx, &mut renderer, profiler, s.sync))?)
}

pub fn run(args: &BenchSyncArgs) -> anyhow::Result<ExitCode> {
    let strategies: Vec<SyncStrategy> = args
        .strategies
        .iter()
        .map(|s| s.parse().map_err(|e: String| anyhow::anyhow!("--strategies: {e}")))
        .collect::<Result<_, _>>()?;
    // One untimed frame first: llvmpipe compiles shader variants on first use.
    let harness = session::harness(1, args.repeat)?;
    bench_args::check_sizes("--sizes", &args.sizes)?;
    let scene = scene_args::load(&args.scene)?;
    let base = scene.settings.ipsvi.clone();
    let line_widths: Vec<IpsviSettings> =
        args.line_widths.iter().map(|&line_width| IpsviSettings { line_width, ..base.clone() }).collect();
    bench_args::check_ipsvi("--line-widths", &line_widths)?;
    let out_folder = OutFolder::prepare(&args.out)?;
    let ctx = session::open(&args.gpu)?;
    let gpu = GpuScene::upload_with(&ctx, &scene, session::volume_texels(&args.gpu)).context("uploading the scene")?;
    let mut profiler = Profiler::new(&ctx, PROFILER_CAPACITY)?;
    let steps = args.sizes.len() * args.line_widths.len() * (1 + strategies.len());
    let mut progress = Progress::new(steps);
    let mut table = BenchTable::new();
    let largest = args.sizes.iter().copied().max().unwrap_or(0);
    for &size in &args.sizes {
        for &lw in &args.line_widths {
            // The equal-work baseline: this line width's frame, the same line
            // dispatches in the sweep's order, with nothing between blocks.
            progress.start_step(&format!("{size}x{size} lw={lw} {BASELINE} baseline"));
            let baseline_settings = IpsviSettings { line_width: lw, sync: SyncStrategy::Racy, ..base.clone() };
            let baseline = frames(&ctx, &gpu, &baseline_settings, size, &mut profiler, &harness)?;
            let hazards = drop_hazards_by_design(&ctx)?;
            let baseline_ms = baseline.median();
            progress.finish_step();
            let lines: u32 = plans(&gpu, &baseline_settings, size, size).iter().map(|p| p.lines()).sum();
            let mut row = BenchRow::new();
            row.set("strategy", BASELINE).set("racy", true).set("line_width", lw).set("width", size);
            row.set("height", size).set("lines", lines).set("dispatches", baseline.last.frame.dispatches);
            row.set("gpu_ms", baseline_ms);
            if ctx.validation_enabled() {
                row.set("hazards_ignored", hazards);
            }
            table.push(row);
            let mut expected: Option<LinearImage> = None;
            for &strategy in &strategies {
                progress.start_step(&format!("{size}x{size} lw={lw} {}", strategy.name()));
                let s = IpsviSettings { line_width: lw, sync: strategy, ..base.clone() };
                let lines: u32 = plans(&gpu, &s, size, size).iter().map(|p| p.lines()).sum();
                let timed = frames(&ctx, &gpu, &s, size, &mut profiler, &harness)?;
                let timed_ms = timed.median();
                let timed = timed.last.frame;
                // The same frame once more with a timestamp around every dispatch.
                profiler.set_detail(true);
                let detailed = frames(&ctx, &gpu, &s, size, &mut profiler, &Harness::once_after(0))?;
                profiler.set_detail(false);
                progress.finish_step();
                let (detailed_ms, detailed) = (detailed.median(), detailed.last.profile);
                let timeline = detailed.timeline("ipsvi_line");
                if strategy == SyncStrategy::BarrierGlobal {
                    expected = Some(timed.image.clone());
                }
                let rmse = match &expected {
                    Some(e) => compare(&timed.image, e).map(|c| c.rmse).unwrap_or(f64::NAN),
                    None => f64::NAN,
                };
                let mut row = BenchRow::new();
                row.set("strategy", strategy.name()).set("racy", strategy.is_racy()).set("line_width", lw);
                row.set("width", size).set("height", size).set("lines", lines).set("dispatches", timed.dispatches);
                row.set("gpu_ms", timed_ms);
                row.set("per_line_overhead_us", per_line_overhead_us(timed_ms, baseline_ms, lines));
                row.set("rmse", rmse);
                row.set("gpu_ms_with_line_timestamps", detailed_ms);
                row.set("timestamp_perturbation_ms", detailed_ms - timed_ms);
                // Replayed secondary buffers carry no per-line timestamps: those
                // columns stay blank rather than 0 or NaN.
                if !timeline.durations_us.is_empty() {
                    row.set("inside_dispatches_ms", timeline.inside_ms).set("gaps_ms", timeline.gap_ms);
                    row.set("median_line_us", median(&timeline.durations_us))
                        .set("median_gap_us", median(&timeline.gaps_us));
                }
                table.push(row);
                if size == largest && lw == 1 {
                    let name = strategy.name();
                    write_json(&args.out.join(format!("trace_{name}.json")), &detailed.chrome_trace())?;
                    write_json(&args.out.join(format!("lines_{name}.json")), &serde_json::to_value(&timeline)?)?;
                    write_histogram(args, strategy, &timeline)?;
                }
            }
        }
    }
    progress.finish();
    drop(gpu);
    write_reports(args, &strategies, &table)?;
    println!("{}", table.to_markdown());
    println!("racy rows are unsynchronized: their images are undefined and only their cost is meaningful.");
    println!("wrote {}/sync.csv, sync.json, sync.md, plots and trace_<strategy>.json (Perfetto)", args.out.display());
    out_folder.finish()?;
    Ok(session::finish(&ctx))
}

fn write_reports(args: &BenchSyncArgs, strategies: &[SyncStrategy], table: &BenchTable) -> anyhow::Result<()> {
    table.write_csv(args.out.join("sync.csv"))?;
    table.write_json(args.out.join("sync.json"))?;
    std::fs::write(args.out.join("sync.md"), table.to_markdown()).context("writing sync.md")?;
    let rows = |strategy: &str, lw: u32| -> Vec<&BenchRow> {
        table
            .rows
            .iter()
            .filter(|r| {
                r.get("strategy").map(|v| v.to_string()) == Some(strategy.to_string())
                    && r.get_f64("line_width") == Some(lw as f64)
            })
            .collect()
    };
    let label = |s: &SyncStrategy| if s.is_racy() { "racy (RACY)".to_string() } else { s.name().to_string() };
    let series = |key: &str| -> Vec<Series> {
        let mut out: Vec<Series> = strategies
            .iter()
            .map(|s| {
                Series::new(
                    label(s),
                    rows(s.name(), 1)
                        .into_iter()
                        .filter_map(|r| Some((r.get_f64("width")?, r.get_f64(key)?)))
                        .collect(),
                )
            })
            .collect();
        if key == "gpu_ms" {
            out.push(Series::new(
                "no barriers (baseline)",
                rows(BASELINE, 1).into_iter().filter_map(|r| Some((r.get_f64("width")?, r.get_f64(key)?))).collect(),
            ));
        }
        out
    };
    plot_lines(
        args.out.join("sync_time_vs_size.png"),
        &Chart::new("IPSVI sweep, line width 1: GPU time", "image size (pixels per side)", "GPU time (ms)")
            .x_scale(AxisScale::Log2)
            .y_scale(AxisScale::Log10),
        &series("gpu_ms"),
    )?;
    plot_lines(
        args.out.join("sync_overhead_per_line.png"),
        &Chart::new(
            "Per-line overhead over no barriers (equal work), line width 1",
            "image size (pixels per side)",
            "us per line",
        )
        .x_scale(AxisScale::Log2),
        &series("per_line_overhead_us"),
    )?;
    let scatter: Vec<Series> = strategies
        .iter()
        .map(|s| {
            let pts = table.points(|r| r.text("strategy") == s.name(), "gpu_ms", "rmse");
            Series::new(label(s), pts.into_iter().map(|(t, e)| (t, e.max(1e-9))).collect())
        })
        .collect();
    plot_error_vs_time(
        args.out.join("sync_error_vs_time.png"),
        &Chart::new("Error against barrier-global, all runs", "GPU time (ms)", "RMSE (floor 1e-9)")
            .x_scale(AxisScale::Log10)
            .y_scale(AxisScale::Log10),
        &scatter,
    )?;
    Ok(())
}

/// Histogram (log-spaced bins) of per-line dispatch times and of the gaps between
/// consecutive dispatches, one chart (PNG and SVG) per strategy.
fn write_histogram(
    args: &BenchSyncArgs,
    strategy: SyncStrategy,
    t: &sweeplab::vk::ScopeTimeline,
) -> anyhow::Result<()> {
    if !t.durations_us.iter().chain(&t.gaps_us).any(|v| *v > 0.0) {
        return Ok(());
    }
    let label = if strategy.is_racy() { format!("{} (RACY)", strategy.name()) } else { strategy.name().to_string() };
    plot_histogram(
        args.out.join(format!("lines_{}.png", strategy.name())),
        &Chart::new(format!("{label}: per-line times, one frame"), "microseconds", "lines").x_scale(AxisScale::Log10),
        &[
            Distribution::new("inside the dispatch", t.durations_us.clone()),
            Distribution::new("gap to the next", t.gaps_us.clone()),
        ],
        24,
    )?;
    Ok(())
}
