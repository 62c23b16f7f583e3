//! `sweeplab bench ipsvi`: error against GPU time over IPSVI's parameters.

use super::args::BenchIpsviArgs;
use super::render_cmd::PROFILER_CAPACITY;
use super::{bench_args, scene_args, session};
use anyhow::Context as _;
use std::process::ExitCode;
use sweeplab::bench::{
    ipsvi_frame, plot_error_vs_time, technique_frame, AxisScale, BenchRow, BenchTable, Chart, OutFolder, ProfiledFrame,
    Progress, Series,
};
use sweeplab::half_angle::HalfAngleSettings;
use sweeplab::ipsvi::renderer::{plans, IpsviRenderer};
use sweeplab::ipsvi::{CacheUpdate, EarlyTermination, IpsviSettings, SyncStrategy, WriteRule};
use sweeplab::linear_image::LinearImage;
use sweeplab::metrics::compare;
use sweeplab::render::GpuScene;
use sweeplab::scene::OpticalModel;
use sweeplab::techniques::{render, Technique};
use sweeplab::vk::Profiler;

/// The write rules a configuration is measured with: both for view samples
/// (so the plot shows which rule serves each budget), light rays' own otherwise.
fn write_rules(base: &IpsviSettings) -> Vec<WriteRule> {
    match base.cache_update {
        CacheUpdate::ViewSamples => WriteRule::ALL.to_vec(),
        CacheUpdate::LightRays => vec![base.write_rule],
    }
}

fn configurations(args: &BenchIpsviArgs, base: &IpsviSettings) -> Vec<IpsviSettings> {
    let mut out = Vec::new();
    if args.one_at_a_time {
        let mut push = |s: IpsviSettings| {
            if !out.contains(&s) {
                out.push(s)
            }
        };
        push(base.clone());
        for write_rule in write_rules(base) {
            push(IpsviSettings { write_rule, ..base.clone() });
        }
        for &lw in &args.line_widths {
            push(IpsviSettings { line_width: lw, ..base.clone() });
            push(IpsviSettings { line_width: lw, piecewise: false, ..base.clone() });
        }
        for &c in &args.cache_sizes {
            push(IpsviSettings { cache_size: c, ..base.clone() });
        }
        for ert in [EarlyTermination::Off, EarlyTermination::Plain, EarlyTermination::ExitPoints] {
            push(IpsviSettings { early_termination: ert, ..base.clone() });
        }
        return out;
    }
    for &lw in &args.line_widths {
        for &c in &args.cache_sizes {
            for piecewise in [true, false] {
                for early_termination in [EarlyTermination::Plain, EarlyTermination::Off, EarlyTermination::ExitPoints]
                {
                    for write_rule in write_rules(base) {
                        out.push(IpsviSettings {
                            line_width: lw,
                            cache_size: c,
                            piecewise,
                            early_termination,
                            write_rule,
                            ..base.clone()
                        });
                    }
                }
            }
        }
    }
    out
}

pub fn run(args: &BenchIpsviArgs) -> anyhow::Result<ExitCode> {
    if args.breakdown {
        return super::bench_breakdown::run(args);
    }
    // One untimed frame first: llvmpipe compiles shader variants on first use.
    let harness = session::harness(1, args.repeat)?;
    bench_args::check_sizes("--sizes", &args.sizes)?;
    bench_args::check_slice_steps("--half-angle-slices", &args.half_angle_slices)?;
    let mut scene = scene_args::load(&args.scene)?;
    scene.reference.model = OpticalModel::EmissiveScattering;
    let base = scene.settings.get::<IpsviSettings>().into_owned();
    let configs = configurations(args, &base);
    bench_args::check_ipsvi("--line-widths/--cache-sizes", &configs)?;
    let out_folder = OutFolder::prepare(&args.out)?;
    let ctx = session::open(&args.gpu)?;
    let gpu = GpuScene::upload_with(&ctx, &scene, session::volume_texels(&args.gpu)).context("uploading the scene")?;
    let mut profiler = Profiler::new(&ctx, PROFILER_CAPACITY)?;
    let mut progress = Progress::weighted(step_weights(args, configs.len(), harness.repeat()));
    let mut table = BenchTable::with_run(session::run_info(&ctx));
    for &size in &args.sizes {
        progress.start_step(&format!("{size}x{size} ground truth (GPU, model ii)"));
        let reference = render(&gpu, Technique::Reference, size, size, &mut profiler)?;
        progress.finish_step();
        let reference_image: LinearImage = reference.image;
        let mut row = BenchRow::new();
        row.set("technique", "reference").set("width", size).set("height", size);
        row.set("gpu_ms", reference.profile.gpu_ms_total).set("rmse", 0.0).set("max_abs", 0.0);
        row.set("dispatches", reference.dispatches).set("gpu_memory_bytes", reference.profile.gpu_memory_bytes);
        table.push(row);
        out_folder.save_rows("ipsvi", &table)?;

        let dvr = harness.measure_step(&mut progress, &format!("{size}x{size} unshaded DVR"), || {
            technique_frame(&gpu, Technique::Dvr, (size, size), &mut profiler)
        })?;
        let (dvr_ms, dvr) = (dvr.median(), dvr.last);
        let stats = compare(&dvr.image, &reference_image)?;
        let mut row = BenchRow::new();
        row.set("technique", "dvr").set("width", size).set("height", size).set("gpu_ms", dvr_ms);
        row.set("rmse", stats.rmse).set("max_abs", stats.max_abs).set("psnr", stats.psnr);
        row.set("dispatches", dvr.dispatches).set("gpu_memory_bytes", dvr.profile.gpu_memory_bytes);
        let dvr_ms = row.get_f64("gpu_ms").unwrap_or(f64::NAN);
        let dvr_bytes = dvr.profile.gpu_memory_bytes;
        table.push(row);
        out_folder.save_rows("ipsvi", &table)?;

        for s in &configs {
            let label = format!(
                "{size}x{size} lw={} cache={} pi={} ert={} rule={}",
                s.line_width,
                s.cache_size,
                s.piecewise,
                s.early_termination.name(),
                s.write_rule.name()
            );
            let lines: u32 = plans(&gpu, s, size, size).iter().map(|p| p.lines()).sum();
            ctx.memory.reset_peak();
            let mut renderer = IpsviRenderer::new(&gpu, s, size, size)?;
            let measured = harness.measure_step(&mut progress, &label, || {
                ipsvi_frame(&ctx, &mut renderer, &mut profiler, SyncStrategy::BarrierGlobal)
            })?;
            let gpu_ms = measured.median();
            let ProfiledFrame { frame, profile } = measured.last;
            let stats = compare(&frame.image, &reference_image)?;
            let mut row = BenchRow::new();
            row.set("technique", "ipsvi").set("width", size).set("height", size);
            row.set("line_width", s.line_width).set("cache_size", s.cache_size);
            row.set("piecewise", s.piecewise).set("early_termination", s.early_termination.name());
            row.set("cache_update", s.cache_update.name()).set("write_rule", s.write_rule.name());
            row.set("gpu_ms", gpu_ms).set("rmse", stats.rmse).set("max_abs", stats.max_abs).set("psnr", stats.psnr);
            row.set("lines", lines).set("dispatches", frame.dispatches).set("barriers", frame.barriers);
            row.set("gpu_memory_bytes", profile.gpu_memory_bytes);
            row.set("extra_memory_bytes_over_dvr", profile.gpu_memory_bytes as i64 - dvr_bytes as i64);
            row.set("time_over_dvr", gpu_ms / dvr_ms);
            row.set("ms_per_dispatch", gpu_ms / frame.dispatches.max(1) as f64);
            table.push(row);
            out_folder.save_rows("ipsvi", &table)?;
        }
        if !args.half_angle_slices.is_empty() && scene.lights.len() == 1 {
            half_angle_rows(args, &ctx, &scene, size, &mut profiler, &mut progress, &mut table)?;
            out_folder.save_rows("ipsvi", &table)?;
        }
    }
    progress.finish();
    drop(gpu);
    // The Pareto front of IPSVI runs, per image size.
    for &size in &args.sizes {
        let idx: Vec<usize> = (0..table.rows.len())
            .filter(|&i| {
                let r = &table.rows[i];
                r.get("technique").map(|t| t.to_string()) == Some("ipsvi".into())
                    && r.get_f64("width") == Some(size as f64)
            })
            .collect();
        let points: Vec<(f64, f64)> = idx
            .iter()
            .map(|&i| (table.rows[i].get_f64("gpu_ms").unwrap(), table.rows[i].get_f64("rmse").unwrap()))
            .collect();
        let front = sweeplab::bench::pareto_front(&points);
        for (k, &i) in idx.iter().enumerate() {
            table.rows[i].set("pareto", front.contains(&k));
        }
        // One series per line width and write rule: which IPSVI to pick at each budget.
        let rules = write_rules(&base);
        let series: Vec<Series> = args
            .line_widths
            .iter()
            .flat_map(|&lw| rules.iter().map(move |&rule| (lw, rule)))
            .map(|(lw, rule)| {
                let pts = idx
                    .iter()
                    .filter(|&&i| {
                        table.rows[i].get_f64("line_width") == Some(lw as f64)
                            && table.rows[i].text("write_rule") == rule.name()
                    })
                    .map(|&i| (table.rows[i].get_f64("gpu_ms").unwrap(), table.rows[i].get_f64("rmse").unwrap()))
                    .collect();
                Series::new(format!("line width {lw}, {}", rule.name()), pts)
            })
            .chain(std::iter::once(Series::new(
                "half-angle (model i)",
                table.points(
                    |r| r.text("technique") == "half-angle" && r.get_f64("width") == Some(size as f64),
                    "gpu_ms",
                    "rmse",
                ),
            )))
            .collect();
        let chart =
            Chart::new(format!("IPSVI {size}x{size}: error against GPU time"), "GPU time (ms)", "RMSE vs ground truth")
                .x_scale(AxisScale::Log10)
                .y_scale(AxisScale::Log10);
        plot_error_vs_time(args.out.join(format!("ipsvi_{size}_error_vs_time.png")), &chart, &series)?;
    }
    table.write_csv(args.out.join("ipsvi.csv"))?;
    table.write_json(args.out.join("ipsvi.json"))?;
    std::fs::write(args.out.join("ipsvi.md"), table.to_markdown_report()).context("writing ipsvi.md")?;
    print_summary(&table);
    println!(
        "wrote {}/ipsvi.csv, ipsvi.json, ipsvi.md (the full table) and ipsvi_<size>_error_vs_time.png (and .svg)",
        args.out.display()
    );
    out_folder.finish()?;
    Ok(session::finish(&ctx))
}

/// Half-angle slicing at each slice spacing, against a model (i) ground truth
/// (half-angle slicing carries no emission along the light), at one image size.
fn half_angle_rows(
    args: &BenchIpsviArgs,
    ctx: &sweeplab::vk::Context,
    scene: &sweeplab::scene::Scene,
    size: u32,
    profiler: &mut Profiler,
    progress: &mut Progress,
    table: &mut BenchTable,
) -> anyhow::Result<()> {
    // A warm-up frame per slice spacing: each compiles its own pipelines.
    let harness = session::harness(1, args.repeat)?;
    let mut scene = scene.clone();
    scene.reference.model = OpticalModel::SingleScattering;
    progress.start_step(&format!("{size}x{size} ground truth (GPU, model i)"));
    let reference = {
        let gpu = GpuScene::upload_with(ctx, &scene, session::volume_texels(&args.gpu))?;
        render(&gpu, Technique::Reference, size, size, profiler)?.image
    };
    progress.finish_step();
    for &step in &args.half_angle_slices {
        if !(step.is_finite() && (0.01..=16.0).contains(&step)) {
            anyhow::bail!("--half-angle-slices: {step} is not a slice spacing in 0.01..=16 voxels");
        }
        scene.settings.get_mut::<HalfAngleSettings>().slice_step = Some(step);
        let gpu = GpuScene::upload_with(ctx, &scene, session::volume_texels(&args.gpu))?;
        let label = format!("{size}x{size} half-angle slices {step} voxel");
        let measured = harness
            .measure_step(progress, &label, || technique_frame(&gpu, Technique::HalfAngle, (size, size), profiler))?;
        let (gpu_ms, out) = (measured.median(), measured.last);
        let stats = compare(&out.image, &reference)?;
        let mut row = BenchRow::new();
        row.set("technique", "half-angle").set("width", size).set("height", size).set("slice_step_voxels", step);
        row.set("gpu_ms", gpu_ms).set("rmse", stats.rmse).set("max_abs", stats.max_abs).set("psnr", stats.psnr);
        row.set("dispatches", out.dispatches).set("gpu_memory_bytes", out.profile.gpu_memory_bytes);
        row.set("reference_model", "single-scattering");
        table.push(row);
    }
    Ok(())
}

/// The relative size of each progress step, in the order `run` takes them:
/// pixels x frames rendered x a rough cost per pixel of the technique (the
/// ground truth and IPSVI about one unit, half-angle half, DVR a twentieth),
/// so the time left weighs a 512x512 step four times a 256x256 one.
fn step_weights(args: &BenchIpsviArgs, configs: usize, repeat: u32) -> Vec<f64> {
    let frames = f64::from(1 + repeat);
    let mut weights = Vec::new();
    for &size in &args.sizes {
        let pixels = f64::from(size) * f64::from(size);
        weights.push(pixels);
        weights.push(pixels * frames * 0.05);
        weights.extend(std::iter::repeat_n(pixels * frames, configs));
        weights.push(pixels);
        weights.extend(std::iter::repeat_n(pixels * frames * 0.5, args.half_angle_slices.len()));
    }
    weights
}

/// What the terminal shows: per size the fastest and the most accurate IPSVI
/// run and the unshaded baseline; the full table is in the files.
fn print_summary(table: &BenchTable) {
    let mut sizes: Vec<u64> = table.rows.iter().filter_map(|r| r.get_f64("width")).map(|w| w as u64).collect();
    sizes.dedup();
    for size in sizes {
        let of = |technique: &str| -> Vec<&BenchRow> {
            table
                .rows
                .iter()
                .filter(|r| r.text("technique") == technique && r.get_f64("width") == Some(size as f64))
                .collect()
        };
        let ipsvi = of("ipsvi");
        let by = |key: &str| {
            ipsvi.iter().copied().min_by(|a, b| {
                a.get_f64(key).unwrap_or(f64::INFINITY).total_cmp(&b.get_f64(key).unwrap_or(f64::INFINITY))
            })
        };
        let describe = |r: &BenchRow| {
            format!(
                "lw={} cache={} {} {:.0} ms, rmse {:.3e}",
                r.text("line_width"),
                r.text("cache_size"),
                r.text("write_rule"),
                r.get_f64("gpu_ms").unwrap_or(f64::NAN),
                r.get_f64("rmse").unwrap_or(f64::NAN)
            )
        };
        let dvr = of("dvr").first().and_then(|r| r.get_f64("gpu_ms")).unwrap_or(f64::NAN);
        println!("{size}x{size}: {} IPSVI runs; unshaded DVR {dvr:.0} ms", ipsvi.len());
        if let (Some(fast), Some(exact)) = (by("gpu_ms"), by("rmse")) {
            println!("  fastest:       {}", describe(fast));
            println!("  most accurate: {}", describe(exact));
        }
    }
}
