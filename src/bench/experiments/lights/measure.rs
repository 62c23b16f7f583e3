//! The light volume experiments of `sweeplab bench lights` (the selective light
//! updates paper, Sundén and Ropinski 2015): the lights of its Table 1 and
//! Figure 10, a scene per measurement, the four updates of a Table 1 row and
//! how each is timed, incremental mode until complete, and full frames for the
//! error against the ground truth. Every part's configurations are measured
//! side by side in shared shuffled rounds ([`Interleaved`]): each has its own
//! renderer, made before the rounds, so one configuration's run leaves
//! nothing another one's depends on (see [`LightsMeter::measure_updates`]).

use crate::bench::harness::Sample;
use crate::bench::interleaved::{Interleaved, Timings};
use crate::bench::progress::Progress;
use crate::bench::protocol::Phase;
use crate::bench::ExperimentError;
use crate::linear_image::LinearImage;
use crate::render::{GpuScene, RenderError};
use crate::scene::{Falloff, Light, LightKind, Scene};
use crate::techniques::lightvolume::{
    CostEstimate, LightVolumeFrame, LightVolumeRenderer, LightVolumeSettings, UpdateKind,
};
use crate::techniques::{render, Technique};
use crate::vk::{Context, Profiler};
use glam::{UVec3, Vec3};

/// Incremental mode gives up after this many frames.
const MAX_INCREMENTAL_FRAMES: usize = 10_000;

/// The four updates of a Table 1 row.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Update {
    EntireSequential,
    EntireCoherent,
    StateChange,
    Toggle,
}

impl Update {
    pub const ALL: [Update; 4] =
        [Update::EntireSequential, Update::EntireCoherent, Update::StateChange, Update::Toggle];

    pub fn name(self) -> &'static str {
        match self {
            Update::EntireSequential => "entire-sequential",
            Update::EntireCoherent => "entire-coherent",
            Update::StateChange => "state-change",
            Update::Toggle => "toggle",
        }
    }

    pub fn column(self) -> &'static str {
        match self {
            Update::EntireSequential => "sequential_ms",
            Update::EntireCoherent => "coherent_ms",
            Update::StateChange => "state_change_ms",
            Update::Toggle => "toggle_ms",
        }
    }

    pub fn expected_kind(self) -> UpdateKind {
        match self {
            Update::EntireSequential | Update::EntireCoherent => UpdateKind::Entire,
            Update::StateChange | Update::Toggle => UpdateKind::Selective,
        }
    }
}

/// `scene` with its light volume settings set to what a measurement needs
/// (scale, coherent, cost estimate, then `extra`); other settings from the
/// scene (`--set lightvolume.substep=0.5`) are kept.
pub fn lightvolume_scene(
    scene: &Scene,
    scale: u32,
    coherent: bool,
    cost_estimate: CostEstimate,
    extra: impl FnOnce(&mut LightVolumeSettings),
) -> Scene {
    let mut s = scene.clone();
    let lv = s.settings.get_mut::<LightVolumeSettings>();
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
pub fn table1_lights(count: usize) -> Vec<Light> {
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
pub fn scaling_lights(count: u32) -> Vec<Light> {
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

pub fn grid_text(g: UVec3) -> String {
    format!("{}x{}x{}", g.x, g.y, g.z)
}

pub fn resolution_label(scale: u32) -> String {
    if scale == 1 {
        "DR*1".into()
    } else {
        format!("DR*1/{scale}")
    }
}

/// A light volume renderer of one configuration, made before the rounds,
/// with the device-local memory it took.
pub struct Volume<'s> {
    pub renderer: LightVolumeRenderer<'s>,
    /// The illumination volume(s), allocated with the renderer.
    pub illumination_bytes: u64,
    /// The slice buffers and slot buffer, allocated by its first update.
    pub propagation_bytes: u64,
    /// The lights the volume holds now: where a selective update starts.
    holds: Vec<Option<Light>>,
}

/// One configuration of a part's updates: its volume (an index into the
/// part's volumes), the update, and the two states a selective update moves
/// between (`first` alone for an entire update).
pub struct UpdateConfig {
    pub volume: usize,
    pub update: Update,
    first: Vec<Option<Light>>,
    second: Vec<Option<Light>>,
}

impl UpdateConfig {
    /// `update` of `lights` (all on) on volume `volume`: a state change moves
    /// the first light a little, a toggle switches it off.
    pub fn new(volume: usize, update: Update, lights: &[Light]) -> UpdateConfig {
        let first: Vec<Option<Light>> = lights.iter().copied().map(Some).collect();
        let mut second = first.clone();
        match update {
            Update::StateChange => second[0] = Some(moved(&lights[0])),
            Update::Toggle => second[0] = None,
            Update::EntireSequential | Update::EntireCoherent => {}
        }
        UpdateConfig { volume, update, first, second }
    }
}

/// What one configuration's updates cost, round by round.
pub struct UpdateMeasurement {
    /// Update GPU ms of the timed updates of the expected kind; the last
    /// timed update's frame (counted or not).
    pub timing: Timings<LightVolumeFrame>,
    pub grid: UVec3,
    pub illumination_bytes: u64,
    pub propagation_bytes: u64,
}

impl UpdateMeasurement {
    pub fn passes(&self) -> usize {
        self.timing.last.groups().len()
    }

    pub fn propagations(&self) -> usize {
        self.timing.last.groups().iter().map(|g| g.members.len()).sum()
    }

    pub fn kind(&self) -> UpdateKind {
        self.timing.last.update.plan.kind
    }

    pub fn reason(&self) -> &str {
        &self.timing.last.update.plan.reason
    }
}

/// Incremental mode from an empty volume: update GPU ms of each frame until
/// the update was complete (one entry for an entire update).
pub struct IncrementalRun {
    pub frame_ms: Vec<f64>,
    pub grid: UVec3,
}

/// Incremental mode's rounds: one entire update beside each renderer's run
/// from an empty volume until complete.
pub struct IncrementalRounds {
    pub entire: Timings<IncrementalRun>,
    /// Per renderer: the frames' total GPU ms (with the last run's frames),
    /// and the most costly frame of each round.
    pub runs: Vec<(Timings<IncrementalRun>, Timings<()>)>,
}

/// One full frame of the error rows: DVR, or a light volume frame (entire
/// update + ray cast).
pub struct FullFrame {
    pub image: LinearImage,
    pub dispatches: u32,
    /// A light volume frame's update (without its image).
    pub light_volume: Option<LightVolumeFrame>,
}

/// One configuration's full frames: the frame time, and for a light volume
/// the entire update's and the ray cast's share of it, round by round.
pub struct FullFrames {
    pub timing: Timings<FullFrame>,
    pub update_ms: Timings<()>,
    pub raycast_ms: Timings<()>,
}

/// Per configuration, one value per timed run, collected beside a part's
/// rounds where a run gives more than its time.
struct Series(Vec<Vec<Option<f64>>>);

impl Series {
    fn new(configurations: usize) -> Series {
        Series((0..configurations).map(|_| Vec::new()).collect())
    }

    fn push(&mut self, configuration: usize, phase: Phase, value: f64) {
        if phase == Phase::Timed {
            self.0[configuration].push(Some(value));
        }
    }

    fn take(&mut self, configuration: usize) -> Timings<()> {
        Timings { rounds: std::mem::take(&mut self.0[configuration]), last: () }
    }
}

/// What every light volume measurement uses: the device, the profiler, the
/// progress line, the rounds every part shares among its configurations, and
/// each part's timed runs in the order they ran.
pub struct LightsMeter<'c> {
    pub ctx: &'c Context,
    pub profiler: Profiler,
    pub progress: Progress,
    pub rounds: Interleaved,
    /// (part, configuration of each timed run in order): shuffled rounds, never blocks.
    pub orders: Vec<(String, Vec<usize>)>,
}

impl LightsMeter<'_> {
    /// `configurations` configurations in the shared rounds as one progress
    /// step labelled `label`: `run(ctx, profiler, c, phase)` runs configuration
    /// `c` once. The order of the timed runs is kept in [`LightsMeter::orders`].
    fn rounds<T>(
        &mut self,
        label: &str,
        configurations: usize,
        mut run: impl FnMut(&Context, &mut Profiler, usize, Phase) -> Result<Sample<T>, ExperimentError>,
    ) -> Result<Vec<Timings<T>>, ExperimentError> {
        let (ctx, profiler) = (self.ctx, &mut self.profiler);
        let mut order = Vec::new();
        let timings = self.rounds.measure(&mut self.progress, label, configurations, |c, phase| {
            if phase == Phase::Timed {
                order.push(c);
            }
            run(ctx, profiler, c, phase)
        })?;
        self.orders.push((label.to_string(), order));
        Ok(timings)
    }

    /// A renderer of `gpu`'s scene, after one untimed entire update of all
    /// `lights` (it records the passes and allocates the slice buffers, and
    /// llvmpipe compiles the shaders on first use), with the memory each took.
    pub fn volume<'s>(&mut self, gpu: &'s GpuScene<'s>, lights: &[Light]) -> Result<Volume<'s>, RenderError> {
        let before = self.ctx.memory.device_local_bytes();
        let mut renderer = LightVolumeRenderer::new(gpu)?;
        let with_renderer = self.ctx.memory.device_local_bytes();
        let all_on: Vec<Option<Light>> = lights.iter().copied().map(Some).collect();
        timed_update(self.ctx, &mut renderer, &mut self.profiler, &all_on, true)?;
        let with_passes = self.ctx.memory.device_local_bytes();
        Ok(Volume {
            renderer,
            illumination_bytes: with_renderer - before,
            propagation_bytes: with_passes - with_renderer,
            holds: all_on,
        })
    }

    /// `configs` in shared rounds, labelled `label`. An entire update re-measures
    /// `first` from an invalidated volume; a selective one goes from whichever
    /// of its two states the volume holds to the other (both directions timed,
    /// as the paper's on/off), after an untimed update to `first` when the
    /// volume holds another configuration's state. Updates that come out as
    /// another kind (e.g. a re-base) are left out.
    pub fn measure_updates(
        &mut self,
        label: &str,
        volumes: &mut [Volume],
        configs: &[UpdateConfig],
    ) -> Result<Vec<UpdateMeasurement>, ExperimentError> {
        let timings = self.rounds(label, configs.len(), |ctx, profiler, c, _| {
            let config = &configs[c];
            let volume = &mut volumes[config.volume];
            let entire = config.update.expected_kind() != UpdateKind::Selective;
            let to = if entire {
                &config.first
            } else if volume.holds == config.first {
                &config.second
            } else if volume.holds == config.second {
                &config.first
            } else {
                timed_update(ctx, &mut volume.renderer, profiler, &config.first, false)?;
                &config.second
            };
            let (ms, frame) = timed_update(ctx, &mut volume.renderer, profiler, to, entire)?;
            volume.holds.clone_from(to);
            Ok(if frame.update.plan.kind == config.update.expected_kind() {
                Sample::timed(ms, frame)
            } else {
                Sample::left_out(frame)
            })
        })?;
        let mut out = Vec::new();
        for (config, timing) in configs.iter().zip(timings) {
            if timing.left_out() > 0 {
                self.progress.message(&format!(
                    "  {label}, {}: {} of {} timed updates were {:?}, not {:?} ({}); left out",
                    config.update.name(),
                    timing.left_out(),
                    timing.rounds.len(),
                    timing.last.update.plan.kind,
                    config.update.expected_kind(),
                    timing.last.update.plan.reason
                ));
            }
            let volume = &volumes[config.volume];
            out.push(UpdateMeasurement {
                timing,
                grid: volume.renderer.grid(),
                illumination_bytes: volume.illumination_bytes,
                propagation_bytes: volume.propagation_bytes,
            });
        }
        Ok(out)
    }

    /// Incremental mode in shared rounds, labelled `label`: an entire update
    /// of `lights` on `entire` beside each of `incremental` (their
    /// `[lightvolume]` tables set the passes per frame) run from an empty volume
    /// until complete. The warm-up round records every pass and compiles the shaders.
    pub fn incremental(
        &mut self,
        label: &str,
        entire: &mut LightVolumeRenderer,
        incremental: &mut [LightVolumeRenderer],
        lights: &[Option<Light>],
    ) -> Result<IncrementalRounds, ExperimentError> {
        let mut most = Series::new(1 + incremental.len());
        let mut timings = self.rounds(label, 1 + incremental.len(), |ctx, profiler, c, phase| {
            if c == 0 {
                let (ms, _) = timed_update(ctx, entire, profiler, lights, true)?;
                return Ok(Sample::timed(ms, IncrementalRun { frame_ms: vec![ms], grid: entire.grid() }));
            }
            let run = incremental_run(ctx, &mut incremental[c - 1], profiler, lights)?;
            most.push(c, phase, run.frame_ms.iter().copied().fold(0.0, f64::max));
            Ok(Sample::timed(run.frame_ms.iter().sum(), run))
        })?;
        let runs = timings.drain(1..).enumerate().map(|(i, t)| (t, most.take(i + 1))).collect();
        let entire = timings.pop().expect("the entire update is configuration 0");
        Ok(IncrementalRounds { entire, runs })
    }

    /// Full frames in shared rounds, labelled `label`: DVR on `dvr`, then each
    /// of `volumes` rendering `all_on`, every light volume frame from an entire update.
    pub fn full_frames(
        &mut self,
        label: &str,
        dvr: &GpuScene,
        volumes: &mut [LightVolumeRenderer],
        all_on: &[Option<Light>],
        (width, height): (u32, u32),
    ) -> Result<Vec<FullFrames>, ExperimentError> {
        let n = 1 + volumes.len();
        let (mut update_ms, mut raycast_ms) = (Series::new(n), Series::new(n));
        let timings = self.rounds(label, n, |ctx, profiler, c, phase| {
            if c == 0 {
                let out = render(dvr, Technique::Dvr, width, height, profiler)?;
                let frame = FullFrame { image: out.image, dispatches: out.dispatches, light_volume: None };
                return Ok(Sample::timed(out.profile.gpu_ms_total, frame));
            }
            let renderer = &mut volumes[c - 1];
            renderer.invalidate();
            profiler.reset();
            let mut frame = renderer.render(all_on, width, height, profiler, false)?;
            let profile = profiler.resolve(ctx.memory.device_local_peak())?;
            update_ms.push(c, phase, profile.pass_ms(UpdateKind::Entire.scope_name()));
            raycast_ms.push(c, phase, profile.pass_ms("lightvolume_raycast"));
            let image = frame
                .image
                .take()
                .ok_or_else(|| ExperimentError::Invalid("light volume frame without an image".into()))?;
            let dispatches = frame.dispatches;
            Ok(Sample::timed(profile.gpu_ms_total, FullFrame { image, dispatches, light_volume: Some(frame) }))
        })?;
        Ok(timings
            .into_iter()
            .enumerate()
            .map(|(c, timing)| FullFrames { timing, update_ms: update_ms.take(c), raycast_ms: raycast_ms.take(c) })
            .collect())
    }
}

/// Incremental mode from an empty volume: frames until the update is complete.
fn incremental_run(
    ctx: &Context,
    renderer: &mut LightVolumeRenderer,
    profiler: &mut Profiler,
    lights: &[Option<Light>],
) -> Result<IncrementalRun, ExperimentError> {
    renderer.invalidate();
    let mut frame_ms = Vec::new();
    loop {
        let (ms, frame) = timed_update(ctx, renderer, profiler, lights, false)?;
        if frame.update.plan.kind == UpdateKind::Unchanged {
            break;
        }
        frame_ms.push(ms);
        if frame_ms.len() > MAX_INCREMENTAL_FRAMES {
            return Err(ExperimentError::NotConverged(MAX_INCREMENTAL_FRAMES));
        }
    }
    Ok(IncrementalRun { frame_ms, grid: renderer.grid() })
}

/// One update, timed by its own profiler scope.
fn timed_update(
    ctx: &Context,
    renderer: &mut LightVolumeRenderer,
    profiler: &mut Profiler,
    state: &[Option<Light>],
    entire: bool,
) -> Result<(f64, LightVolumeFrame), RenderError> {
    if entire {
        renderer.invalidate();
    }
    profiler.reset();
    let frame = renderer.update(state, profiler)?;
    let profile = profiler.resolve(ctx.memory.device_local_peak())?;
    Ok((profile.pass_ms(frame.update.plan.kind.scope_name()), frame))
}
