//! `sweeplab bench lights` as an experiment: the light volume against the
//! selective light updates paper (Sundén and Ropinski 2015): Table 1 (entire
//! updates with sequential and coherence-based propagation, selective updates
//! of one light), Figure 10 (entire update time over 1-40 lights of one
//! direction), the memory of one illumination volume against one per light,
//! incremental mode, and the error of a full frame against the ground truth
//! next to its time. The measuring pieces are in [`super::lights`].

use super::lights::{
    grid_text, lightvolume_scene, resolution_label, scaling_lights, table1_lights, LightsMeter, Update,
    UpdateMeasurement,
};
use crate::bench::{
    fit_line, median, plot_error_vs_time, plot_lines, technique_frame, AxisScale, BenchError, BenchRow, BenchTable,
    Chart, ExperimentError, Harness, OutFolder, Progress, RunInfo, Series,
};
use crate::lightvolume::CostEstimate;
use crate::linear_image::LinearImage;
use crate::metrics::compare;
use crate::render::{GpuScene, VolumeTexels};
use crate::scene::{Falloff, Light, LightKind, Scene};
use crate::techniques::{render, Technique};
use crate::vk::{Context, Profiler};
use glam::Vec3;
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
    /// Timed updates per measurement.
    pub repeat: u32,
    /// Image of the error rows.
    pub image: (u32, u32),
    pub volume_texels: VolumeTexels,
}

impl LightsPlan {
    /// Every list non-empty and in range; the error names the flag.
    pub fn check(&self) -> Result<Harness, ExperimentError> {
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
        Harness::new(0, self.repeat).map_err(|e| ExperimentError::Invalid(format!("--repeat: {e}")))
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
    let harness = plan.check()?;
    let mut scene = scene.clone();
    // The light volume carries transmittance alone: optical model (i).
    scene.reference.model = Technique::LightVolume.reference_model(&scene);
    let mut meter = LightsMeter {
        ctx,
        profiler: Profiler::new(ctx, profiler_capacity)?,
        progress: Progress::weighted(step_weights(plan, plan.image)),
        harness,
    };
    let mut report = Report { run, ..Report::default() };
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
    report.write(plan, out_folder.path())?;
    Ok(report)
}

/// The relative size of each progress step in the order the parts take them,
/// in passes over an illumination volume at DR*1 (a pass at scale s costs
/// about 1/s^3 of one; sequential propagation runs a pass per light, a
/// coherent one about a pass per four lights, a selective update one or two);
/// a ground truth about two such passes per light at 256x256.
pub fn step_weights(plan: &LightsPlan, (width, height): (u32, u32)) -> Vec<f64> {
    let pass = |scale: u32| 1.0 / f64::from(scale.max(1)).powi(3);
    let coherent = |count: u32| 1.0 + f64::from(count) / 4.0;
    let mut weights = Vec::new();
    for &scale in &plan.scales {
        for &count in &plan.light_counts {
            let sequential = f64::from(count);
            weights.extend([sequential, coherent(count), 1.0, 1.0].map(|passes| passes * pass(scale)));
        }
    }
    for &scale in &plan.scales {
        weights.extend([6.0 * pass(scale), 2.0 * pass(scale)]);
    }
    let scaling = pass(plan.scaling_scale);
    for &count in &plan.scaling_counts {
        weights.extend([coherent(count) * scaling, f64::from(count) * scaling]);
    }
    let most = plan.light_counts.iter().copied().max().unwrap_or(2);
    weights.extend(std::iter::repeat_n(coherent(most) * scaling, plan.incremental_passes.len()));
    let pixels = f64::from(width) * f64::from(height) / 65536.0;
    weights.extend([2.0 * f64::from(most) * pixels, 2.0 * f64::from(most) * pixels, 0.01]);
    for &scale in &plan.error_scales {
        weights.extend([
            coherent(most) * pass(scale),
            2.0 * f64::from(most) * pass(scale),
            2.0 * f64::from(most) * pass(scale),
        ]);
    }
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
}

fn table1(
    plan: &LightsPlan,
    meter: &mut LightsMeter,
    scene: &Scene,
    report: &mut Report,
) -> Result<(), ExperimentError> {
    let data = scene.volume.name.clone();
    for &scale in &plan.scales {
        for &count in &plan.light_counts {
            let lights = table1_lights(count as usize);
            let mut ours = BenchRow::new();
            ours.set("source", "ours (lavapipe)").set("data_set", &data).set("resolution", resolution_label(scale));
            ours.set("lights", count);
            let mut counts = BenchRow::new();
            let label = format!("{} {count} lights", resolution_label(scale));
            let mut measured = Vec::new();
            // Sequential propagation needs its own renderer; the other three share one.
            for (coherent, updates) in [
                (false, &[Update::EntireSequential][..]),
                (true, &[Update::EntireCoherent, Update::StateChange, Update::Toggle][..]),
            ] {
                let s = lightvolume_scene(
                    scene,
                    scale,
                    coherent,
                    if coherent { CostEstimate::Selective } else { CostEstimate::Entire },
                    |_| {},
                );
                let results = meter.measure_updates(&s, &lights, updates, &label)?;
                measured.extend(updates.iter().copied().zip(results));
            }
            for (update, m) in measured {
                let ms = m.timing.median();
                ours.set("grid", grid_text(m.grid));
                ours.set(update.column(), ms);
                counts.set(format!("{}_passes", update.column().trim_end_matches("_ms")), m.passes());
                counts.set(format!("{}_dispatches", update.column().trim_end_matches("_ms")), m.timing.last.dispatches);
                let mut row = BenchRow::new();
                row.set("resolution", resolution_label(scale)).set("scale", scale).set("grid", grid_text(m.grid));
                let last = &m.timing.last;
                row.set("lights", count).set("update", update.name()).set("kind", format!("{:?}", m.kind()));
                row.set("gpu_ms", ms);
                row.set("min_ms", m.timing.min());
                row.set("max_ms", m.timing.max());
                row.set("timed", m.timing.samples.len())
                    .set("passes", m.passes())
                    .set("propagations", m.propagations());
                row.set("dispatches", last.dispatches).set("barriers", last.barriers);
                row.set("ms_per_pass", ms / m.passes().max(1) as f64);
                row.set("recorded", last.update.recorded).set("reused", last.update.reused).set("reason", m.reason());
                report.updates.push(row);
                if update == Update::EntireCoherent {
                    report.memory.push(memory_row(scale, count, "coherent", &m));
                }
            }
            set_ratios(&mut ours);
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
                set_ratios(&mut row);
                report.table1.push(row);
            }
        }
    }
    Ok(())
}

/// A point light inside the volume (at its centre: all six groups, the paper's
/// section 7.3) beside the same light outside (two or three groups), entire
/// coherent updates.
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
    for &scale in &plan.scales {
        for (place, light) in [("centre", point(Vec3::ZERO)), ("outside", point(Vec3::new(1.2, 0.8, 0.6)))] {
            let s = lightvolume_scene(scene, scale, true, CostEstimate::Entire, |_| {});
            let label = format!("{} point light {place}", resolution_label(scale));
            let m = meter
                .measure_updates(&s, &[light], &[Update::EntireCoherent], &label)?
                .pop()
                .ok_or_else(|| ExperimentError::Invalid("no measurement".into()))?;
            let mut row = BenchRow::new();
            row.set("resolution", resolution_label(scale)).set("light", format!("point, {place}"));
            row.set("gpu_ms", m.timing.median()).set("passes", m.passes()).set("dispatches", m.timing.last.dispatches);
            report.inside.push(row);
        }
    }
    Ok(())
}

/// sequential/coherent, coherent/state change, coherent/toggle, state change/toggle.
fn set_ratios(row: &mut BenchRow) {
    let get = |u: Update| row.get_f64(u.column()).unwrap_or(f64::NAN);
    let (seq, coh, state, toggle) =
        (get(Update::EntireSequential), get(Update::EntireCoherent), get(Update::StateChange), get(Update::Toggle));
    row.set("sequential_over_coherent", seq / coh);
    row.set("coherent_over_state_change", coh / state);
    row.set("coherent_over_toggle", coh / toggle);
    row.set("state_change_over_toggle", state / toggle);
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
/// and what each frame's update costs, beside one entire update.
fn incremental(
    plan: &LightsPlan,
    meter: &mut LightsMeter,
    scene: &Scene,
    report: &mut Report,
) -> Result<(), ExperimentError> {
    let scale = plan.scaling_scale;
    let count = plan.light_counts.iter().copied().max().unwrap_or(2);
    let lights: Vec<Option<Light>> = table1_lights(count as usize).into_iter().map(Some).collect();
    let entire =
        meter.entire_update_ms(&lightvolume_scene(scene, scale, true, CostEstimate::Entire, |_| {}), &lights)?;
    for &n in &plan.incremental_passes {
        meter
            .progress
            .start_step(&format!("incremental {} {count} lights, {n} passes a frame", resolution_label(scale)));
        let s = lightvolume_scene(scene, scale, true, CostEstimate::Passes, |lv| lv.max_passes_per_frame = n);
        let run = meter.incremental(&s, &lights)?;
        meter.progress.finish_step();
        let frames = run.frame_ms;
        let mut row = BenchRow::new();
        row.set("resolution", resolution_label(scale)).set("grid", grid_text(run.grid)).set("lights", count);
        row.set("max_passes_per_frame", n).set("frames", frames.len());
        row.set("max_frame_ms", frames.iter().copied().fold(0.0, f64::max));
        row.set("total_ms", frames.iter().sum::<f64>()).set("entire_update_ms", entire);
        report.incremental.push(row);
    }
    Ok(())
}

fn scaling(
    plan: &LightsPlan,
    meter: &mut LightsMeter,
    scene: &Scene,
    report: &mut Report,
) -> Result<(), ExperimentError> {
    let scale = plan.scaling_scale;
    let mut points: [Vec<(f64, f64)>; 2] = [Vec::new(), Vec::new()];
    for &count in &plan.scaling_counts {
        let lights = scaling_lights(count);
        for (i, update) in [Update::EntireCoherent, Update::EntireSequential].into_iter().enumerate() {
            let propagation = if update == Update::EntireCoherent { "coherent" } else { "sequential" };
            let s = lightvolume_scene(scene, scale, update == Update::EntireCoherent, CostEstimate::Entire, |_| {});
            let label = format!("scaling {} {count} lights", resolution_label(scale));
            let m = meter
                .measure_updates(&s, &lights, &[update], &label)?
                .pop()
                .ok_or_else(|| ExperimentError::Invalid("no measurement".into()))?;
            let ms = m.timing.median();
            points[i].push((count as f64, ms));
            let mut row = BenchRow::new();
            row.set("resolution", resolution_label(scale)).set("grid", grid_text(m.grid)).set("lights", count);
            row.set("propagation", propagation).set("gpu_ms", ms).set("passes", m.passes());
            row.set("dispatches", m.timing.last.dispatches).set("barriers", m.timing.last.barriers);
            row.set("ms_per_pass", ms / m.passes().max(1) as f64);
            report.scaling.push(row);
            if update == Update::EntireCoherent {
                report.memory.push(memory_row(scale, count, "coherent (scaling)", &m));
            }
        }
    }
    for (i, (propagation, paper)) in
        [("coherent", PAPER_SLOPE_COHERENT), ("sequential", PAPER_SLOPE_SEQUENTIAL)].into_iter().enumerate()
    {
        let fit = fit_line(&points[i]);
        let mut row = BenchRow::new();
        row.set("propagation", propagation).set("resolution", resolution_label(scale));
        row.set("ms_per_added_light", fit.map_or(f64::NAN, |f| f.slope));
        row.set("intercept_ms", fit.map_or(f64::NAN, |f| f.intercept));
        row.set("r_squared", fit.map_or(f64::NAN, |f| f.r_squared));
        row.set("paper_ms_per_added_light", paper);
        row.set(
            "paper_note",
            if propagation == "coherent" { "1-2 ms, GTX 670, 256^3" } else { "30 ms, GTX 670, 256^3" },
        );
        report.scaling_fit.push(row);
    }
    if let (Some(c), Some(s)) = (fit_line(&points[0]), fit_line(&points[1])) {
        let mut row = BenchRow::new();
        row.set("propagation", "sequential/coherent").set("resolution", resolution_label(scale));
        row.set("ms_per_added_light", s.slope / c.slope);
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
        let gpu = GpuScene::upload_with(meter.ctx, &truth, texels)?;
        references.push(render(&gpu, Technique::Reference, width, height, &mut meter.profiler)?.image);
        meter.progress.finish_step();
    }
    let reference: &LinearImage = &references[0];
    let dvr = {
        let gpu = GpuScene::upload_with(meter.ctx, &lit, texels)?;
        // One untimed frame first: llvmpipe compiles the shader on first use.
        let harness = meter.harness.with_warm_up(1);
        harness.measure_step(&mut meter.progress, &format!("{width}x{height} unshaded DVR"), || {
            technique_frame(&gpu, Technique::Dvr, (width, height), &mut meter.profiler)
        })?
    };
    let stats = compare(&dvr.last.image, reference)?;
    let mut row = BenchRow::new();
    row.set("technique", "dvr").set("chromatic", false).set("width", width).set("height", height).set("lights", count);
    row.set("gpu_ms", dvr.median()).set("rmse", stats.rmse).set("max_abs", stats.max_abs).set("psnr", stats.psnr);
    row.set("dispatches", dvr.last.dispatches);
    report.error.push(row);
    let all_on: Vec<Option<Light>> = lit.lights.iter().copied().map(Some).collect();
    // The default (the paper's: medium shared by a pass's lights, coloured), the
    // accurate per-light integration, and the per-light integration of model (i)
    // (the default before chromatic propagation), each against its own ground truth.
    let variants = plan.error_scales.iter().flat_map(|&scale| {
        [
            ("lightvolume", true, true),
            ("lightvolume-per-light", false, true),
            ("lightvolume-per-light-grey", false, false),
        ]
        .map(|(technique, shared, chromatic)| (scale, technique, shared, chromatic))
    });
    for (scale, technique, shared, chromatic) in variants {
        meter.progress.start_step(&format!("{width}x{height} {technique} {} frame", resolution_label(scale)));
        let s = lightvolume_scene(&lit, scale, true, CostEstimate::Passes, |lv| {
            (lv.shared_medium, lv.chromatic) = (shared, chromatic)
        });
        let frames = meter.lightvolume_frames(&s, texels, &all_on, (width, height))?;
        meter.progress.finish_step();
        let gpu_ms = frames.timing.median();
        let (frame, bytes) = frames.timing.last;
        let image =
            frame.image.ok_or_else(|| ExperimentError::Invalid("light volume frame without an image".into()))?;
        let stats = compare(&image, &references[chromatic as usize])?;
        let mut row = BenchRow::new();
        row.set("technique", technique)
            .set("chromatic", chromatic)
            .set("width", width)
            .set("height", height)
            .set("lights", count);
        row.set("resolution", resolution_label(scale)).set("grid", grid_text(frame.grid));
        row.set("gpu_ms", gpu_ms).set("rmse", stats.rmse).set("max_abs", stats.max_abs);
        row.set("psnr", stats.psnr).set("dispatches", frame.dispatches);
        row.set("update_ms", median(&frames.update_ms))
            .set("raycast_ms", median(&frames.raycast_ms))
            .set("passes", frame.update.plan.passes.len());
        row.set("gpu_memory_bytes", bytes);
        report.error.push(row);
    }
    Ok(())
}

impl Report {
    /// What the terminal shows: the per-added-light slopes, each entire update's
    /// sequential/coherent ratio and each error row, one line each; every
    /// column is in the files.
    pub fn print_summary(&self) {
        let num = |r: &BenchRow, k: &str| r.get_f64(k).unwrap_or(f64::NAN);
        for r in &self.scaling_fit.rows {
            println!(
                "figure 10, {} {}: {:.3} per added light (ms; the paper {:.3})",
                r.text("resolution"),
                r.text("propagation"),
                num(r, "ms_per_added_light"),
                num(r, "paper_ms_per_added_light")
            );
        }
        for r in self.table1.rows.iter().filter(|r| r.text("source").starts_with("ours")) {
            println!(
                "entire update, {} {} lights: sequential/coherent {:.2}x",
                r.text("resolution"),
                r.text("lights"),
                num(r, "sequential_over_coherent")
            );
        }
        for r in &self.error.rows {
            println!(
                "error, {} {}: rmse {:.4} in {:.0} ms",
                r.text("technique"),
                r.text("resolution"),
                num(r, "rmse"),
                num(r, "gpu_ms")
            );
        }
    }

    fn sections(&self) -> [(&'static str, &'static str, &BenchTable); 8] {
        [
            ("table1", "Table 1 shape: median GPU ms per update, ours beside the paper's Engine rows", &self.table1),
            ("inside", "A point light inside the volume (six passes) and outside, entire update", &self.inside),
            ("update", "Every measured update", &self.updates),
            ("scaling", "Figure 10 shape: entire update over lights of one direction", &self.scaling),
            ("scaling_fit", "Figure 10 slopes (least squares), ms per added light", &self.scaling_fit),
            ("memory", "Memory: one illumination volume against one RGBA32F volume per light", &self.memory),
            (
                "incremental",
                "Incremental mode: frames and GPU ms per frame until the volume is complete",
                &self.incremental,
            ),
            (
                "error",
                "Error against time: one full frame (entire update + ray cast), against model (i), grey or chromatic as the row says",
                &self.error,
            ),
        ]
    }

    /// Every part's rows in one table, each tagged with its part.
    fn combined(&self) -> BenchTable {
        let mut all = BenchTable::with_run(self.run.clone());
        for (part, _, table) in self.sections() {
            for row in &table.rows {
                let mut tagged = BenchRow::new().with("part", part);
                for (k, v) in row.iter() {
                    tagged.set(k, v.clone());
                }
                all.push(tagged);
            }
        }
        all
    }

    /// The rows measured so far, as `lights.csv` and `lights.json`.
    pub fn save(&self, out_folder: &OutFolder) -> Result<(), ExperimentError> {
        Ok(out_folder.save_rows("lights", &self.combined())?)
    }

    pub fn write(&self, plan: &LightsPlan, out: &Path) -> Result<(), ExperimentError> {
        let all = self.combined();
        let mut markdown = self.run.markdown();
        for (_, title, table) in self.sections() {
            markdown.push_str(&format!("## {title}\n\n{}\n", table.to_markdown()));
        }
        all.write_csv(out.join("lights.csv"))?;
        all.write_json(out.join("lights.json"))?;
        let md = out.join("lights.md");
        std::fs::write(&md, &markdown).map_err(|source| BenchError::Write { path: md, source })?;
        self.plots(plan, out)
    }

    fn plots(&self, plan: &LightsPlan, out: &Path) -> Result<(), ExperimentError> {
        let scaling: Vec<Series> = ["coherent", "sequential"]
            .iter()
            .map(|p| Series::new(*p, self.scaling.points(|r| r.text("propagation") == *p, "lights", "gpu_ms")))
            .collect();
        plot_lines(
            out.join("lights_scaling.png"),
            &Chart::new(
                format!("Entire update, lights of one direction, {}", resolution_label(plan.scaling_scale)),
                "lights",
                "GPU time (ms)",
            ),
            &scaling,
        )?;
        for &scale in &plan.scales {
            let label = resolution_label(scale);
            let series: Vec<Series> = Update::ALL
                .iter()
                .map(|u| {
                    let keep = |r: &BenchRow| r.text("update") == u.name() && r.get_f64("scale") == Some(scale as f64);
                    Series::new(u.name(), self.updates.points(keep, "lights", "gpu_ms"))
                })
                .collect();
            plot_lines(
                out.join(format!("lights_table1_{scale}.png")),
                &Chart::new(format!("Light volume updates, {label}"), "lights", "GPU time (ms)")
                    .y_scale(AxisScale::Log10),
                &series,
            )?;
        }
        let error: Vec<Series> = ["lightvolume", "lightvolume-per-light", "lightvolume-per-light-grey", "dvr"]
            .iter()
            .map(|t| Series::new(*t, self.error.points(|r| r.text("technique") == *t, "gpu_ms", "rmse")))
            .collect();
        plot_error_vs_time(
            out.join("lights_error_vs_time.png"),
            &Chart::new("Light volume frames against the ground truth of their model", "GPU time (ms)", "RMSE")
                .x_scale(AxisScale::Log10)
                .y_scale(AxisScale::Log10),
            &error,
        )?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plan() -> LightsPlan {
        LightsPlan {
            scales: vec![4],
            light_counts: vec![2],
            scaling_counts: vec![1, 2],
            scaling_scale: 4,
            error_scales: vec![4],
            incremental_passes: vec![1],
            repeat: 1,
            image: (16, 16),
            volume_texels: VolumeTexels::Native,
        }
    }

    #[test]
    fn a_tiny_plan_is_accepted_and_each_bad_list_is_named() {
        assert_eq!(plan().check().unwrap().repeat(), 1);
        type Spoil = fn(&mut LightsPlan);
        let bad: [(&str, Spoil); 7] = [
            ("--scales", |p| p.scales = vec![3]),
            ("--error-scales", |p| p.error_scales.clear()),
            ("--scaling-scale", |p| p.scaling_scale = 8),
            ("--incremental-passes", |p| p.incremental_passes = vec![65]),
            ("--light-counts", |p| p.light_counts = vec![1]),
            ("--scaling-counts", |p| p.scaling_counts = vec![257]),
            ("--repeat", |p| p.repeat = 0),
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
        // table1: 4 per (scale, count); inside: 2 per scale; scaling: 2 per count;
        // incremental: 1 per pass count; error: 3 + 3 per error scale.
        let p = plan();
        assert_eq!(step_weights(&p, p.image).len(), 4 + 2 + 4 + 1 + 3 + 3);
        assert!(step_weights(&p, p.image).iter().all(|w| *w > 0.0));
    }
}
