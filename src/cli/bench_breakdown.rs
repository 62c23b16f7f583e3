//! `sweeplab bench ipsvi --breakdown`: where the time of one IPSVI frame goes,
//! in both cache-update modes. Each step adds one part of the
//! frame to the one before; its cost is its GPU time minus the previous step's.

use super::args::BenchIpsviArgs;
use super::render_cmd::PROFILER_CAPACITY;
use super::{bench_args, scene_args, session};
use anyhow::Context as _;
use std::process::ExitCode;
use sweeplab::bench::{
    ipsvi_frame, plot_stacked_bars, technique_frame, BenchRow, BenchTable, Chart, OutFolder, Progress, StackedBar,
};
use sweeplab::ipsvi::renderer::{plans, IpsviRenderer};
use sweeplab::ipsvi::{BreakdownStep, CacheUpdate, IpsviSettings, SyncStrategy, WriteRule};
use sweeplab::render::GpuScene;
use sweeplab::techniques::Technique;
use sweeplab::vk::Profiler;

/// (step label, breakdown step, synchronization) after the single-dispatch DVR.
/// e1-e5 split the write path (f minus e) of view samples; light rays, whose
/// writes are all in their texel advance, skip them (f is then e's next step).
const STEPS: [(&str, BreakdownStep, SyncStrategy); 10] = [
    ("b: lines, no barriers", BreakdownStep::Lines, SyncStrategy::Racy),
    ("c: + barriers", BreakdownStep::Lines, SyncStrategy::BarrierGlobal),
    ("d: + cache reads", BreakdownStep::CacheReads, SyncStrategy::BarrierGlobal),
    ("e: + piecewise integration", BreakdownStep::Piecewise, SyncStrategy::BarrierGlobal),
    ("e1: + history carry", BreakdownStep::Carry, SyncStrategy::BarrierGlobal),
    ("e2: + the two stores (racy, as read)", BreakdownStep::Stores, SyncStrategy::BarrierGlobal),
    ("e3: + claim pass", BreakdownStep::ClaimPass, SyncStrategy::BarrierGlobal),
    ("e4: + claim check", BreakdownStep::ClaimCheck, SyncStrategy::BarrierGlobal),
    ("e5: + own segment", BreakdownStep::OwnSegment, SyncStrategy::BarrierGlobal),
    ("f: + cache writes = IPSVI", BreakdownStep::Full, SyncStrategy::BarrierGlobal),
];

/// Whether a configuration runs a step (see [`STEPS`]).
fn runs_step(s: &IpsviSettings, step: BreakdownStep) -> bool {
    s.cache_update == CacheUpdate::ViewSamples
        || matches!(
            step,
            BreakdownStep::Lines | BreakdownStep::CacheReads | BreakdownStep::Piecewise | BreakdownStep::Full
        )
}

/// A configuration's name in rows and bars: the cache update, and for view
/// samples the write rule.
fn config_name(s: &IpsviSettings) -> String {
    match s.cache_update {
        CacheUpdate::ViewSamples => format!("{} {}", s.cache_update.name(), s.write_rule.name()),
        CacheUpdate::LightRays => s.cache_update.name().to_string(),
    }
}

/// A bar label's name for a configuration.
fn short_mode(s: &IpsviSettings) -> &'static str {
    match (s.cache_update, s.write_rule) {
        (CacheUpdate::ViewSamples, WriteRule::NonEmpty) => "view",
        (CacheUpdate::ViewSamples, WriteRule::EverySample) => "view every",
        (CacheUpdate::LightRays, _) => "rays",
    }
}

pub fn run(args: &BenchIpsviArgs) -> anyhow::Result<ExitCode> {
    let harness = session::harness(1, args.repeat)?;
    bench_args::check_sizes("--sizes", &args.sizes)?;
    let scene = scene_args::load(&args.scene)?;
    let base = scene.settings.get::<IpsviSettings>().into_owned();
    // View samples with both write rules, then light rays.
    let configs: Vec<IpsviSettings> = WriteRule::ALL
        .iter()
        .map(|&write_rule| IpsviSettings { cache_update: CacheUpdate::ViewSamples, write_rule, ..base.clone() })
        .chain(std::iter::once(IpsviSettings { cache_update: CacheUpdate::LightRays, ..base.clone() }))
        .collect();
    bench_args::check_ipsvi("the scene's [ipsvi] settings", &configs)?;
    let widths: Vec<IpsviSettings> =
        args.line_widths.iter().map(|&line_width| IpsviSettings { line_width, ..base.clone() }).collect();
    bench_args::check_ipsvi("--line-widths", &widths)?;
    let out_folder = OutFolder::prepare(&args.out)?;
    let ctx = session::open(&args.gpu)?;
    let gpu = GpuScene::upload_with(&ctx, &scene, session::volume_texels(&args.gpu)).context("uploading the scene")?;
    let mut profiler = Profiler::new(&ctx, PROFILER_CAPACITY)?;
    // Each step weighs its pixels (DVR a twentieth of an IPSVI step's cost per
    // pixel), so the time left counts a 512x512 step as four 256x256 ones.
    let per_size: usize = configs
        .iter()
        .map(|s| STEPS.iter().filter(|(_, step, _)| runs_step(s, *step)).count() + args.line_widths.len())
        .sum();
    let weights: Vec<f64> = args
        .sizes
        .iter()
        .flat_map(|&size| {
            let pixels = f64::from(size) * f64::from(size);
            std::iter::once(pixels * 0.05).chain(std::iter::repeat_n(pixels, per_size))
        })
        .collect();
    let mut progress = Progress::weighted(weights);
    let mut table = BenchTable::with_run(session::run_info(&ctx));
    let mut widths_table = BenchTable::with_run(session::run_info(&ctx));
    let mut bars = Vec::new();
    for &size in &args.sizes {
        let dvr = harness.measure_step(&mut progress, &format!("{size}x{size} a: DVR, one dispatch"), || {
            technique_frame(&gpu, Technique::Dvr, (size, size), &mut profiler)
        })?;
        let dvr_ms = dvr.median();
        for s in &configs {
            let mode = s.cache_update.name();
            let name = config_name(s);
            let lines: u32 = plans(&gpu, s, size, size).iter().map(|p| p.lines()).sum();
            let mut measured = vec![("a: DVR, one dispatch", dvr_ms, dvr.last.dispatches, dvr.last.barriers)];
            for (label, step, sync) in STEPS {
                if !runs_step(s, step) {
                    continue;
                }
                let settings = IpsviSettings { breakdown_step: step, ..s.clone() };
                let mut renderer = IpsviRenderer::new(&gpu, &settings, size, size)?;
                let m = harness.measure_step(&mut progress, &format!("{size}x{size} {name} {label}"), || {
                    ipsvi_frame(&ctx, &mut renderer, &mut profiler, sync)
                })?;
                measured.push((label, m.median(), m.last.frame.dispatches, m.last.frame.barriers));
            }
            let total = measured.last().map(|m| m.1).unwrap_or(f64::NAN);
            let mut bar = StackedBar { label: format!("{size} {}", short_mode(s)), segments: Vec::new() };
            let mut previous = 0.0;
            for (label, gpu_ms, dispatches, barriers) in measured {
                let step_ms = gpu_ms - previous;
                previous = gpu_ms;
                bar.segments.push((label.to_string(), step_ms));
                let mut row = BenchRow::new();
                row.set("width", size).set("height", size).set("cache_update", mode).set("step", label);
                row.set("write_rule", s.write_rule.name());
                row.set("gpu_ms", gpu_ms).set("step_ms", step_ms).set("step_share", step_ms / total);
                row.set("step_us_per_line", step_ms * 1000.0 / lines.max(1) as f64);
                row.set("lines", lines).set("dispatches", dispatches).set("barriers", barriers);
                table.push(row);
            }
            out_folder.save_rows("ipsvi_breakdown", &table)?;
            bars.push(bar);
            // The whole frame (step f) at each line width: what wider blocks save.
            let mut by_width = Vec::new();
            for &line_width in &args.line_widths {
                let settings = IpsviSettings { line_width, ..s.clone() };
                let mut renderer = IpsviRenderer::new(&gpu, &settings, size, size)?;
                let m = harness.measure_step(
                    &mut progress,
                    &format!("{size}x{size} {name} line width {line_width}"),
                    || ipsvi_frame(&ctx, &mut renderer, &mut profiler, SyncStrategy::BarrierGlobal),
                )?;
                by_width.push((line_width, m.median(), m.last.frame.dispatches));
            }
            let lw1_ms = by_width.iter().find(|w| w.0 == 1).map(|w| w.1);
            for (line_width, gpu_ms, dispatches) in by_width {
                let mut row = BenchRow::new();
                row.set("width", size).set("height", size).set("cache_update", mode).set("line_width", line_width);
                row.set("write_rule", s.write_rule.name());
                row.set("gpu_ms", gpu_ms).set("dispatches", dispatches);
                if let Some(lw1) = lw1_ms {
                    row.set("speedup_over_lw1", lw1 / gpu_ms);
                }
                widths_table.push(row);
            }
            out_folder.save_rows("ipsvi_line_widths", &widths_table)?;
        }
    }
    progress.finish();
    drop(gpu);
    table.write_csv(args.out.join("ipsvi_breakdown.csv"))?;
    table.write_json(args.out.join("ipsvi_breakdown.json"))?;
    std::fs::write(args.out.join("ipsvi_breakdown.md"), table.to_markdown_report())
        .context("writing ipsvi_breakdown.md")?;
    let chart = Chart::new("One IPSVI frame, step by step", "bars: size, view samples or light rays", "GPU time (ms)")
        .size(960, 600);
    plot_stacked_bars(args.out.join("ipsvi_breakdown.png"), &chart, &bars)?;
    widths_table.write_csv(args.out.join("ipsvi_line_widths.csv"))?;
    widths_table.write_json(args.out.join("ipsvi_line_widths.json"))?;
    std::fs::write(args.out.join("ipsvi_line_widths.md"), widths_table.to_markdown_report())
        .context("writing ipsvi_line_widths.md")?;
    print_summary(&table);
    println!(
        "wrote {}/ipsvi_breakdown.csv, ipsvi_breakdown.json, ipsvi_breakdown.md (the full tables), ipsvi_breakdown.png and .svg, \
         ipsvi_line_widths.csv, ipsvi_line_widths.json, ipsvi_line_widths.md",
        args.out.display()
    );
    out_folder.finish()?;
    Ok(session::finish(&ctx))
}

/// What the terminal shows: per size and mode the whole frame against DVR and
/// its largest step; every step is in the files.
fn print_summary(table: &BenchTable) {
    let mut groups: Vec<(String, String)> = Vec::new();
    for r in &table.rows {
        let key = (r.text("width"), format!("{} {}", r.text("cache_update"), r.text("write_rule")));
        if !groups.contains(&key) {
            groups.push(key);
        }
    }
    for (size, mode) in groups {
        let rows: Vec<&BenchRow> = table
            .rows
            .iter()
            .filter(|r| {
                r.text("width") == size && format!("{} {}", r.text("cache_update"), r.text("write_rule")) == mode
            })
            .collect();
        let (Some(first), Some(last)) = (rows.first(), rows.last()) else { continue };
        let ms = |r: &BenchRow, k: &str| r.get_f64(k).unwrap_or(f64::NAN);
        let largest = rows.iter().max_by(|a, b| ms(a, "step_ms").total_cmp(&ms(b, "step_ms")));
        let (dvr, frame) = (ms(first, "gpu_ms"), ms(last, "gpu_ms"));
        print!("{size}x{size} {mode}: IPSVI {frame:.0} ms, {:.1}x DVR ({dvr:.0} ms)", frame / dvr);
        if let Some(step) = largest {
            print!("; largest step {} ({:.0} %)", step.text("step"), 100.0 * ms(step, "step_share"));
        }
        println!();
    }
}
