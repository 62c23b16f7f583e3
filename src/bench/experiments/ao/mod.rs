//! `sweeplab bench ao` as an experiment: ambient occlusion from clustered
//! histograms against the 2008 paper's parameters. For every (r, bits, packed
//! dimension, n_c, metric): the preprocessing time per step (of the run that
//! computed the cached result), the codebook error, the TF-change update and
//! the frame time (with Blinn-Phong's frame beside it), and the image RMSE
//! against the image of the unclustered histograms and against the ground
//! truth (both per r and bits). CSV, JSON, Markdown and two charts: error
//! against n_c per metric (the paper's figure 6) and error against
//! preprocessing time.

mod experiment;
pub mod paper_table1;

pub use experiment::AoExperiment;

use crate::bench::{
    plot_error_vs_time, plot_lines, technique_frame, AxisScale, BenchError, BenchRow, BenchTable, Chart,
    ExperimentError, Interleaved, OutFolder, Progress, RunInfo, Sample, Series,
};
use crate::linear_image::LinearImage;
use crate::metrics::compare;
use crate::render::view_chunks::ChunkSync;
use crate::render::{GpuScene, RenderError};
use crate::scene::scene_file::SceneError;
use crate::scene::{Scene, TransferLut};
use crate::techniques::ao::ground_truth::gpu::reference_gpu;
use crate::techniques::ao::ground_truth::unclustered::unclustered_lookup;
use crate::techniques::ao::ground_truth::AoReferenceParams;
use crate::techniques::ao::render::AoRenderer;
use crate::techniques::ao::technique::preprocessed;
use crate::techniques::ao::{AoPreprocessed, AoSettings, Metric};
use crate::techniques::Technique;
use crate::vk::{Context, Profiler};
use std::path::Path;

/// What `bench ao` sweeps: every combination of the lists is a configuration.
#[derive(Clone, Debug)]
pub struct AoPlan {
    pub radii: Vec<u32>,
    pub bits: Vec<u32>,
    pub packed_dims: Vec<u32>,
    pub clusters: Vec<u32>,
    /// Metric names ("l2", "l1", "lmax").
    pub metrics: Vec<String>,
    /// Direction pairs of the ground truth.
    pub reference_pairs: u32,
    /// The rounds in which the frames and updates of every configuration
    /// (and Blinn-Phong's frame) are timed, side by side.
    pub rounds: Interleaved,
    /// The data set's name in the tables.
    pub data_set: String,
}

/// Every configuration, each checked as the scene file's `[ao]` would be.
pub fn configurations(plan: &AoPlan, base: &AoSettings) -> Result<Vec<AoSettings>, ExperimentError> {
    let lists: [(&str, usize); 5] = [
        ("--radii", plan.radii.len()),
        ("--bits", plan.bits.len()),
        ("--packed-dims", plan.packed_dims.len()),
        ("--clusters", plan.clusters.len()),
        ("--metrics", plan.metrics.len()),
    ];
    if let Some((flag, _)) = lists.iter().find(|(_, n)| *n == 0) {
        return Err(ExperimentError::Invalid(format!("{flag}: give at least one value")));
    }
    let metrics = plan.metrics.iter().map(|m| parse_metric(m)).collect::<Result<Vec<_>, _>>()?;
    if plan.reference_pairs == 0 {
        return Err(ExperimentError::Invalid("--reference-pairs: at least one direction pair".into()));
    }
    let mut all = Vec::new();
    for &radius in &plan.radii {
        for &bits in &plan.bits {
            for &packed_dim in &plan.packed_dims {
                for &clusters in &plan.clusters {
                    for &metric in &metrics {
                        let settings = AoSettings { radius, bits, packed_dim, clusters, metric, ..base.clone() };
                        settings.validate().map_err(|e| {
                            ExperimentError::Invalid(format!("--radii/--bits/--packed-dims/--clusters: {e}"))
                        })?;
                        all.push(settings);
                    }
                }
            }
        }
    }
    Ok(all)
}

fn parse_metric(name: &str) -> Result<Metric, ExperimentError> {
    Metric::ALL.into_iter().find(|m| m.name() == name).ok_or_else(|| {
        let names = Metric::ALL.map(|m| m.name());
        let near = crate::scene::suggest::nearest(name, names).map(|n| format!(" (did you mean {n}?)"));
        ExperimentError::Invalid(format!(
            "--metrics: unknown metric {name:?}{}; known: {}",
            near.unwrap_or_default(),
            names.join(", ")
        ))
    })
}

/// What a run measured: one row per configuration, and the paper's Table 1
/// rows with ours after them.
pub struct AoReport {
    pub table: BenchTable,
    pub table1: BenchTable,
}

/// Every configuration of `plan` on `scene` (its image size), each row saved
/// in `out_folder` as it is measured; the report and charts at the end.
pub fn run(
    ctx: &Context,
    scene: &Scene,
    plan: &AoPlan,
    run: RunInfo,
    out_folder: &OutFolder,
    profiler_capacity: u32,
) -> Result<AoReport, ExperimentError> {
    let configs = configurations(plan, &scene.settings.get::<AoSettings>())?;
    let gpu = GpuScene::upload(ctx, scene)?;
    let mut profiler = Profiler::new(ctx, profiler_capacity)?;
    let size = (scene.render.width, scene.render.height);
    let mut progress = Progress::weighted(step_weights(&configs, plan.rounds.most_runs()));

    let lut = scene.transfer.bake(TransferLut::DEFAULT_SIZE);
    // Per (r, bits): the unclustered image and the ground truth's.
    let mut baselines: Vec<((u32, u32), LinearImage, LinearImage)> = Vec::new();
    let mut table = BenchTable::with_run(plan.rounds.recorded_in(run));
    let mut table1 = paper_table1_rows();
    table1.run = table.run.clone();
    // First every configuration's preprocessing (a one-off cost, timed once
    // as it runs) and renderer; then their times in shared rounds.
    let mut prepared = Vec::new();
    for s in &configs {
        if !baselines.iter().any(|(k, _, _)| *k == (s.radius, s.bits)) {
            progress.start_step(&format!("unclustered r={} bits={}", s.radius, s.bits));
            let lookup = unclustered_lookup(&scene.volume, s, &lut);
            let unclustered = AoRenderer::per_voxel(&gpu, &lookup, s)?.frame(&gpu, size, &mut profiler)?.image;
            progress.finish_step();
            progress.start_step(&format!("ground truth r={}", s.radius));
            let params = AoReferenceParams { radius: s.radius, pairs: plan.reference_pairs, step: 0.5 };
            profiler.reset();
            let lookup = reference_gpu(&gpu, &params, None, &mut profiler, ChunkSync::Barrier)?;
            let truth = AoRenderer::per_voxel(&gpu, &lookup, s)?.frame(&gpu, size, &mut profiler)?.image;
            progress.finish_step();
            baselines.push(((s.radius, s.bits), unclustered, truth));
        }
        let label =
            format!("r={} bits={} packed={} n_c={} {}", s.radius, s.bits, s.packed_dim, s.clusters, s.metric.name());
        progress.start_step(&format!("preprocessing {label}"));
        let pre = preprocessed(&scene.volume, s, Some(ctx), &mut |_| {}).map_err(RenderError::from)?;
        let renderer = AoRenderer::new(&gpu, &pre, s)?;
        progress.finish_step();
        prepared.push((pre, renderer));
    }
    // Configuration 0 is Blinn-Phong's frame, then per AO configuration its
    // TF-change update (odd) and its frame (even).
    let timings = plan.rounds.measure(&mut progress, "frames and updates", 1 + 2 * configs.len(), |c, _| {
        if c == 0 {
            let frame = technique_frame(&gpu, Technique::Phong, size, &mut profiler)?;
            return Ok::<_, ExperimentError>(Sample { ms: frame.ms, output: None });
        }
        let renderer = &prepared[(c - 1) / 2].1;
        profiler.reset();
        if c % 2 == 1 {
            renderer.update_environment(&gpu, &mut profiler)?;
            Ok(Sample::timed(profiler.resolve(0)?.pass_ms("ao_environment"), None))
        } else {
            let frame = renderer.frame(&gpu, size, &mut profiler)?;
            Ok(Sample::timed(profiler.resolve(0)?.pass_ms("ao"), Some(frame.image)))
        }
    })?;
    let phong = &timings[0];
    for (i, (s, (pre, _))) in configs.iter().zip(&prepared).enumerate() {
        let (update, frame) = (&timings[1 + 2 * i], &timings[2 + 2 * i]);
        let (_, unclustered, truth) = baselines.iter().find(|(k, _, _)| *k == (s.radius, s.bits)).expect("made above");
        let image = frame.last.as_ref().expect("an AO frame gives its image");
        let against_unclustered = compare(image, unclustered)?;
        let against_truth = compare(image, truth)?;
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
            .set_timing("update_ms", update)
            .set_timing("ao_ms", frame)
            .set_timing("phong_ms", phong)
            .set("overhead", frame.median() / phong.median())
            .set_estimate("overhead", frame.paired_ratio(phong))
            .set("rmse_unclustered", against_unclustered.rmse)
            .set("rmse_unclustered_of_peak", against_unclustered.rmse / unclustered.max_value().max(1e-12) as f64)
            .set("rmse_truth", against_truth.rmse);
        table.push(row);
        table1.push(table1_row(&plan.data_set, scene, s, pre));
    }
    out_folder.save_rows("ao", &table)?;
    progress.finish();
    drop(gpu);
    let report = AoReport { table, table1 };
    report.write(out_folder.path())?;
    Ok(report)
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
fn step_weights(configs: &[AoSettings], runs: u32) -> Vec<f64> {
    let mut weights = Vec::new();
    let mut seen: Vec<(u32, u32)> = Vec::new();
    for s in configs {
        let r = f64::from(s.radius);
        if !seen.contains(&(s.radius, s.bits)) {
            seen.push((s.radius, s.bits));
            weights.extend([1.5 * r, 4.0 * r]);
        }
        weights.push(r);
    }
    // The shared rounds: every configuration's frame and update, and Phong's.
    weights.push(f64::from(runs) * (0.1 + configs.len() as f64 * 0.2));
    weights
}

impl AoReport {
    /// ao.csv, ao.json, ao_table1.csv, ao.md and the two charts in `out`.
    pub fn write(&self, out: &Path) -> Result<(), ExperimentError> {
        let (table, table1) = (&self.table, &self.table1);
        table.write_csv(out.join("ao.csv"))?;
        table.write_json(out.join("ao.json"))?;
        table1.write_csv(out.join("ao_table1.csv"))?;
        let markdown = format!(
        "{}## Ambient occlusion (bench ao)\n\n{}\n\n## Table 1 shape: the paper's preprocessing beside ours\n\n\
         Paper: Opteron 852, 4 per process, minutes as seconds; ours: this machine (the preprocessing runs where `ao.backend` puts it; \
         a one-off cost, timed once as it runs, where frame and update times are medians of shared rounds) \
         (histograms_s is our histograms with the nearest-codeword assignment, streamed together; \
         local_histograms is what the unpacked histograms would take, which we never hold).\n\n{}\n",
        table.run.as_ref().map(|r| r.markdown()).unwrap_or_default(),
        table.to_markdown(),
        table1.to_markdown()
    );
        let md = out.join("ao.md");
        std::fs::write(&md, &markdown).map_err(|source| BenchError::Write { path: md, source })?;
        let by_metric = |y: &'static str, x: &'static str| -> Vec<Series> {
            Metric::ALL
                .iter()
                .map(|m| Series::new(m.name(), table.points(|r| r.text("metric") == m.name(), x, y)))
                .filter(|s| !s.points.is_empty())
                .collect()
        };
        plot_lines(
            out.join("ao_error_vs_clusters.png"),
            &Chart::new("AO: image RMSE against the unclustered histograms", "n_c", "RMSE")
                .x_scale(AxisScale::Log10)
                .run_caption(table.run.as_ref()),
            &by_metric("rmse_unclustered", "clusters"),
        )?;
        plot_error_vs_time(
            out.join("ao_error_vs_preprocessing.png"),
            &Chart::new("AO: RMSE against the ground truth over preprocessing time", "preprocessing (s)", "RMSE")
                .run_caption(table.run.as_ref()),
            &by_metric("rmse_truth", "preprocess_s"),
        )?;
        Ok(())
    }
}

/// What the terminal shows: one short line per configuration; every column is
/// in the files.
pub fn print_summary(table: &BenchTable) {
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

/// The image `bench ao` renders without `--size`.
pub const DEFAULT_IMAGE: u32 = 256;

/// The scene `bench ao` measures without `--scene`/`--volume`: the Cornell box
/// of the paper's Fig. 5, the same file the tests render.
pub fn default_scene(overrides: &[String]) -> Result<Scene, SceneError> {
    const CORNELL_BOX: &str = include_str!("../../../../tests/scenes/cornell-box.toml");
    let base = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scenes");
    crate::techniques::scene_from_toml_str(CORNELL_BOX, &base, "cornell-box", overrides)
}

/// The data set's name in the tables: the scene or volume file's stem, or
/// the default scene's.
pub fn data_set_name(path: Option<&std::path::Path>) -> String {
    path.and_then(|p| p.file_stem()).map_or("cornell-box".into(), |s| s.to_string_lossy().into_owned())
}
