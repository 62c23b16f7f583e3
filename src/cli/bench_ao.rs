//! `sweeplab bench ao`: ambient occlusion from clustered histograms against
//! the 2008 paper's parameters. For every (r, bits, packed dimension, n_c,
//! metric): the preprocessing time per step (of the run that computed the
//! cached result), the codebook error, the TF-change update and the frame
//! time (with Blinn-Phong's frame beside it), and the image RMSE against the
//! image of the unclustered histograms and against the ground truth (both per
//! r and bits). CSV, JSON, Markdown and two charts: error against n_c per
//! metric (the paper's figure 6) and error against preprocessing time.

use super::args::BenchAoArgs;
use super::render_cmd::PROFILER_CAPACITY;
use super::{scene_args, session};
use anyhow::{bail, Context as _};
use std::process::ExitCode;
use sweeplab::ao::render::AoRenderer;
use sweeplab::ao::technique::preprocessed;
use sweeplab::ao::{paper_table1, AoPreprocessed, AoSettings, Metric};
use sweeplab::bench::{
    plot_error_vs_time, plot_lines, technique_frame, AxisScale, BenchRow, BenchTable, Chart, Harness, OutFolder,
    Progress, Sample, Series,
};
use sweeplab::linear_image::LinearImage;
use sweeplab::metrics::compare;
use sweeplab::reference::ao::AoReferenceParams;
use sweeplab::reference::ao_gpu::reference_gpu;
use sweeplab::reference::ao_unclustered::unclustered_lookup;
use sweeplab::reference::gpu::ChunkSync;
use sweeplab::render::{GpuScene, RenderError};
use sweeplab::scene::{Scene, TransferLut};
use sweeplab::techniques::Technique;
use sweeplab::vk::Profiler;

const DEFAULT_IMAGE: u32 = 256;
const CORNELL_BOX: &str = include_str!("../../tests/scenes/cornell-box.toml");

/// Every configuration, each checked as the scene file's `[ao]` would be.
fn configurations(args: &BenchAoArgs, base: &AoSettings) -> anyhow::Result<Vec<AoSettings>> {
    let lists: [(&str, usize); 5] = [
        ("--radii", args.radii.len()),
        ("--bits", args.bits.len()),
        ("--packed-dims", args.packed_dims.len()),
        ("--clusters", args.clusters.len()),
        ("--metrics", args.metrics.len()),
    ];
    if let Some((flag, _)) = lists.iter().find(|(_, n)| *n == 0) {
        bail!("{flag}: give at least one value");
    }
    let metrics = args.metrics.iter().map(|m| parse_metric(m)).collect::<anyhow::Result<Vec<_>>>()?;
    if args.reference_pairs == 0 {
        bail!("--reference-pairs: at least one direction pair");
    }
    let mut all = Vec::new();
    for &radius in &args.radii {
        for &bits in &args.bits {
            for &packed_dim in &args.packed_dims {
                for &clusters in &args.clusters {
                    for &metric in &metrics {
                        let settings = AoSettings { radius, bits, packed_dim, clusters, metric, ..base.clone() };
                        settings.validate().context("--radii/--bits/--packed-dims/--clusters")?;
                        all.push(settings);
                    }
                }
            }
        }
    }
    Ok(all)
}

fn parse_metric(name: &str) -> anyhow::Result<Metric> {
    Metric::ALL.into_iter().find(|m| m.name() == name).ok_or_else(|| {
        let names = Metric::ALL.map(|m| m.name());
        let near = sweeplab::scene::suggest::nearest(name, names).map(|n| format!(" (did you mean {n}?)"));
        anyhow::anyhow!("--metrics: unknown metric {name:?}{}; known: {}", near.unwrap_or_default(), names.join(", "))
    })
}

fn load_scene(args: &BenchAoArgs) -> anyhow::Result<Scene> {
    let mut scene = if args.scene.scene.is_none() && args.scene.volume.is_none() {
        let base = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scenes");
        sweeplab::techniques::scene_from_toml_str(CORNELL_BOX, &base, "cornell-box", &args.scene.set)?
    } else {
        scene_args::load(&args.scene)?
    };
    let (w, h) = match &args.scene.size {
        Some(size) => scene_args::parse_size(size)?,
        None => (DEFAULT_IMAGE, DEFAULT_IMAGE),
    };
    (scene.render.width, scene.render.height) = (w, h);
    Ok(scene)
}

pub fn run(args: &BenchAoArgs) -> anyhow::Result<ExitCode> {
    let harness = Harness::new(1, args.repeat).context("--repeat")?;
    let scene = load_scene(args)?;
    let configs = configurations(args, &scene.settings.get::<AoSettings>())?;
    let out_folder = OutFolder::prepare(&args.out)?;
    let ctx = session::open(&args.gpu)?;
    let gpu = GpuScene::upload(&ctx, &scene).context("uploading the scene")?;
    let mut profiler = Profiler::new(&ctx, PROFILER_CAPACITY)?;
    let size = (scene.render.width, scene.render.height);
    let mut progress = Progress::weighted(step_weights(&configs));

    progress.start_step("phong frame");
    let phong = harness.measure(|| technique_frame(&gpu, Technique::Phong, size, &mut profiler))?;
    progress.finish_step();
    let phong_ms = phong.median();

    let lut = scene.transfer.bake(TransferLut::DEFAULT_SIZE);
    // Per (r, bits): the unclustered image and the ground truth's.
    let mut baselines: Vec<((u32, u32), LinearImage, LinearImage)> = Vec::new();
    let mut table = BenchTable::with_run(session::run_info(&ctx));
    let mut table1 = paper_table1_rows();
    table1.run = table.run.clone();
    for s in &configs {
        if !baselines.iter().any(|(k, _, _)| *k == (s.radius, s.bits)) {
            progress.start_step(&format!("unclustered r={} bits={}", s.radius, s.bits));
            let lookup = unclustered_lookup(&scene.volume, s, &lut);
            let unclustered = AoRenderer::per_voxel(&gpu, &lookup, s)?.frame(&gpu, size, &mut profiler)?.image;
            progress.finish_step();
            progress.start_step(&format!("ground truth r={}", s.radius));
            let params = AoReferenceParams { radius: s.radius, pairs: args.reference_pairs, step: 0.5 };
            profiler.reset();
            let lookup = reference_gpu(&gpu, &params, None, &mut profiler, ChunkSync::Barrier)?;
            let truth = AoRenderer::per_voxel(&gpu, &lookup, s)?.frame(&gpu, size, &mut profiler)?.image;
            progress.finish_step();
            baselines.push(((s.radius, s.bits), unclustered, truth));
        }
        let (_, unclustered, truth) = baselines.iter().find(|(k, _, _)| *k == (s.radius, s.bits)).expect("just made");
        let label =
            format!("r={} bits={} packed={} n_c={} {}", s.radius, s.bits, s.packed_dim, s.clusters, s.metric.name());
        progress.start_step(&label);
        let pre = preprocessed(&scene.volume, s, Some(&ctx), &mut |_| {})?;
        let renderer = AoRenderer::new(&gpu, &pre, s)?;
        let update = harness.measure(|| -> Result<Sample<()>, RenderError> {
            profiler.reset();
            renderer.update_environment(&gpu, &mut profiler)?;
            Ok(Sample::timed(profiler.resolve(0)?.pass_ms("ao_environment"), ()))
        })?;
        let frame = harness.measure(|| -> Result<Sample<LinearImage>, RenderError> {
            profiler.reset();
            let frame = renderer.frame(&gpu, size, &mut profiler)?;
            Ok(Sample::timed(profiler.resolve(0)?.pass_ms("ao"), frame.image))
        })?;
        progress.finish_step();
        let against_unclustered = compare(&frame.last, unclustered)?;
        let against_truth = compare(&frame.last, truth)?;
        let t = &pre.stats.timings;
        let mut row = BenchRow::new()
            .with("r", s.radius as f64)
            .with("bits", s.bits as f64)
            .with("packed_dim", s.packed_dim as f64)
            .with("clusters", s.clusters as f64)
            .with("metric", s.metric.name());
        row.set("packing_s", t.packing)
            .set("training_histograms_s", t.training_histograms)
            .set("training_s", t.training)
            .set("assignment_s", t.assignment)
            .set("preprocess_s", t.total())
            .set("lloyd_iterations", pre.stats.lloyd_iterations as f64)
            .set("training_distortion", pre.stats.training_distortion)
            .set("assignment_distortion", pre.stats.assignment_distortion)
            .set("lookup_bytes", (pre.codebook.len() * 4 + pre.cluster_ids.len() * 4) as f64)
            .set("update_ms", update.median())
            .set("ao_ms", frame.median())
            .set("phong_ms", phong_ms)
            .set("overhead", frame.median() / phong_ms)
            .set("rmse_unclustered", against_unclustered.rmse)
            .set("rmse_unclustered_of_peak", against_unclustered.rmse / unclustered.max_value().max(1e-12) as f64)
            .set("rmse_truth", against_truth.rmse);
        table.push(row);
        out_folder.save_rows("ao", &table)?;
        table1.push(table1_row(&data_set_name(args), &scene, s, &pre));
    }
    progress.finish();
    write_report(args, &table, &table1)?;
    drop(gpu);
    out_folder.finish()?;
    Ok(session::finish(&ctx))
}

/// The paper's Table 1 (minutes turned into seconds), our rows follow.
fn paper_table1_rows() -> BenchTable {
    let mut t = BenchTable::new();
    for p in &paper_table1::ROWS {
        let source = if p.space_sweep { "paper (space sweep)" } else { "paper (brute force)" };
        t.push(
            BenchRow::new()
                .with("source", source)
                .with("data_set", p.data_set)
                .with("size", p.size)
                .with("r", p.radius as f64)
                .with("histograms_s", p.histograms_min * 60.0)
                .with("codewords_packed", p.training)
                .with(
                    "training_s",
                    p.training_min
                        .split(' ')
                        .map(|m| m.parse::<f64>().map_or(m.to_string(), |m| format!("{:.1}", m * 60.0)))
                        .collect::<Vec<_>>()
                        .join(" "),
                )
                .with("local_histograms", p.local_histograms)
                .with("codebook", p.codebook),
        );
    }
    t
}

/// The data set's name in the tables: the scene or volume file's stem.
fn data_set_name(args: &BenchAoArgs) -> String {
    let path = args.scene.scene.as_ref().or(args.scene.volume.as_ref());
    path.and_then(|p| p.file_stem()).map_or("cornell-box".into(), |s| s.to_string_lossy().into_owned())
}

/// Our preprocessing of `s` in the paper's Table 1 columns: the histograms
/// with the assignment (streamed together here), the training, and the sizes
/// the unpacked local histograms would take and the codebook takes.
fn table1_row(name: &str, scene: &Scene, s: &AoSettings, pre: &AoPreprocessed) -> BenchRow {
    let d = scene.volume.dims;
    let mb = |bytes: f64| format!("{:.3} MB", bytes / (1024.0 * 1024.0));
    let bins = s.bins() as f64;
    let t = &pre.stats.timings;
    BenchRow::new()
        .with("source", "ours (this machine)")
        .with("data_set", name)
        .with("size", format!("{}x{}x{}", d.x, d.y, d.z))
        .with("r", s.radius as f64)
        .with("histograms_s", t.assignment)
        .with("codewords_packed", format!("{}/{} {}", s.clusters, s.packed_dim, s.metric.name()))
        .with("training_s", format!("{:.3}", t.training_histograms + t.training))
        .with("local_histograms", mb(scene.volume.voxel_count() as f64 * 2.0 * bins * 4.0))
        .with("codebook", mb(pre.codebook.len() as f64 * 4.0))
}

/// The relative size of each progress step in the order `run` takes them:
/// the Phong frame, then per configuration its (radius, bits) baselines the
/// first time they come up, then its preprocessing and frames. All grow about
/// linearly with the radius on lavapipe (engine.vti at r = 16: preprocessing
/// 45 s, unclustered image 71 s, ground truth 180 s; at r = 4 about a
/// quarter), so the radius is the weight.
fn step_weights(configs: &[AoSettings]) -> Vec<f64> {
    let mut weights = vec![0.1];
    let mut seen: Vec<(u32, u32)> = Vec::new();
    for s in configs {
        let r = f64::from(s.radius);
        if !seen.contains(&(s.radius, s.bits)) {
            seen.push((s.radius, s.bits));
            weights.extend([1.5 * r, 4.0 * r]);
        }
        weights.push(r);
    }
    weights
}

fn write_report(args: &BenchAoArgs, table: &BenchTable, table1: &BenchTable) -> anyhow::Result<()> {
    table.write_csv(args.out.join("ao.csv"))?;
    table.write_json(args.out.join("ao.json"))?;
    table1.write_csv(args.out.join("ao_table1.csv"))?;
    let markdown = format!(
        "{}## Ambient occlusion (bench ao)\n\n{}\n\n## Table 1 shape: the paper's preprocessing beside ours\n\n\
         Paper: Opteron 852, 4 per process, minutes as seconds; ours: this machine (the preprocessing runs where `ao.backend` puts it) \
         (histograms_s is our histograms with the nearest-codeword assignment, streamed together; \
         local_histograms is what the unpacked histograms would take, which we never hold).\n\n{}\n",
        table.run.as_ref().map(|r| r.markdown()).unwrap_or_default(),
        table.to_markdown(),
        table1.to_markdown()
    );
    std::fs::write(args.out.join("ao.md"), &markdown).context("writing ao.md")?;
    let by_metric = |y: &'static str, x: &'static str| -> Vec<Series> {
        Metric::ALL
            .iter()
            .map(|m| Series::new(m.name(), table.points(|r| r.text("metric") == m.name(), x, y)))
            .filter(|s| !s.points.is_empty())
            .collect()
    };
    plot_lines(
        args.out.join("ao_error_vs_clusters.png"),
        &Chart::new("AO: image RMSE against the unclustered histograms", "n_c", "RMSE").x_scale(AxisScale::Log10),
        &by_metric("rmse_unclustered", "clusters"),
    )?;
    plot_error_vs_time(
        args.out.join("ao_error_vs_preprocessing.png"),
        &Chart::new("AO: RMSE against the ground truth over preprocessing time", "preprocessing (s)", "RMSE"),
        &by_metric("rmse_truth", "preprocess_s"),
    )?;
    print_summary(table);
    println!(
        "wrote {}/ao.csv, ao.json, ao_table1.csv, ao.md (the full table), ao_error_vs_clusters.png, \
         ao_error_vs_preprocessing.png (and .svg)",
        args.out.display()
    );
    Ok(())
}

/// What the terminal shows: one short line per configuration; every column is
/// in the files.
fn print_summary(table: &BenchTable) {
    for r in &table.rows {
        println!(
            "r={} bits={} n_c={} {}: preprocessing {:.1} s, error {:.3} % of the peak, TF change {:.2} ms, frame {:.2}x Phong",
            r.text("r"),
            r.text("bits"),
            r.text("clusters"),
            r.text("metric"),
            r.get_f64("preprocess_s").unwrap_or(f64::NAN),
            100.0 * r.get_f64("rmse_unclustered_of_peak").unwrap_or(f64::NAN),
            r.get_f64("update_ms").unwrap_or(f64::NAN),
            r.get_f64("overhead").unwrap_or(f64::NAN)
        );
    }
}
