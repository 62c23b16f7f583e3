//! The light volume experiments of `sweeplab bench lights` (the selective light
//! updates paper, Sundén and Ropinski 2015): the lights of its Table 1 and
//! Figure 10, a scene per measurement, the four updates of a Table 1 row and
//! how each is timed, incremental mode until complete, and full frames for the
//! error against the ground truth.

use crate::bench::harness::{Harness, Measurement, Sample};
use crate::bench::progress::Progress;
use crate::bench::ExperimentError;
use crate::lightvolume::{CostEstimate, LightVolumeFrame, LightVolumeRenderer, LightVolumeSettings, UpdateKind};
use crate::render::{GpuScene, RenderError, VolumeTexels};
use crate::scene::{Falloff, Light, LightKind, Scene};
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

/// What repeated updates of one kind cost.
pub struct UpdateMeasurement {
    /// Update GPU ms of the timed updates of the expected kind; the last
    /// timed update's frame (counted or not).
    pub timing: Measurement<LightVolumeFrame>,
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
/// the update was complete.
pub struct IncrementalRun {
    pub frame_ms: Vec<f64>,
    pub grid: UVec3,
}

/// Full frames (entire update + ray cast) of one light volume renderer.
pub struct LightVolumeFrames {
    /// Frame GPU ms; the last frame and its device-local memory peak.
    pub timing: Measurement<(LightVolumeFrame, u64)>,
    /// The entire update and the ray cast of each timed frame.
    pub update_ms: Vec<f64>,
    pub raycast_ms: Vec<f64>,
}

/// What every light volume measurement uses: the device, the profiler, the
/// progress line and the harness (its warm-up is the experiment's own: see
/// each measurement).
pub struct LightsMeter<'c> {
    pub ctx: &'c Context,
    pub profiler: Profiler,
    pub progress: Progress,
    pub harness: Harness,
}

impl LightsMeter<'_> {
    /// One update, timed by its own profiler scope.
    fn timed_update(
        &mut self,
        renderer: &mut LightVolumeRenderer,
        state: &[Option<Light>],
        entire: bool,
    ) -> Result<(f64, LightVolumeFrame), RenderError> {
        timed_update(self.ctx, renderer, &mut self.profiler, state, entire)
    }

    /// Measures `updates` on one renderer of `scene` (whose `[lightvolume]` table
    /// they share): first an untimed entire update of all `lights` (it records
    /// the passes, and llvmpipe compiles the shaders on first use), whose memory
    /// is kept in each result.
    pub fn measure_updates(
        &mut self,
        scene: &Scene,
        lights: &[Light],
        updates: &[Update],
        label: &str,
    ) -> Result<Vec<UpdateMeasurement>, RenderError> {
        let gpu = GpuScene::upload(self.ctx, scene)?;
        let before = self.ctx.memory.device_local_bytes();
        let mut renderer = LightVolumeRenderer::new(&gpu)?;
        let with_renderer = self.ctx.memory.device_local_bytes();
        let first: Vec<Option<Light>> = lights.iter().copied().map(Some).collect();
        self.timed_update(&mut renderer, &first, true)?;
        let with_passes = self.ctx.memory.device_local_bytes();
        let mut out = Vec::new();
        for &update in updates {
            self.progress.start_step(&format!("{label}: {}", update.name()));
            let mut second = first.clone();
            match update {
                Update::StateChange => second[0] = Some(moved(&lights[0])),
                Update::Toggle => second[0] = None,
                Update::EntireSequential | Update::EntireCoherent => {}
            }
            let timing = self.measure(&mut renderer, update, (&first, &second))?;
            self.progress.finish_step();
            if timing.left_out > 0 {
                self.progress.message(&format!(
                    "  {} of {} timed updates were {:?}, not {:?} ({}); left out",
                    timing.left_out,
                    self.harness.repeat(),
                    timing.last.update.plan.kind,
                    update.expected_kind(),
                    timing.last.update.plan.reason
                ));
            }
            out.push(UpdateMeasurement {
                timing,
                grid: renderer.grid(),
                illumination_bytes: with_renderer - before,
                propagation_bytes: with_passes - with_renderer,
            });
        }
        Ok(out)
    }

    /// Timed updates of `update`. Entire updates re-measure `first`; selective
    /// ones alternate between `first` and `second`, after an untimed change to
    /// `second` (which records its passes). The renderer holds `first` before
    /// and after. Updates that come out as another kind (e.g. a re-base) are left out.
    fn measure(
        &mut self,
        renderer: &mut LightVolumeRenderer,
        update: Update,
        (first, second): (&[Option<Light>], &[Option<Light>]),
    ) -> Result<Measurement<LightVolumeFrame>, RenderError> {
        let selective = update.expected_kind() == UpdateKind::Selective;
        let mut now_second = false;
        if selective {
            self.timed_update(renderer, second, false)?;
            now_second = true;
        }
        let (ctx, profiler) = (self.ctx, &mut self.profiler);
        let timing = self.harness.measure(|| {
            let state = if now_second { first } else { second };
            let (t, frame) = if selective {
                now_second = !now_second;
                timed_update(ctx, renderer, profiler, state, false)?
            } else {
                timed_update(ctx, renderer, profiler, first, true)?
            };
            Ok::<_, RenderError>(if frame.update.plan.kind == update.expected_kind() {
                Sample::timed(t, frame)
            } else {
                Sample::left_out(frame)
            })
        })?;
        if now_second {
            self.timed_update(renderer, first, false)?;
        }
        Ok(timing)
    }

    /// GPU ms of one entire update of `lights` on `scene`, after an untimed one.
    pub fn entire_update_ms(&mut self, scene: &Scene, lights: &[Option<Light>]) -> Result<f64, RenderError> {
        let gpu = GpuScene::upload(self.ctx, scene)?;
        let mut renderer = LightVolumeRenderer::new(&gpu)?;
        let (ctx, profiler) = (self.ctx, &mut self.profiler);
        let timing = Harness::once_after(1).measure(|| {
            let (ms, _) = timed_update(ctx, &mut renderer, profiler, lights, true)?;
            Ok::<_, RenderError>(Sample::timed(ms, ()))
        })?;
        Ok(timing.median())
    }

    /// Incremental mode on `scene` (its `[lightvolume]` table sets the passes
    /// per frame): frames from an empty volume until the update is complete.
    pub fn incremental(&mut self, scene: &Scene, lights: &[Option<Light>]) -> Result<IncrementalRun, ExperimentError> {
        let gpu = GpuScene::upload(self.ctx, scene)?;
        let mut renderer = LightVolumeRenderer::new(&gpu)?;
        // Untimed: records every pass and compiles the shaders.
        while self.timed_update(&mut renderer, lights, false)?.1.update.plan.kind != UpdateKind::Unchanged {}
        renderer.invalidate();
        let mut frame_ms = Vec::new();
        loop {
            let (ms, frame) = self.timed_update(&mut renderer, lights, false)?;
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

    /// Full frames of `all_on` on `scene`: an untimed one (it records the
    /// passes and compiles the shaders), then each timed frame from an entire update.
    pub fn lightvolume_frames(
        &mut self,
        scene: &Scene,
        texels: VolumeTexels,
        all_on: &[Option<Light>],
        (width, height): (u32, u32),
    ) -> Result<LightVolumeFrames, RenderError> {
        let gpu = GpuScene::upload_with(self.ctx, scene, texels)?;
        self.ctx.memory.reset_peak();
        let mut renderer = LightVolumeRenderer::new(&gpu)?;
        self.profiler.reset();
        renderer.render(all_on, width, height, &mut self.profiler, false)?;
        self.profiler.resolve(0)?;
        let (ctx, profiler) = (self.ctx, &mut self.profiler);
        let (mut update_ms, mut raycast_ms) = (Vec::new(), Vec::new());
        let timing = self.harness.measure(|| {
            renderer.invalidate();
            profiler.reset();
            let frame = renderer.render(all_on, width, height, profiler, false)?;
            let profile = profiler.resolve(ctx.memory.device_local_peak())?;
            update_ms.push(profile.pass_ms(UpdateKind::Entire.scope_name()));
            raycast_ms.push(profile.pass_ms("lightvolume_raycast"));
            Ok::<_, RenderError>(Sample::timed(profile.gpu_ms_total, (frame, profile.gpu_memory_bytes)))
        })?;
        Ok(LightVolumeFrames { timing, update_ms, raycast_ms })
    }
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
