//! `sweeplab bench lights`: the light volume against the selective light
//! updates paper (Jönsson/Ropinski et al. 2015): Table 1 (entire updates with
//! sequential and coherence-based propagation, selective updates of one
//! light), Figure 10 (entire update time over 1-40 lights of one direction),
//! the memory of one illumination volume against one per light, and the error
//! of a full frame against the ground truth next to its time.

use super::args::BenchLightsArgs;
use super::render_cmd::PROFILER_CAPACITY;
use super::{scene_args, session};
use anyhow::{bail, Context as _};
use glam::{UVec3, Vec3};
use std::process::ExitCode;
use sweeplab::bench::{
    fit_line, median, plot_error_vs_time, plot_lines, AxisScale, BenchRow, BenchTable, Chart, Progress, Series,
};
use sweeplab::lightvolume::{CostEstimate, LightVolumeFrame, LightVolumeRenderer, LightVolumeSettings, UpdateKind};
use sweeplab::linear_image::LinearImage;
use sweeplab::metrics::compare;
use sweeplab::render::{render, GpuScene, Technique};
use sweeplab::scene::{Falloff, Light, LightKind, Scene};
use sweeplab::vk::{Context, Profiler};

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
const DEFAULT_ERROR_IMAGE: u32 = 256;

/// The four updates of a Table 1 row.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Update {
    EntireSequential,
    EntireCoherent,
    StateChange,
    Toggle,
}

impl Update {
    const ALL: [Update; 4] = [Update::EntireSequential, Update::EntireCoherent, Update::StateChange, Update::Toggle];

    fn name(self) -> &'static str {
        match self {
            Update::EntireSequential => "entire-sequential",
            Update::EntireCoherent => "entire-coherent",
            Update::StateChange => "state-change",
            Update::Toggle => "toggle",
        }
    }

    fn column(self) -> &'static str {
        match self {
            Update::EntireSequential => "sequential_ms",
            Update::EntireCoherent => "coherent_ms",
            Update::StateChange => "state_change_ms",
            Update::Toggle => "toggle_ms",
        }
    }

    fn expected_kind(self) -> UpdateKind {
        match self {
            Update::EntireSequential | Update::EntireCoherent => UpdateKind::Entire,
            Update::StateChange | Update::Toggle => UpdateKind::Selective,
        }
    }
}

/// `scene` with its light volume settings set to what a measurement needs
/// (scale, coherent, cost estimate, then `extra`); other settings from the
/// scene (`--set lightvolume.substep=0.5`) are kept.
fn lightvolume_scene(
    scene: &Scene,
    scale: u32,
    coherent: bool,
    cost_estimate: CostEstimate,
    extra: impl FnOnce(&mut LightVolumeSettings),
) -> Scene {
    let mut s = scene.clone();
    let lv = &mut s.settings.lightvolume;
    (lv.scale, lv.coherent, lv.cost_estimate) = (scale, coherent, cost_estimate);
    extra(lv);
    s
}

fn directional(direction: Vec3, color: Vec3, intensity: f32) -> Light {
    Light { kind: LightKind::Directional { direction }, color, intensity, falloff: Falloff::None }
}

/// A general coloured set spread around the volume (box half extents <= 0.5),
/// taken in order: two directional lights from above sharing the -y group
/// (one also in +x, one in -x), a point light sharing -x and -y, a blue light
/// from the front (-z, -y), a spot light from above (-y, -z), a grazing light
/// (-x, +z); beyond six, dimmer white directional lights from the upper
/// hemisphere at golden-angle azimuths. The first light is the one that changes.
fn table1_lights(count: usize) -> Vec<Light> {
    let mut all = vec![
        directional(Vec3::new(0.45, -1.0, 0.3), Vec3::ONE, 1.0),
        directional(Vec3::new(-0.5, -1.0, -0.2), Vec3::new(1.0, 0.85, 0.6), 0.8),
        Light {
            kind: LightKind::Point { position: Vec3::new(0.95, 0.55, -0.35) },
            color: Vec3::new(1.0, 0.6, 0.25),
            intensity: 1.2,
            falloff: Falloff::None,
        },
        directional(Vec3::new(0.25, -0.55, -1.0), Vec3::new(0.6, 0.75, 1.0), 0.7),
        Light {
            kind: LightKind::Spot {
                position: Vec3::new(-0.4, 1.1, 0.6),
                direction: Vec3::new(0.4, -1.1, -0.6),
                inner_cone_deg: 20.0,
                outer_cone_deg: 35.0,
            },
            color: Vec3::new(0.9, 1.0, 0.8),
            intensity: 1.0,
            falloff: Falloff::None,
        },
        directional(Vec3::new(-1.0, -0.35, 0.5), Vec3::new(1.0, 0.7, 0.9), 0.5),
    ];
    for i in all.len()..count {
        let azimuth = i as f32 * 2.399_963;
        let direction = Vec3::new(azimuth.cos(), -1.2, azimuth.sin());
        all.push(directional(direction, Vec3::ONE, 0.4));
    }
    all.truncate(count);
    all
}

/// The changed light's second state: its direction turned by about 3 degrees,
/// staying in the same two groups (a small move, as in the paper).
fn moved(light: &Light) -> Light {
    let mut l = *light;
    if let LightKind::Directional { direction } = &mut l.kind {
        *direction = glam::Quat::from_rotation_y(3f32.to_radians()) * *direction;
    }
    l
}

/// Figure 10's lights: `count` directional lights jittered by at most ~2.5
/// degrees around one direction, all in the same two groups (-y and +x).
fn scaling_lights(count: u32) -> Vec<Light> {
    let base = Vec3::new(0.35, -1.0, 0.25);
    (0..count)
        .map(|i| {
            let angle = i as f32 * 2.399_963; // golden angle: spread without repeats
            let radius = 0.04 * ((i + 1) as f32 / count as f32).sqrt();
            let d = base + Vec3::new(radius * angle.cos(), 0.0, radius * angle.sin());
            directional(d, Vec3::ONE, 1.0 / count as f32)
        })
        .collect()
}

fn grid_text(g: UVec3) -> String {
    format!("{}x{}x{}", g.x, g.y, g.z)
}

fn resolution_label(scale: u32) -> String {
    if scale == 1 {
        "DR*1".into()
    } else {
        format!("DR*1/{scale}")
    }
}

/// What repeated updates of one kind cost.
struct Measured {
    ms: Vec<f64>,
    passes: usize,
    propagations: usize,
    dispatches: u32,
    barriers: u32,
    recorded: usize,
    reused: usize,
    kind: UpdateKind,
    reason: String,
    /// Timed frames that came out as another kind (e.g. a re-base) and were left out.
    other_kind: usize,
    grid: UVec3,
    illumination_bytes: u64,
    propagation_bytes: u64,
}

/// One update, timed by its own profiler scope.
fn timed_update(
    ctx: &Context,
    renderer: &mut LightVolumeRenderer,
    profiler: &mut Profiler,
    state: &[Option<Light>],
    entire: bool,
) -> anyhow::Result<(f64, LightVolumeFrame)> {
    if entire {
        renderer.invalidate();
    }
    profiler.reset();
    let frame = renderer.update(state, profiler)?;
    let profile = profiler.resolve(ctx.memory.device_local_peak())?;
    Ok((profile.pass_ms(frame.update.plan.kind.scope_name()), frame))
}

/// `repeat` timed updates of `update`. Entire updates re-measure `first`;
/// selective ones alternate between `first` and `second`, after an untimed
/// change to `second` (which records its passes). The renderer holds `first`
/// before and after.
fn measure(
    ctx: &Context,
    renderer: &mut LightVolumeRenderer,
    profiler: &mut Profiler,
    update: Update,
    (first, second): (&[Option<Light>], &[Option<Light>]),
    repeat: u32,
) -> anyhow::Result<Measured> {
    let selective = update.expected_kind() == UpdateKind::Selective;
    let mut now_second = false;
    if selective {
        timed_update(ctx, renderer, profiler, second, false)?;
        now_second = true;
    }
    let mut ms = Vec::new();
    let mut other_kind = 0;
    let mut last = None;
    for _ in 0..repeat {
        let state = if now_second { first } else { second };
        let (t, frame) = if selective {
            now_second = !now_second;
            timed_update(ctx, renderer, profiler, state, false)?
        } else {
            timed_update(ctx, renderer, profiler, first, true)?
        };
        if frame.update.plan.kind == update.expected_kind() {
            ms.push(t);
        } else {
            other_kind += 1;
        }
        last = Some(frame);
    }
    if now_second {
        timed_update(ctx, renderer, profiler, first, false)?;
    }
    let frame = last.context("no timed update (repeat is 0)")?;
    let plan = &frame.update.plan;
    Ok(Measured {
        ms,
        passes: frame.groups().len(),
        propagations: frame.groups().iter().map(|g| g.members.len()).sum(),
        dispatches: frame.dispatches,
        barriers: frame.barriers,
        recorded: frame.update.recorded,
        reused: frame.update.reused,
        kind: plan.kind,
        reason: plan.reason.clone(),
        other_kind,
        grid: renderer.grid(),
        illumination_bytes: 0,
        propagation_bytes: 0,
    })
}

/// What every measurement uses: the device, the profiler, the progress line
/// and the number of timed repeats.
struct Meter<'c> {
    ctx: &'c Context,
    profiler: Profiler,
    progress: Progress,
    repeat: u32,
}

/// Measures `updates` on one renderer of `scene` (whose `[lightvolume]` table
/// they share): first an untimed entire update of all `lights` (it records
/// the passes, and llvmpipe compiles the shaders on first use), whose memory
/// is kept in each result.
fn measure_all(
    meter: &mut Meter,
    scene: &Scene,
    lights: &[Light],
    updates: &[Update],
    label: &str,
) -> anyhow::Result<Vec<Measured>> {
    let gpu = GpuScene::upload(meter.ctx, scene).context("uploading the scene")?;
    let before = meter.ctx.memory.device_local_bytes();
    let mut renderer = LightVolumeRenderer::new(&gpu)?;
    let with_renderer = meter.ctx.memory.device_local_bytes();
    let first: Vec<Option<Light>> = lights.iter().copied().map(Some).collect();
    timed_update(meter.ctx, &mut renderer, &mut meter.profiler, &first, true)?;
    let with_passes = meter.ctx.memory.device_local_bytes();
    let mut out = Vec::new();
    for &update in updates {
        meter.progress.start_step(&format!("{label}: {}", update.name()));
        let mut second = first.clone();
        match update {
            Update::StateChange => second[0] = Some(moved(&lights[0])),
            Update::Toggle => second[0] = None,
            Update::EntireSequential | Update::EntireCoherent => {}
        }
        let mut m = measure(meter.ctx, &mut renderer, &mut meter.profiler, update, (&first, &second), meter.repeat)?;
        meter.progress.finish_step();
        if m.other_kind > 0 {
            meter.progress.message(&format!(
                "  {} of {} timed updates were {:?}, not {:?} ({}); left out",
                m.other_kind,
                meter.repeat,
                m.kind,
                update.expected_kind(),
                m.reason
            ));
        }
        m.illumination_bytes = with_renderer - before;
        m.propagation_bytes = with_passes - with_renderer;
        out.push(m);
    }
    Ok(out)
}

fn check_args(args: &BenchLightsArgs) -> anyhow::Result<()> {
    let scales_ok = |name: &str, scales: &[u32]| -> anyhow::Result<()> {
        if scales.is_empty() {
            bail!("--{name}: give at least one scale (1, 2 or 4)");
        }
        if let Some(s) = scales.iter().find(|s| !matches!(s, 1 | 2 | 4)) {
            bail!(
                "--{name}: {s} is not an illumination volume scale; use 1, 2 or 4 data voxels per illumination voxel"
            );
        }
        Ok(())
    };
    scales_ok("scales", &args.scales)?;
    scales_ok("error-scales", &args.error_scales)?;
    scales_ok("scaling-scale", &[args.scaling_scale])?;
    if let Some(n) = args.incremental_passes.iter().find(|n| !(1..=64).contains(*n)) {
        bail!("--incremental-passes: {n} is outside 1..=64 passes per frame");
    }
    if args.light_counts.is_empty() {
        bail!("--light-counts: give at least one light count (2..={MAX_TABLE1_LIGHTS})");
    }
    if let Some(n) = args.light_counts.iter().find(|n| !(2..=MAX_TABLE1_LIGHTS).contains(n)) {
        bail!(
            "--light-counts: {n} is outside 2..={MAX_TABLE1_LIGHTS} (toggling one light needs another left on; \
             more than {MAX_TABLE1_LIGHTS} is the scaling test's job)"
        );
    }
    if args.scaling_counts.is_empty() {
        bail!("--scaling-counts: give at least one light count (1..={MAX_SCALING_LIGHTS})");
    }
    if let Some(n) = args.scaling_counts.iter().find(|n| !(1..=MAX_SCALING_LIGHTS).contains(n)) {
        bail!("--scaling-counts: {n} is outside 1..={MAX_SCALING_LIGHTS}");
    }
    if args.repeat == 0 {
        bail!("--repeat: 0 timed updates measure nothing; use 1 or more");
    }
    Ok(())
}

pub fn run(args: &BenchLightsArgs) -> anyhow::Result<ExitCode> {
    check_args(args)?;
    let (width, height) = match &args.scene.size {
        Some(size) => scene_args::parse_size(size)?,
        None => (DEFAULT_ERROR_IMAGE, DEFAULT_ERROR_IMAGE),
    };
    let mut scene = scene_args::load(&args.scene)?;
    // The light volume carries transmittance alone: optical model (i).
    scene.reference.model = Technique::LightVolume.reference_model(&scene);
    std::fs::create_dir_all(&args.out).with_context(|| format!("cannot create {}", args.out.display()))?;
    let ctx = session::open(&args.gpu)?;
    let table1_steps = args.scales.len() * args.light_counts.len() * Update::ALL.len();
    let steps =
        table1_steps + 2 * args.scaling_counts.len() + args.incremental_passes.len() + 2 + 2 * args.error_scales.len();
    let mut meter = Meter {
        ctx: &ctx,
        profiler: Profiler::new(&ctx, PROFILER_CAPACITY)?,
        progress: Progress::new(steps),
        repeat: args.repeat,
    };
    let mut report = Report::default();
    table1(args, &mut meter, &scene, &mut report)?;
    scaling(args, &mut meter, &scene, &mut report)?;
    incremental(args, &mut meter, &scene, &mut report)?;
    error_rows(args, &mut meter, &scene, (width, height), &mut report)?;
    meter.progress.finish();
    report.write(args)?;
    Ok(session::finish(&ctx))
}

#[derive(Default)]
struct Report {
    updates: BenchTable,
    table1: BenchTable,
    scaling: BenchTable,
    scaling_fit: BenchTable,
    memory: BenchTable,
    incremental: BenchTable,
    error: BenchTable,
}

fn table1(args: &BenchLightsArgs, meter: &mut Meter, scene: &Scene, report: &mut Report) -> anyhow::Result<()> {
    let data = scene.volume.name.clone();
    for &scale in &args.scales {
        for &count in &args.light_counts {
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
                let results = measure_all(meter, &s, &lights, updates, &label)?;
                measured.extend(updates.iter().copied().zip(results));
            }
            for (update, m) in measured {
                let ms = median(&m.ms);
                ours.set("grid", grid_text(m.grid));
                ours.set(update.column(), ms);
                counts.set(format!("{}_passes", update.column().trim_end_matches("_ms")), m.passes);
                counts.set(format!("{}_dispatches", update.column().trim_end_matches("_ms")), m.dispatches);
                let mut row = BenchRow::new();
                row.set("resolution", resolution_label(scale)).set("scale", scale).set("grid", grid_text(m.grid));
                row.set("lights", count).set("update", update.name()).set("kind", format!("{:?}", m.kind));
                row.set("gpu_ms", ms);
                row.set("min_ms", m.ms.iter().copied().fold(f64::NAN, f64::min));
                row.set("max_ms", m.ms.iter().copied().fold(f64::NAN, f64::max));
                row.set("timed", m.ms.len()).set("passes", m.passes).set("propagations", m.propagations);
                row.set("dispatches", m.dispatches).set("barriers", m.barriers);
                row.set("ms_per_pass", ms / m.passes.max(1) as f64);
                row.set("recorded", m.recorded).set("reused", m.reused).set("reason", m.reason.clone());
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
fn memory_row(scale: u32, count: u32, propagation: &str, m: &Measured) -> BenchRow {
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
fn incremental(args: &BenchLightsArgs, meter: &mut Meter, scene: &Scene, report: &mut Report) -> anyhow::Result<()> {
    let scale = args.scaling_scale;
    let count = args.light_counts.iter().copied().max().unwrap_or(2);
    let lights: Vec<Option<Light>> = table1_lights(count as usize).into_iter().map(Some).collect();
    let entire = {
        let s = lightvolume_scene(scene, scale, true, CostEstimate::Entire, |_| {});
        let gpu = GpuScene::upload(meter.ctx, &s).context("uploading the scene")?;
        let mut renderer = LightVolumeRenderer::new(&gpu)?;
        timed_update(meter.ctx, &mut renderer, &mut meter.profiler, &lights, true)?; // untimed warm-up
        timed_update(meter.ctx, &mut renderer, &mut meter.profiler, &lights, true)?.0
    };
    for &n in &args.incremental_passes {
        meter
            .progress
            .start_step(&format!("incremental {} {count} lights, {n} passes a frame", resolution_label(scale)));
        let s = lightvolume_scene(scene, scale, true, CostEstimate::Passes, |lv| lv.max_passes_per_frame = n);
        let gpu = GpuScene::upload(meter.ctx, &s).context("uploading the scene")?;
        let mut renderer = LightVolumeRenderer::new(&gpu)?;
        // Untimed: records every pass and compiles the shaders.
        while timed_update(meter.ctx, &mut renderer, &mut meter.profiler, &lights, false)?.1.update.plan.kind
            != UpdateKind::Unchanged
        {}
        renderer.invalidate();
        let mut frames = Vec::new();
        loop {
            let (ms, frame) = timed_update(meter.ctx, &mut renderer, &mut meter.profiler, &lights, false)?;
            if frame.update.plan.kind == UpdateKind::Unchanged {
                break;
            }
            frames.push(ms);
            if frames.len() > 10_000 {
                bail!("incremental mode did not converge in 10,000 frames");
            }
        }
        meter.progress.finish_step();
        let mut row = BenchRow::new();
        row.set("resolution", resolution_label(scale)).set("grid", grid_text(renderer.grid())).set("lights", count);
        row.set("max_passes_per_frame", n).set("frames", frames.len());
        row.set("max_frame_ms", frames.iter().copied().fold(0.0, f64::max));
        row.set("total_ms", frames.iter().sum::<f64>()).set("entire_update_ms", entire);
        report.incremental.push(row);
    }
    Ok(())
}

fn scaling(args: &BenchLightsArgs, meter: &mut Meter, scene: &Scene, report: &mut Report) -> anyhow::Result<()> {
    let scale = args.scaling_scale;
    let mut points: [Vec<(f64, f64)>; 2] = [Vec::new(), Vec::new()];
    for &count in &args.scaling_counts {
        let lights = scaling_lights(count);
        for (i, update) in [Update::EntireCoherent, Update::EntireSequential].into_iter().enumerate() {
            let propagation = if update == Update::EntireCoherent { "coherent" } else { "sequential" };
            let s = lightvolume_scene(scene, scale, update == Update::EntireCoherent, CostEstimate::Entire, |_| {});
            let label = format!("scaling {} {count} lights", resolution_label(scale));
            let m = measure_all(meter, &s, &lights, &[update], &label)?.pop().context("no measurement")?;
            let ms = median(&m.ms);
            points[i].push((count as f64, ms));
            let mut row = BenchRow::new();
            row.set("resolution", resolution_label(scale)).set("grid", grid_text(m.grid)).set("lights", count);
            row.set("propagation", propagation).set("gpu_ms", ms).set("passes", m.passes);
            row.set("dispatches", m.dispatches).set("barriers", m.barriers);
            row.set("ms_per_pass", ms / m.passes.max(1) as f64);
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
    args: &BenchLightsArgs,
    meter: &mut Meter,
    scene: &Scene,
    (width, height): (u32, u32),
    report: &mut Report,
) -> anyhow::Result<()> {
    let count = args.light_counts.iter().copied().max().unwrap_or(2);
    let mut lit = scene.clone();
    lit.lights = table1_lights(count as usize);
    let texels = session::volume_texels(&args.gpu);
    meter.progress.start_step(&format!("{width}x{height} ground truth (GPU, model i), {count} lights"));
    let reference: LinearImage = {
        let gpu = GpuScene::upload_with(meter.ctx, &lit, texels).context("uploading the scene")?;
        render(&gpu, Technique::Reference, width, height, &mut meter.profiler)?.image
    };
    meter.progress.finish_step();
    meter.progress.start_step(&format!("{width}x{height} unshaded DVR"));
    let mut times = Vec::new();
    let mut dvr = None;
    {
        let gpu = GpuScene::upload_with(meter.ctx, &lit, texels).context("uploading the scene")?;
        render(&gpu, Technique::Dvr, width, height, &mut meter.profiler)?; // untimed warm-up
        for _ in 0..args.repeat {
            let out = render(&gpu, Technique::Dvr, width, height, &mut meter.profiler)?;
            times.push(out.profile.gpu_ms_total);
            dvr = Some(out);
        }
    }
    meter.progress.finish_step();
    let dvr = dvr.context("no DVR frame")?;
    let stats = compare(&dvr.image, &reference)?;
    let mut row = BenchRow::new();
    row.set("technique", "dvr").set("width", width).set("height", height).set("lights", count);
    row.set("gpu_ms", median(&times)).set("rmse", stats.rmse).set("max_abs", stats.max_abs).set("psnr", stats.psnr);
    row.set("dispatches", dvr.dispatches);
    report.error.push(row);
    let all_on: Vec<Option<Light>> = lit.lights.iter().copied().map(Some).collect();
    // Both propagations of the medium: along each light (default), and shared
    // by the lights of a pass (the paper's, cheaper per light).
    let variants = args.error_scales.iter().flat_map(|&scale| [(scale, false), (scale, true)]);
    for (scale, shared) in variants {
        let medium = if shared { "shared" } else { "per-light" };
        meter
            .progress
            .start_step(&format!("{width}x{height} light volume {} frame, {medium} medium", resolution_label(scale)));
        let s = lightvolume_scene(&lit, scale, true, CostEstimate::Passes, |lv| lv.shared_medium = shared);
        let gpu = GpuScene::upload_with(meter.ctx, &s, texels).context("uploading the scene")?;
        meter.ctx.memory.reset_peak();
        let mut renderer = LightVolumeRenderer::new(&gpu)?;
        // Untimed: records the passes and compiles the shaders.
        meter.profiler.reset();
        renderer.render(&all_on, width, height, &mut meter.profiler, false)?;
        meter.profiler.resolve(0)?;
        let (mut total, mut update, mut raycast) = (Vec::new(), Vec::new(), Vec::new());
        let mut last = None;
        for _ in 0..args.repeat {
            renderer.invalidate();
            meter.profiler.reset();
            let frame = renderer.render(&all_on, width, height, &mut meter.profiler, false)?;
            let profile = meter.profiler.resolve(meter.ctx.memory.device_local_peak())?;
            total.push(profile.gpu_ms_total);
            update.push(profile.pass_ms(UpdateKind::Entire.scope_name()));
            raycast.push(profile.pass_ms("lightvolume_raycast"));
            last = Some((frame, profile.gpu_memory_bytes));
        }
        meter.progress.finish_step();
        let (frame, bytes) = last.context("no light volume frame")?;
        let image = frame.image.context("light volume frame without an image")?;
        let stats = compare(&image, &reference)?;
        let mut row = BenchRow::new();
        let technique = if shared { "lightvolume-shared-medium" } else { "lightvolume" };
        row.set("technique", technique).set("width", width).set("height", height).set("lights", count);
        row.set("resolution", resolution_label(scale)).set("grid", grid_text(frame.grid));
        row.set("gpu_ms", median(&total)).set("rmse", stats.rmse).set("max_abs", stats.max_abs);
        row.set("psnr", stats.psnr).set("dispatches", frame.dispatches);
        row.set("update_ms", median(&update))
            .set("raycast_ms", median(&raycast))
            .set("passes", frame.update.plan.passes.len());
        row.set("gpu_memory_bytes", bytes);
        report.error.push(row);
    }
    Ok(())
}

impl Report {
    fn sections(&self) -> [(&'static str, &'static str, &BenchTable); 7] {
        [
            ("table1", "Table 1 shape: median GPU ms per update, ours beside the paper's Engine rows", &self.table1),
            ("update", "Every measured update", &self.updates),
            ("scaling", "Figure 10 shape: entire update over lights of one direction", &self.scaling),
            ("scaling_fit", "Figure 10 slopes (least squares), ms per added light", &self.scaling_fit),
            ("memory", "Memory: one illumination volume against one RGBA32F volume per light", &self.memory),
            (
                "incremental",
                "Incremental mode: frames and GPU ms per frame until the volume is complete",
                &self.incremental,
            ),
            ("error", "Error against time: one full frame (entire update + ray cast), model (i)", &self.error),
        ]
    }

    fn write(&self, args: &BenchLightsArgs) -> anyhow::Result<()> {
        let mut all = BenchTable::new();
        let mut markdown = String::new();
        for (part, title, table) in self.sections() {
            for row in &table.rows {
                let mut tagged = BenchRow::new().with("part", part);
                for (k, v) in row.iter() {
                    tagged.set(k, v.clone());
                }
                all.push(tagged);
            }
            markdown.push_str(&format!("## {title}\n\n{}\n", table.to_markdown()));
        }
        all.write_csv(args.out.join("lights.csv"))?;
        all.write_json(args.out.join("lights.json"))?;
        std::fs::write(args.out.join("lights.md"), &markdown).context("writing lights.md")?;
        self.plots(args)?;
        println!("{markdown}");
        println!(
            "wrote {}/lights.csv, lights.json, lights.md, lights_scaling.png, lights_table1_<scale>.png, \
             lights_error_vs_time.png",
            args.out.display()
        );
        Ok(())
    }

    fn plots(&self, args: &BenchLightsArgs) -> anyhow::Result<()> {
        let scaling: Vec<Series> = ["coherent", "sequential"]
            .iter()
            .map(|p| Series::new(*p, self.scaling.points(|r| r.text("propagation") == *p, "lights", "gpu_ms")))
            .collect();
        plot_lines(
            args.out.join("lights_scaling.png"),
            &Chart::new(
                format!("Entire update, lights of one direction, {}", resolution_label(args.scaling_scale)),
                "lights",
                "GPU time (ms)",
            ),
            &scaling,
        )?;
        for &scale in &args.scales {
            let label = resolution_label(scale);
            let series: Vec<Series> = Update::ALL
                .iter()
                .map(|u| {
                    let keep = |r: &BenchRow| r.text("update") == u.name() && r.get_f64("scale") == Some(scale as f64);
                    Series::new(u.name(), self.updates.points(keep, "lights", "gpu_ms"))
                })
                .collect();
            plot_lines(
                args.out.join(format!("lights_table1_{scale}.png")),
                &Chart::new(format!("Light volume updates, {label}"), "lights", "GPU time (ms)")
                    .y_scale(AxisScale::Log10),
                &series,
            )?;
        }
        let error: Vec<Series> = ["lightvolume", "lightvolume-shared-medium", "dvr"]
            .iter()
            .map(|t| Series::new(*t, self.error.points(|r| r.text("technique") == *t, "gpu_ms", "rmse")))
            .collect();
        plot_error_vs_time(
            args.out.join("lights_error_vs_time.png"),
            &Chart::new("Light volume frames against the ground truth of model (i)", "GPU time (ms)", "RMSE")
                .x_scale(AxisScale::Log10)
                .y_scale(AxisScale::Log10),
            &error,
        )?;
        Ok(())
    }
}
