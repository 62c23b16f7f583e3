//! `sweeplab bench lights` as an experiment: the light volume against the
//! selective light updates paper (Sundén and Ropinski 2015): Table 1 (entire
//! updates with sequential and coherence-based propagation, selective updates
//! of one light), Figure 10 (entire update time over 1-40 lights of one
//! direction), the memory of one illumination volume against one per light,
//! incremental mode, and the error of a full frame against the ground truth
//! next to its time. Each part measures its configurations side by side in
//! the shared shuffled rounds of [`Interleaved`]; ratios between them come
//! from paired rounds. The measuring pieces are in [`measure`].

mod experiment;
pub mod measure;
mod report;

pub use experiment::LightsExperiment;

use crate::bench::estimate::readable;
use crate::bench::{
    fit_line, plot_error_vs_time, plot_lines, AxisScale, BenchError, BenchRow, BenchTable, Chart, ExperimentError,
    Interleaved, OutFolder, Progress, RunInfo, Series, Timings,
};
use crate::linear_image::LinearImage;
use crate::metrics::compare;
use crate::render::{GpuScene, VolumeTexels};
use crate::scene::{Falloff, Light, LightKind, Scene};
use crate::techniques::lightvolume::{CostEstimate, LightVolumeRenderer};
use crate::techniques::{render, Technique};
use crate::vk::{Context, Profiler};
use glam::Vec3;
use measure::{
    grid_text, lightvolume_scene, resolution_label, scaling_lights, table1_lights, LightsMeter, Update, UpdateConfig,
    UpdateMeasurement,
};
use std::path::Path;

/// The paper's Table 1, Engine (256x256x256) rows: (illumination scale, lights,
/// sequential, coherent, state change, on/off) in ms on a GTX 670.
const PAPER_ENGINE: [(u32, u32, [f64; 4]); 4] = [
    (1, 2, [129.0, 114.0, 72.0, 30.0]),
    (1, 3, [192.0, 124.0, 72.0, 30.0]),
    (4, 2, [22.0, 18.0, 11.0, 5.0]),
    (4, 3, [30.0, 20.0, 11.0, 5.0]),
];
/// Figure 10: ms per added light on a GTX 670 (coherent "1-2 ms", sequential 30 ms).
const PAPER_SLOPE_COHERENT: f64 = 1.5;
const PAPER_SLOPE_SEQUENTIAL: f64 = 30.0;
const PAPER_DEVICE: &str = "paper (GTX 670)";

const MAX_TABLE1_LIGHTS: u32 = 16;
const MAX_SCALING_LIGHTS: u32 = 256;

/// The ratios of a Table 1 row: (column, numerator, denominator).
const RATIOS: [(&str, Update, Update); 4] = [
    ("sequential_over_coherent", Update::EntireSequential, Update::EntireCoherent),
    ("coherent_over_state_change", Update::EntireCoherent, Update::StateChange),
    ("coherent_over_toggle", Update::EntireCoherent, Update::Toggle),
    ("state_change_over_toggle", Update::StateChange, Update::Toggle),
];

/// What `bench lights` measures.
#[derive(Clone, Debug)]
pub struct LightsPlan {
    /// Data voxels per illumination voxel of the Table 1 rows.
    pub scales: Vec<u32>,
    /// Lights of the Table 1 rows (2..=16).
    pub light_counts: Vec<u32>,
    /// Light counts of the scaling test (1..=256).
    pub scaling_counts: Vec<u32>,
    /// Scale of the scaling test and of incremental mode.
    pub scaling_scale: u32,
    /// Scales of the error-against-time rows.
    pub error_scales: Vec<u32>,
    /// Passes per frame of incremental mode (1..=64).
    pub incremental_passes: Vec<u32>,
    /// The rounds each part's configurations share.
    pub rounds: Interleaved,
    /// Image of the error rows.
    pub image: (u32, u32),
    pub volume_texels: VolumeTexels,
}

impl LightsPlan {
    /// The smallest plan with every part: DR*1/4 alone, two lights, a slope
    /// over one and two lights, one incremental setting (tests, a quick look).
    pub fn smallest(rounds: Interleaved, image: (u32, u32)) -> LightsPlan {
        LightsPlan {
            scales: vec![4],
            light_counts: vec![2],
            scaling_counts: vec![1, 2],
            scaling_scale: 4,
            error_scales: vec![4],
            incremental_passes: vec![1],
            rounds,
            image,
            volume_texels: VolumeTexels::Native,
        }
    }

    /// Every list non-empty and in range; the error names the flag.
    pub fn check(&self) -> Result<(), ExperimentError> {
        fn invalid<T>(m: String) -> Result<T, ExperimentError> {
            Err(ExperimentError::Invalid(m))
        }
        let scales_ok = |name: &str, scales: &[u32]| -> Result<(), ExperimentError> {
            if scales.is_empty() {
                return invalid(format!("--{name}: give at least one scale (1, 2 or 4)"));
            }
            if let Some(s) = scales.iter().find(|s| !matches!(s, 1 | 2 | 4)) {
                return invalid(format!(
                    "--{name}: {s} is not an illumination volume scale; use 1, 2 or 4 data voxels per illumination voxel"
                ));
            }
            Ok(())
        };
        scales_ok("scales", &self.scales)?;
        scales_ok("error-scales", &self.error_scales)?;
        scales_ok("scaling-scale", &[self.scaling_scale])?;
        if let Some(n) = self.incremental_passes.iter().find(|n| !(1..=64).contains(*n)) {
            return invalid(format!("--incremental-passes: {n} is outside 1..=64 passes per frame"));
        }
        if self.light_counts.is_empty() {
            return invalid(format!("--light-counts: give at least one light count (2..={MAX_TABLE1_LIGHTS})"));
        }
        if let Some(n) = self.light_counts.iter().find(|n| !(2..=MAX_TABLE1_LIGHTS).contains(n)) {
            return invalid(format!(
                "--light-counts: {n} is outside 2..={MAX_TABLE1_LIGHTS} (toggling one light needs another left on; \
                 more than {MAX_TABLE1_LIGHTS} is the scaling test's job)"
            ));
        }
        if self.scaling_counts.is_empty() {
            return invalid(format!("--scaling-counts: give at least one light count (1..={MAX_SCALING_LIGHTS})"));
        }
        if let Some(n) = self.scaling_counts.iter().find(|n| !(1..=MAX_SCALING_LIGHTS).contains(n)) {
            return invalid(format!("--scaling-counts: {n} is outside 1..={MAX_SCALING_LIGHTS}"));
        }
        Ok(())
    }
}

/// Every part of `bench lights` on `scene` (its light volume settings kept),
/// each part's rows saved in `out_folder` as soon as it ends (an interrupted
/// run keeps them); the charts and the Markdown report are written at the end.
pub fn run(
    ctx: &Context,
    scene: &Scene,
    plan: &LightsPlan,
    run: RunInfo,
    out_folder: &OutFolder,
    profiler_capacity: u32,
) -> Result<Report, ExperimentError> {
    plan.check()?;
    let mut scene = scene.clone();
    // The light volume carries transmittance alone: optical model (i).
    scene.reference.model = Technique::LightVolume.reference_model(&scene);
    let mut meter = LightsMeter {
        ctx,
        profiler: Profiler::new(ctx, profiler_capacity)?,
        progress: Progress::weighted(step_weights(plan, plan.image)),
        rounds: plan.rounds,
        orders: Vec::new(),
    };
    let mut report = Report { run: plan.rounds.recorded_in(run), ..Report::default() };
    table1(plan, &mut meter, &scene, &mut report)?;
    report.save(out_folder)?;
    inside(plan, &mut meter, &scene, &mut report)?;
    report.save(out_folder)?;
    scaling(plan, &mut meter, &scene, &mut report)?;
    report.save(out_folder)?;
    incremental(plan, &mut meter, &scene, &mut report)?;
    report.save(out_folder)?;
    error_rows(plan, &mut meter, &scene, plan.image, &mut report)?;
    meter.progress.finish();
    report.orders = std::mem::take(&mut meter.orders);
    report.write(plan, out_folder.path())?;
    Ok(report)
}

/// The relative size of each progress step in the order the parts take them
/// (per part its set-up, then its rounds), in passes over an illumination
/// volume at DR*1 (a pass at scale s costs about 1/s^3 of one; sequential
/// propagation runs a pass per light, a coherent one about a pass per four
/// lights, a selective update one or two, with an untimed one to bring the
/// volume back); a ground truth about two such passes per light at 256x256.
pub fn step_weights(plan: &LightsPlan, (width, height): (u32, u32)) -> Vec<f64> {
    let pass = |scale: u32| 1.0 / f64::from(scale.max(1)).powi(3);
    let coherent = |count: u32| 1.0 + f64::from(count) / 4.0;
    let runs = f64::from(plan.rounds.most_runs());
    let grid = |counts: &[u32], per: &dyn Fn(u32) -> f64| -> f64 {
        plan.scales.iter().flat_map(|&s| counts.iter().map(move |&n| (s, n))).map(|(s, n)| per(n) * pass(s)).sum()
    };
    let entire = |n: u32| f64::from(n) + coherent(n);
    let table1 = [grid(&plan.light_counts, &entire), runs * grid(&plan.light_counts, &|n| entire(n) + 4.0)];
    let inside = grid(&[1], &|_| 8.0);
    let scaling = pass(plan.scaling_scale) * plan.scaling_counts.iter().map(|&n| entire(n)).sum::<f64>();
    let most = plan.light_counts.iter().copied().max().unwrap_or(2);
    let incremental = coherent(most) * pass(plan.scaling_scale) * (1 + plan.incremental_passes.len()) as f64;
    let truth = 2.0 * f64::from(most) * f64::from(width) * f64::from(height) / 65536.0;
    let frames = 0.01 + plan.error_scales.iter().map(|&s| 3.0 * coherent(most) * pass(s)).sum::<f64>();
    let mut weights = table1.to_vec();
    weights.extend([inside, runs * inside, scaling, runs * scaling, 0.01, runs * incremental]);
    weights.extend([truth, truth, frames, runs * frames]);
    weights
}

/// Every part's rows, saved as each part ends.
#[derive(Default)]
pub struct Report {
    updates: BenchTable,
    table1: BenchTable,
    inside: BenchTable,
    scaling: BenchTable,
    scaling_fit: BenchTable,
    memory: BenchTable,
    incremental: BenchTable,
    error: BenchTable,
    run: RunInfo,
    orders: Vec<(String, Vec<usize>)>,
}

/// `key`: `a` over `b`, the median of their ratios round by round with its
/// interval (below six rounds the ratio of their medians, without one).
fn set_ratio<A, B>(row: &mut BenchRow, key: &str, a: &Timings<A>, b: &Timings<B>) {
    row.set(key, a.median() / b.median()).set_estimate(key, a.paired_ratio(b));
}

/// The scenes of a part's renderers, uploaded; a renderer borrows its scene's upload.
fn upload<'s>(ctx: &'s Context, scenes: &'s [Scene]) -> Result<Vec<GpuScene<'s>>, ExperimentError> {
    Ok(scenes.iter().map(|s| GpuScene::upload(ctx, s)).collect::<Result<Vec<_>, _>>()?)
}

fn table1(
    plan: &LightsPlan,
    meter: &mut LightsMeter,
    scene: &Scene,
    report: &mut Report,
) -> Result<(), ExperimentError> {
    let data = scene.volume.name.clone();
    meter.progress.start_step("Table 1: a light volume per scale, light count and propagation");
    // Per scale, sequential propagation (its own renderer settings) and coherent.
    let scenes: Vec<Scene> = plan
        .scales
        .iter()
        .flat_map(|&scale| {
            [(false, CostEstimate::Entire), (true, CostEstimate::Selective)]
                .map(|(coherent, estimate)| lightvolume_scene(scene, scale, coherent, estimate, |_| {}))
        })
        .collect();
    let gpus = upload(meter.ctx, &scenes)?;
    let (mut volumes, mut configs, mut rows) = (Vec::new(), Vec::new(), Vec::new());
    for (i, &scale) in plan.scales.iter().enumerate() {
        for &count in &plan.light_counts {
            let lights = table1_lights(count as usize);
            // Configurations in the order of Update::ALL; the three coherent ones share a renderer.
            for (gpu, updates) in [
                (&gpus[2 * i], &[Update::EntireSequential][..]),
                (&gpus[2 * i + 1], &[Update::EntireCoherent, Update::StateChange, Update::Toggle][..]),
            ] {
                volumes.push(meter.volume(gpu, &lights)?);
                configs.extend(updates.iter().map(|&u| UpdateConfig::new(volumes.len() - 1, u, &lights)));
            }
            rows.push((scale, count));
        }
    }
    meter.progress.finish_step();
    let measured = meter.measure_updates("Table 1 updates", &mut volumes, &configs)?;
    for (&(scale, count), row_of) in rows.iter().zip(measured.chunks(Update::ALL.len())) {
        let mut ours = BenchRow::new();
        ours.set("source", "ours (lavapipe)").set("data_set", &data).set("resolution", resolution_label(scale));
        ours.set("lights", count);
        let mut counts = BenchRow::new();
        for (&update, m) in Update::ALL.iter().zip(row_of) {
            let ms = m.timing.median();
            ours.set("grid", grid_text(m.grid));
            ours.set_timing(update.column(), &m.timing);
            counts.set(format!("{}_passes", update.column().trim_end_matches("_ms")), m.passes());
            counts.set(format!("{}_dispatches", update.column().trim_end_matches("_ms")), m.timing.last.dispatches);
            let samples = m.timing.samples();
            let mut row = BenchRow::new();
            row.set("resolution", resolution_label(scale)).set("scale", scale).set("grid", grid_text(m.grid));
            let last = &m.timing.last;
            row.set("lights", count).set("update", update.name()).set("kind", format!("{:?}", m.kind()));
            row.set_timing("gpu_ms", &m.timing);
            row.set("min_ms", samples.iter().copied().fold(f64::NAN, f64::min));
            row.set("max_ms", samples.iter().copied().fold(f64::NAN, f64::max));
            row.set("timed", samples.len()).set("passes", m.passes()).set("propagations", m.propagations());
            row.set("dispatches", last.dispatches).set("barriers", last.barriers);
            row.set("ms_per_pass", ms / m.passes().max(1) as f64);
            row.set("recorded", last.update.recorded).set("reused", last.update.reused).set("reason", m.reason());
            report.updates.push(row);
            if update == Update::EntireCoherent {
                report.memory.push(memory_row(scale, count, "coherent", m));
            }
        }
        // Update::ALL's order is the declaration order, so `as usize` indexes row_of.
        for (key, a, b) in RATIOS {
            set_ratio(&mut ours, key, &row_of[a as usize].timing, &row_of[b as usize].timing);
        }
        for (k, v) in counts.iter() {
            ours.set(k, v.clone());
        }
        report.table1.push(ours);
        if let Some((_, _, paper)) = PAPER_ENGINE.iter().find(|(s, n, _)| *s == scale && *n == count) {
            let mut row = BenchRow::new();
            row.set("source", PAPER_DEVICE).set("data_set", "Engine 256x256x256");
            row.set("resolution", resolution_label(scale)).set("lights", count).set("grid", "");
            for (update, ms) in Update::ALL.iter().zip(paper) {
                row.set(update.column(), *ms);
            }
            for (key, a, b) in RATIOS {
                row.set(key, paper[a as usize] / paper[b as usize]);
            }
            report.table1.push(row);
        }
    }
    Ok(())
}

/// A point light inside the volume (at its centre: all six groups, the paper's
/// section 7.3) beside the same light outside (two or three groups), entire
/// coherent updates; the centre row's `over_outside` is its paired ratio.
fn inside(
    plan: &LightsPlan,
    meter: &mut LightsMeter,
    scene: &Scene,
    report: &mut Report,
) -> Result<(), ExperimentError> {
    let point = |position: Vec3| Light {
        kind: LightKind::Point { position },
        color: Vec3::ONE,
        intensity: 1.0,
        falloff: Falloff::None,
    };
    let places = [("centre", point(Vec3::ZERO)), ("outside", point(Vec3::new(1.2, 0.8, 0.6)))];
    meter.progress.start_step("a point light inside and outside: a light volume each");
    let scenes: Vec<Scene> =
        plan.scales.iter().map(|&scale| lightvolume_scene(scene, scale, true, CostEstimate::Entire, |_| {})).collect();
    let gpus = upload(meter.ctx, &scenes)?;
    let (mut volumes, mut configs) = (Vec::new(), Vec::new());
    for gpu in &gpus {
        for (_, light) in &places {
            volumes.push(meter.volume(gpu, &[*light])?);
            configs.push(UpdateConfig::new(volumes.len() - 1, Update::EntireCoherent, &[*light]));
        }
    }
    meter.progress.finish_step();
    let measured = meter.measure_updates("point light inside and outside", &mut volumes, &configs)?;
    for (&scale, pair) in plan.scales.iter().zip(measured.chunks(places.len())) {
        for ((place, _), m) in places.iter().zip(pair) {
            let mut row = BenchRow::new();
            row.set("resolution", resolution_label(scale)).set("light", format!("point, {place}"));
            row.set_timing("gpu_ms", &m.timing).set("passes", m.passes()).set("dispatches", m.timing.last.dispatches);
            if *place == "centre" {
                set_ratio(&mut row, "over_outside", &m.timing, &pair[1].timing);
            }
            report.inside.push(row);
        }
    }
    Ok(())
}

/// One illumination volume (two with compensated sums) for any number of
/// lights, against one RGBA32F volume per light (the approach before the paper).
fn memory_row(scale: u32, count: u32, propagation: &str, m: &UpdateMeasurement) -> BenchRow {
    let voxel_bytes = 16 * m.grid.x as u64 * m.grid.y as u64 * m.grid.z as u64;
    let per_light = voxel_bytes * count as u64;
    let mut row = BenchRow::new();
    row.set("resolution", resolution_label(scale)).set("grid", grid_text(m.grid)).set("lights", count);
    row.set("propagation", propagation);
    row.set("illumination_bytes", m.illumination_bytes);
    row.set("rgba32f_volumes", m.illumination_bytes as f64 / voxel_bytes as f64);
    row.set("one_volume_per_light_bytes", per_light);
    row.set("per_light_over_ours", per_light as f64 / m.illumination_bytes as f64);
    row.set("slice_buffer_bytes", m.propagation_bytes);
    row.set("total_bytes", m.illumination_bytes + m.propagation_bytes);
    row
}

/// Incremental mode from an empty volume: frames until the update is complete,
/// and what each frame's update costs, beside one entire update in the same rounds.
fn incremental(
    plan: &LightsPlan,
    meter: &mut LightsMeter,
    scene: &Scene,
    report: &mut Report,
) -> Result<(), ExperimentError> {
    let scale = plan.scaling_scale;
    let count = plan.light_counts.iter().copied().max().unwrap_or(2);
    let lights: Vec<Option<Light>> = table1_lights(count as usize).into_iter().map(Some).collect();
    let label = format!("incremental {} {count} lights", resolution_label(scale));
    meter.progress.start_step(&format!("{label}: a light volume per passes a frame"));
    let mut scenes = vec![lightvolume_scene(scene, scale, true, CostEstimate::Entire, |_| {})];
    scenes.extend(
        plan.incremental_passes
            .iter()
            .map(|&n| lightvolume_scene(scene, scale, true, CostEstimate::Passes, |lv| lv.max_passes_per_frame = n)),
    );
    let gpus = upload(meter.ctx, &scenes)?;
    let mut renderers = gpus.iter().map(LightVolumeRenderer::new).collect::<Result<Vec<_>, _>>()?;
    meter.progress.finish_step();
    let (entire, incremental) = renderers.split_first_mut().expect("the entire update's renderer comes first");
    let rounds = meter.incremental(&label, entire, incremental, &lights)?;
    for (&n, (total, most)) in plan.incremental_passes.iter().zip(&rounds.runs) {
        let frames = &total.last.frame_ms;
        let mut row = BenchRow::new();
        row.set("resolution", resolution_label(scale)).set("grid", grid_text(total.last.grid)).set("lights", count);
        row.set("max_passes_per_frame", n).set("frames", frames.len());
        row.set_timing("max_frame_ms", most);
        row.set_timing("total_ms", total).set_timing("entire_update_ms", &rounds.entire);
        set_ratio(&mut row, "total_over_entire", total, &rounds.entire);
        report.incremental.push(row);
    }
    Ok(())
}

/// One least-squares slope per round through that round's (lights, ms)
/// points (none where fewer than two light counts counted), as a series whose
/// median and interval are the slope's: each round's slope sees one state of
/// the machine, and rounds that went wrong only move the tails.
fn slope_per_round(points: &[(f64, &Timings<impl Sized>)]) -> Timings<()> {
    let rounds = points.iter().map(|(_, t)| t.rounds.len()).min().unwrap_or(0);
    let slopes = (0..rounds)
        .map(|r| {
            let round: Vec<(f64, f64)> = points.iter().filter_map(|(x, t)| t.rounds[r].map(|ms| (*x, ms))).collect();
            fit_line(&round).map(|f| f.slope)
        })
        .collect();
    Timings { rounds: slopes, last: () }
}

fn scaling(
    plan: &LightsPlan,
    meter: &mut LightsMeter,
    scene: &Scene,
    report: &mut Report,
) -> Result<(), ExperimentError> {
    let scale = plan.scaling_scale;
    let propagations = [(Update::EntireCoherent, "coherent"), (Update::EntireSequential, "sequential")];
    let label = format!("Figure 10 {}", resolution_label(scale));
    meter.progress.start_step(&format!("{label}: a light volume per light count and propagation"));
    let scenes: Vec<Scene> = propagations
        .iter()
        .map(|(u, _)| lightvolume_scene(scene, scale, *u == Update::EntireCoherent, CostEstimate::Entire, |_| {}))
        .collect();
    let gpus = upload(meter.ctx, &scenes)?;
    let (mut volumes, mut configs) = (Vec::new(), Vec::new());
    for &count in &plan.scaling_counts {
        let lights = scaling_lights(count);
        for (gpu, (update, _)) in gpus.iter().zip(&propagations) {
            volumes.push(meter.volume(gpu, &lights)?);
            configs.push(UpdateConfig::new(volumes.len() - 1, *update, &lights));
        }
    }
    meter.progress.finish_step();
    let measured = meter.measure_updates(&label, &mut volumes, &configs)?;
    for (&count, pair) in plan.scaling_counts.iter().zip(measured.chunks(propagations.len())) {
        for ((update, propagation), m) in propagations.iter().zip(pair) {
            let mut row = BenchRow::new();
            row.set("resolution", resolution_label(scale)).set("grid", grid_text(m.grid)).set("lights", count);
            row.set("propagation", *propagation).set_timing("gpu_ms", &m.timing).set("passes", m.passes());
            row.set("dispatches", m.timing.last.dispatches).set("barriers", m.timing.last.barriers);
            row.set("ms_per_pass", m.timing.median() / m.passes().max(1) as f64);
            report.scaling.push(row);
            if *update == Update::EntireCoherent {
                report.memory.push(memory_row(scale, count, "coherent (scaling)", m));
            }
        }
    }
    let series = |i: usize| -> Vec<(f64, &Timings<_>)> {
        plan.scaling_counts
            .iter()
            .zip(measured.chunks(propagations.len()))
            .map(|(&n, p)| (n as f64, &p[i].timing))
            .collect()
    };
    let slopes: Vec<Timings<()>> = (0..propagations.len()).map(|i| slope_per_round(&series(i))).collect();
    // The ratio's interval needs six rounds whose coherent slope is above 0.
    for (i, (propagation, paper)) in
        [("coherent", PAPER_SLOPE_COHERENT), ("sequential", PAPER_SLOPE_SEQUENTIAL)].into_iter().enumerate()
    {
        // The intercept and r^2 of the line through each light count's median.
        let medians: Vec<(f64, f64)> = series(i).iter().map(|(n, t)| (*n, t.median())).collect();
        let fit = fit_line(&medians);
        let mut row = BenchRow::new();
        row.set("propagation", propagation).set("resolution", resolution_label(scale));
        row.set_timing("ms_per_added_light", &slopes[i]);
        // A cost per light whose interval holds 0 reads "within noise", not as a (negative) cost.
        if let Some(e) = slopes[i].estimate() {
            row.set("ms_per_added_light_verdict", e.verdict().name());
        }
        row.set("intercept_ms", fit.map_or(f64::NAN, |f| f.intercept));
        row.set("r_squared", fit.map_or(f64::NAN, |f| f.r_squared));
        row.set("paper_ms_per_added_light", paper);
        row.set(
            "paper_note",
            if propagation == "coherent" { "1-2 ms, GTX 670, 256^3" } else { "30 ms, GTX 670, 256^3" },
        );
        report.scaling_fit.push(row);
    }
    if slopes.iter().all(|s| s.median().is_finite()) {
        let mut row = BenchRow::new();
        row.set("propagation", "sequential/coherent").set("resolution", resolution_label(scale));
        set_ratio(&mut row, "ms_per_added_light", &slopes[1], &slopes[0]);
        row.set("paper_ms_per_added_light", PAPER_SLOPE_SEQUENTIAL / PAPER_SLOPE_COHERENT);
        row.set("paper_note", "slope ratio (paper: 15-30)");
        report.scaling_fit.push(row);
    }
    Ok(())
}

fn error_rows(
    plan: &LightsPlan,
    meter: &mut LightsMeter,
    scene: &Scene,
    (width, height): (u32, u32),
    report: &mut Report,
) -> Result<(), ExperimentError> {
    let ctx = meter.ctx;
    let count = plan.light_counts.iter().copied().max().unwrap_or(2);
    let mut lit = scene.clone();
    lit.lights = table1_lights(count as usize);
    let texels = plan.volume_texels;
    // Two ground truths: model (i) with one transmittance, and with coloured
    // extinction (`reference.chromatic`), each propagation against its own.
    let mut references = Vec::new();
    for chromatic in [false, true] {
        let what = if chromatic { "chromatic" } else { "grey" };
        meter.progress.start_step(&format!("{width}x{height} ground truth (GPU, model i, {what}), {count} lights"));
        let mut truth = lit.clone();
        truth.reference.chromatic = chromatic;
        let gpu = GpuScene::upload_with(ctx, &truth, texels)?;
        references.push(render(&gpu, Technique::Reference, width, height, &mut meter.profiler)?.image);
        meter.progress.finish_step();
    }
    let reference: &LinearImage = &references[0];
    let all_on: Vec<Option<Light>> = lit.lights.iter().copied().map(Some).collect();
    // The default (the paper's: medium shared by a pass's lights, coloured), the
    // accurate per-light integration, and the per-light integration of model (i)
    // (the default before chromatic propagation), each against its own ground truth.
    let variants: Vec<(u32, &str, bool, bool)> = plan
        .error_scales
        .iter()
        .flat_map(|&scale| {
            [
                ("lightvolume", true, true),
                ("lightvolume-per-light", false, true),
                ("lightvolume-per-light-grey", false, false),
            ]
            .map(|(technique, shared, chromatic)| (scale, technique, shared, chromatic))
        })
        .collect();
    meter.progress.start_step(&format!("{width}x{height} DVR and light volume frames: a renderer each"));
    let base = ctx.memory.device_local_bytes();
    let dvr = GpuScene::upload_with(ctx, &lit, texels)?;
    let scenes: Vec<Scene> = variants
        .iter()
        .map(|&(scale, _, shared, chromatic)| {
            lightvolume_scene(&lit, scale, true, CostEstimate::Passes, |lv| {
                (lv.shared_medium, lv.chromatic) = (shared, chromatic)
            })
        })
        .collect();
    let mut gpus = Vec::new();
    for s in &scenes {
        let before = ctx.memory.device_local_bytes();
        let gpu = GpuScene::upload_with(ctx, s, texels)?;
        gpus.push((gpu, ctx.memory.device_local_bytes() - before));
    }
    let (mut renderers, mut memory) = (Vec::new(), Vec::new());
    for (gpu, upload_bytes) in &gpus {
        let start = ctx.memory.device_local_bytes();
        ctx.memory.reset_peak();
        let mut renderer = LightVolumeRenderer::new(gpu)?;
        // Untimed: records the passes and compiles the shaders, and shows the frame's memory.
        meter.profiler.reset();
        renderer.render(&all_on, width, height, &mut meter.profiler, false)?;
        meter.profiler.resolve(0)?;
        // A frame's device-local memory as if it ran alone: what the device
        // held before this part, its scene, and its renderer's peak.
        memory.push(base + upload_bytes + (ctx.memory.device_local_peak() - start));
        renderers.push(renderer);
    }
    meter.progress.finish_step();
    let frames =
        meter.full_frames(&format!("{width}x{height} frames"), &dvr, &mut renderers, &all_on, (width, height))?;
    let (dvr, light_volume) = frames.split_first().expect("DVR is configuration 0");
    let stats = compare(&dvr.timing.last.image, reference)?;
    let mut row = BenchRow::new();
    row.set("technique", "dvr").set("chromatic", false).set("width", width).set("height", height).set("lights", count);
    row.set_timing("gpu_ms", &dvr.timing).set("rmse", stats.rmse).set("max_abs", stats.max_abs).set("psnr", stats.psnr);
    row.set("dispatches", dvr.timing.last.dispatches);
    report.error.push(row);
    for ((&(scale, technique, _, chromatic), f), bytes) in variants.iter().zip(light_volume).zip(memory) {
        let last = &f.timing.last;
        let frame =
            last.light_volume.as_ref().ok_or_else(|| ExperimentError::Invalid("no light volume frame".into()))?;
        let stats = compare(&last.image, &references[chromatic as usize])?;
        let mut row = BenchRow::new();
        row.set("technique", technique)
            .set("chromatic", chromatic)
            .set("width", width)
            .set("height", height)
            .set("lights", count);
        row.set("resolution", resolution_label(scale)).set("grid", grid_text(frame.grid));
        row.set_timing("gpu_ms", &f.timing).set("rmse", stats.rmse).set("max_abs", stats.max_abs);
        row.set("psnr", stats.psnr).set("dispatches", last.dispatches);
        row.set_timing("update_ms", &f.update_ms)
            .set_timing("raycast_ms", &f.raycast_ms)
            .set("passes", frame.update.plan.passes.len());
        row.set("gpu_memory_bytes", bytes);
        report.error.push(row);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plan() -> LightsPlan {
        LightsPlan::smallest(Interleaved::fixed(1, 1).unwrap(), (16, 16))
    }

    #[test]
    fn a_tiny_plan_is_accepted_and_each_bad_list_is_named() {
        assert!(plan().check().is_ok());
        type Spoil = fn(&mut LightsPlan);
        let bad: [(&str, Spoil); 6] = [
            ("--scales", |p| p.scales = vec![3]),
            ("--error-scales", |p| p.error_scales.clear()),
            ("--scaling-scale", |p| p.scaling_scale = 8),
            ("--incremental-passes", |p| p.incremental_passes = vec![65]),
            ("--light-counts", |p| p.light_counts = vec![1]),
            ("--scaling-counts", |p| p.scaling_counts = vec![257]),
        ];
        for (flag, spoil) in bad {
            let mut p = plan();
            spoil(&mut p);
            let e = p.check().unwrap_err().to_string();
            assert!(e.starts_with(flag), "{flag}: {e}");
        }
    }

    #[test]
    fn the_progress_weights_cover_every_step_of_the_plan() {
        // Each of the five parts: its set-up and its rounds; the error rows'
        // two ground truths before theirs.
        let p = plan();
        let weights = step_weights(&p, p.image);
        assert_eq!(weights.len(), 5 * 2 + 2);
        assert!(weights.iter().all(|w| *w > 0.0));
        // More rounds weigh the rounds more, the set-ups and ground truths alike.
        let more = step_weights(&LightsPlan { rounds: Interleaved::fixed(6, 1).unwrap(), ..p.clone() }, p.image);
        for (i, (a, b)) in weights.iter().zip(&more).enumerate() {
            let rounds = [1, 3, 5, 7, 11].contains(&i);
            assert_eq!(b / a > 1.0, rounds, "step {i}: {a} and {b}");
        }
    }
}
