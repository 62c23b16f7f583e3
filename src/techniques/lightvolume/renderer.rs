//! The light volume kept from frame to frame: the illumination volume, what it
//! holds (contributions), the recorded passes, and the view pass. Each frame
//! plans an update (plan.rs), runs its passes from their secondary command
//! buffers and ray casts the image.

use super::groups::{contributions, Contribution, PropagationGroup};
use super::illumination::{IlluminationReadback, IlluminationVolume};
use super::pass_cache::{PassCache, PassKey, RecordedPass};
use super::plan::{apply, drift_after, plan_update, PeakGeometry, PlanState, UpdateKind, UpdatePlan};
use super::propagation::{Capacity, GroupEntry, Propagation, MAX_ENTRIES, SCENE_MAX_ENTRIES};
use super::raycast::RayCast;
use super::settings::LightVolumeSettings;
use crate::linear_image::LinearImage;
use crate::render::frame_params::{frame_params, GpuLight, MarchSteps};
use crate::render::view_chunks::ChunkSync;
use crate::render::{GpuScene, OutputImage, RenderError};
use crate::scene::settings_table::SettingsTable;
use crate::scene::Light;
use crate::vk::barriers::{Access, Barrier};
use crate::vk::commands::{submit_and_wait, submit_and_wait_or};
use crate::vk::{Buffer, Profiler, Recorder};
use ash::vk;
use glam::UVec3;
use std::sync::Arc;

/// What an update did and why.
#[derive(Clone, Debug)]
pub struct UpdateReport {
    pub plan: UpdatePlan,
    /// Passes recorded into new secondary command buffers this frame, and
    /// passes replayed from earlier ones.
    pub recorded: usize,
    pub reused: usize,
    /// Bound on the rounding error selective updates have left since the last
    /// entire update (volume units).
    pub drift_bound: f64,
}

/// A frame recorded by [`LightVolumeRenderer::record_frame`]: its update, and
/// the output image when a view was asked for.
pub struct RecordedUpdate {
    pub output: Option<Arc<OutputImage>>,
    pub update: UpdateReport,
}

/// One frame: the update, and the image when a view was asked for.
pub struct LightVolumeFrame {
    pub image: Option<LinearImage>,
    pub dispatches: u32,
    pub barriers: u32,
    /// Illumination volume size.
    pub grid: UVec3,
    pub update: UpdateReport,
    /// The illumination volume after the frame, when asked for.
    pub illumination: Option<IlluminationReadback>,
}

impl LightVolumeFrame {
    /// The passes that ran, in order.
    pub fn groups(&self) -> &[PropagationGroup] {
        &self.update.plan.passes
    }
}

struct ViewPass {
    width: u32,
    height: u32,
    _frame: Buffer,
    output: Arc<OutputImage>,
    raycast: RayCast,
    readback: Buffer,
}

pub struct LightVolumeRenderer<'s> {
    gpu: &'s GpuScene<'s>,
    pub settings: LightVolumeSettings,
    illumination: IlluminationVolume,
    propagation: Option<Propagation>,
    cache: PassCache,
    /// Mirror of the slot buffer (None: never written).
    slot_states: Vec<Option<GpuLight>>,
    /// What the volume holds.
    present: Vec<Contribution>,
    plan_state: PlanState,
    geometry: PeakGeometry,
    view: Option<ViewPass>,
    updates: u64,
}

impl<'s> LightVolumeRenderer<'s> {
    pub fn new(gpu: &'s GpuScene<'s>) -> Result<Self, RenderError> {
        let settings = gpu.scene.settings.get::<LightVolumeSettings>().into_owned();
        settings.validate()?;
        let illumination = IlluminationVolume::new(
            gpu.ctx,
            &gpu.frame_images,
            gpu.scene.volume.dims,
            settings.scale,
            settings.compensated,
        )?;
        let bx = gpu.scene.volume_box();
        Ok(LightVolumeRenderer {
            gpu,
            settings,
            illumination,
            propagation: None,
            cache: PassCache::default(),
            slot_states: Vec::new(),
            present: Vec::new(),
            plan_state: PlanState { invalid: true, ..Default::default() },
            geometry: PeakGeometry { box_half: bx.half_extent, voxel_length: bx.voxel_length },
            view: None,
            updates: 0,
        })
    }

    pub fn grid(&self) -> UVec3 {
        self.illumination.size
    }

    /// The next update rebuilds the volume entirely (after a change of the
    /// data or the transfer function, which every light sees).
    pub fn invalidate(&mut self) {
        self.plan_state.invalid = true;
    }

    /// Brings the volume up to `lights` (`None`: a light switched off; the
    /// index is the light's identity) without rendering an image.
    pub fn update(
        &mut self,
        lights: &[Option<Light>],
        profiler: &mut Profiler,
    ) -> Result<LightVolumeFrame, RenderError> {
        self.frame(lights, None, profiler, false)
    }

    /// Updates the volume and ray casts a `width` x `height` image.
    pub fn render(
        &mut self,
        lights: &[Option<Light>],
        width: u32,
        height: u32,
        profiler: &mut Profiler,
        read_illumination: bool,
    ) -> Result<LightVolumeFrame, RenderError> {
        self.frame(lights, Some((width, height)), profiler, read_illumination)
    }

    fn frame(
        &mut self,
        lights: &[Option<Light>],
        view: Option<(u32, u32)>,
        profiler: &mut Profiler,
        read_illumination: bool,
    ) -> Result<LightVolumeFrame, RenderError> {
        let ctx = self.gpu.ctx;
        let illumination_readback =
            if read_illumination { Some(self.illumination.readback_buffers(ctx)?) } else { None };
        let (recorded, dispatches, barriers) = submit_and_wait_or(ctx, "lightvolume frame", |rec| {
            let recorded = self.record_frame(rec, lights, view, profiler)?;
            if let (Some(output), Some(v)) = (&recorded.output, &self.view) {
                output.record_readback(rec, &v.readback);
            }
            if let Some(buffers) = &illumination_readback {
                self.illumination.record_readback(rec, buffers);
            }
            Ok::<_, RenderError>((recorded, rec.dispatch_count, rec.barrier_count))
        })?;
        let image = match (&recorded.output, &self.view) {
            (Some(output), Some(v)) => Some(output.read(&v.readback)?),
            _ => None,
        };
        let volume = match &illumination_readback {
            Some(buffers) => Some(self.illumination.read(buffers)?),
            None => None,
        };
        let update = recorded.update;
        Ok(LightVolumeFrame { image, dispatches, barriers, grid: self.illumination.size, update, illumination: volume })
    }

    /// Records the update to `lights` and, with `view`, the ray cast into
    /// `rec`, a command buffer its caller submits (the viewer); the frame is
    /// left in the view's output image as `crate::render::RecordedFrame` says.
    /// The caller makes sure the previous frame finished: the update writes
    /// host-visible buffers the previous one read, and replays its secondaries.
    pub fn record_frame(
        &mut self,
        rec: &mut Recorder,
        lights: &[Option<Light>],
        view: Option<(u32, u32)>,
        profiler: &mut Profiler,
    ) -> Result<RecordedUpdate, RenderError> {
        self.updates += 1;
        let target = contributions(lights, self.geometry.box_half);
        let plan = plan_update(&self.present, &target, &self.settings, &self.plan_state, self.geometry);
        let (pass_indices, recorded) = self.prepare_passes(&plan.passes)?;
        if let Some((width, height)) = view {
            self.prepare_view(width, height)?;
        }
        let view_pass = if view.is_some() { self.view.as_ref() } else { None };
        let (illumination, propagation, cache) = (&self.illumination, &self.propagation, &self.cache);
        // The volume, slots and entries carry over from the previous frame,
        // whose last use of them varies (propagation, ray cast or readback).
        rec.barrier(&Barrier::memory("previous_frame_to_this_frame", Access::ANY, Access::ANY));
        if plan.kind != UpdateKind::Unchanged {
            let update_scope = profiler.begin(rec, plan.kind.scope_name())?;
            if plan.kind == UpdateKind::Entire {
                illumination.record_clear(rec);
            }
            if let (Some(p), false) = (propagation, pass_indices.is_empty()) {
                p.record_prepare(rec);
                for &i in &pass_indices {
                    let pass = &cache.passes[i];
                    let scope = profiler.begin(rec, &pass.name)?;
                    rec.execute(&pass.commands, 0);
                    profiler.end(rec, scope)?;
                }
            }
            profiler.end(rec, update_scope)?;
        }
        if let Some(v) = view_pass {
            // Read and written: the chunks of the ray cast ping-pong with it.
            v.output.prepare_for_compute_read_write(rec);
            let scope = profiler.begin(rec, "lightvolume_raycast")?;
            v.raycast.record(rec, v.width, v.height, ChunkSync::Barrier);
            profiler.end(rec, scope)?;
        }
        let output = view_pass.map(|v| v.output.clone());
        let drift = drift_after(&self.plan_state, &self.present, &plan, &self.settings, self.geometry);
        apply(&mut self.present, plan.kind == UpdateKind::Entire, &plan.passes);
        self.plan_state = PlanState { invalid: false, pending: plan.deferred > 0, drift };
        let update = UpdateReport { recorded, reused: plan.passes.len() - recorded, drift_bound: drift.bound, plan };
        Ok(RecordedUpdate { output, update })
    }

    /// Reads the illumination volume back (its own submission).
    pub fn read_illumination(&self) -> Result<IlluminationReadback, RenderError> {
        if self.updates == 0 {
            // The volume has no contents (nor layout) before its first clear.
            return Err(RenderError::Invalid("the illumination volume is read before its first update".into()));
        }
        let ctx = self.gpu.ctx;
        let buffers = self.illumination.readback_buffers(ctx)?;
        submit_and_wait(ctx, "lightvolume readback", |rec| {
            rec.barrier(&Barrier::memory("previous_frame_to_readback", Access::ANY, Access::ANY));
            self.illumination.record_readback(rec, &buffers);
            Ok(())
        })?;
        self.illumination.read(&buffers)
    }

    fn prepare_view(&mut self, width: u32, height: u32) -> Result<(), RenderError> {
        if self.view.as_ref().is_some_and(|v| v.width == width && v.height == height) {
            return Ok(());
        }
        let (gpu, ctx) = (self.gpu, self.gpu.ctx);
        let params = frame_params(gpu.scene, width, height, gpu.lut_size, MarchSteps::render(gpu.scene));
        let frame = Buffer::with_data(ctx, "lightvolume view params", &[params], vk::BufferUsageFlags::STORAGE_BUFFER)?;
        let output = gpu.frame_images.output(ctx, "lightvolume output", width, height)?;
        let raycast = RayCast::new(gpu, &frame, &self.illumination, &output)?;
        let readback = output.readback_buffer(ctx)?;
        self.view = Some(ViewPass { width, height, _frame: frame, output, raycast, readback });
        Ok(())
    }

    /// Slot of every member of `passes`, and the light states to write. Slots
    /// hold distinct light states, whoever they belong to: a state already in a
    /// slot is read from there (so passes recorded against it stay valid, e.g.
    /// both directions of a light moved back and forth); a new one takes an
    /// empty slot, else one no kept pass reads, else any slot this update does
    /// not need. The caller makes sure there are at least as many slots as
    /// distinct states.
    fn assign_slots(&self, passes: &[PropagationGroup], capacity: usize) -> (Vec<Vec<u32>>, Vec<(usize, GpuLight)>) {
        let mut states = self.slot_states.clone();
        states.resize(capacity, None);
        let needed: Vec<GpuLight> = passes.iter().flat_map(|p| p.members.iter().map(|m| m.state)).collect();
        let is_needed = |s: &Option<GpuLight>| s.is_some_and(|s| needed.contains(&s));
        let kept_reads =
            |slot: usize| self.cache.passes.iter().any(|p| p.key.entries.iter().any(|e| e.0 as usize == slot));
        let mut writes = Vec::new();
        let mut slot_of = |state: GpuLight, states: &mut Vec<Option<GpuLight>>| -> usize {
            if let Some(i) = states.iter().position(|s| *s == Some(state)) {
                return i;
            }
            let victim = states
                .iter()
                .position(|s| s.is_none())
                .or_else(|| (0..states.len()).find(|&i| !is_needed(&states[i]) && !kept_reads(i)))
                .or_else(|| (0..states.len()).find(|&i| !is_needed(&states[i])))
                .expect("at least as many slots as distinct states");
            states[victim] = Some(state);
            writes.push((victim, state));
            victim
        };
        let slots =
            passes.iter().map(|p| p.members.iter().map(|m| slot_of(m.state, &mut states) as u32).collect()).collect();
        (slots, writes)
    }

    /// Makes every pass of `passes` available as a recorded secondary: reused
    /// where the cache has it, recorded otherwise. Returns their cache indices
    /// and how many were recorded.
    fn prepare_passes(&mut self, passes: &[PropagationGroup]) -> Result<(Vec<usize>, usize), RenderError> {
        if passes.is_empty() {
            return Ok((Vec::new(), 0));
        }
        let need = Capacity::needed(passes);
        if need.entries > MAX_ENTRIES {
            return Err(RenderError::Invalid(format!(
                "lightvolume: this update propagates {} light contributions, at most {MAX_ENTRIES} fit one update \
                 (the scene's limit of {} lights needs at most {SCENE_MAX_ENTRIES})",
                need.entries,
                crate::scene::scene_schema::MAX_LIGHTS,
            )));
        }
        let fits = self.propagation.as_ref().is_some_and(|p| p.capacity.holds(&need));
        if !fits {
            let old = self.propagation.as_ref().map(|p| p.capacity);
            let capacity = need.grown(old, self.settings.pass_lights);
            // New buffers: nothing recorded against the old ones survives.
            self.cache = PassCache::default();
            self.slot_states.clear();
            self.propagation = None;
            self.propagation = Some(Propagation::new(self.gpu, &self.illumination, capacity, &self.settings)?);
            return self.prepare_passes(passes);
        }
        let capacity = self.propagation.as_ref().map_or(0, |p| p.capacity.slots);
        let (slots, writes) = self.assign_slots(passes, capacity);
        let propagation = self.propagation.as_mut().expect("checked above");
        for (slot, state) in &writes {
            propagation.write_slots(*slot, std::slice::from_ref(state))?;
            if self.slot_states.len() <= *slot {
                self.slot_states.resize(*slot + 1, None);
            }
            self.slot_states[*slot] = Some(*state);
        }
        self.cache.retain_valid(&self.slot_states);
        // Before this update's passes join, so the indices handed out stay put.
        self.cache.trim();
        let mut indices = Vec::new();
        let mut recorded = 0;
        for (pass, pass_slots) in passes.iter().zip(&slots) {
            let key = PassKey::new(pass, pass_slots);
            if let Some(i) = self.cache.find(&key) {
                if !indices.contains(&i) {
                    self.cache.passes[i].last_used = self.updates;
                    indices.push(i);
                    continue;
                }
            }
            let capacity = propagation.capacity.entries;
            let Some(first) = self.cache.free_region(pass.members.len(), capacity) else {
                // Fragmented: start over with every pass laid out afresh.
                self.cache = PassCache::default();
                self.slot_states.clear();
                self.propagation = None;
                return self.prepare_passes(passes);
            };
            let entries: Vec<GroupEntry> = pass
                .members
                .iter()
                .zip(pass_slots)
                .enumerate()
                .map(|(layer, (m, &slot))| propagation.entry(pass, m, slot, layer as u32))
                .collect();
            propagation.write_entries(first, &entries)?;
            let commands = propagation.record_pass(self.gpu.ctx, pass, first as u32, self.settings.racy)?;
            recorded += 1;
            self.cache.passes.push(RecordedPass {
                key,
                name: if self.settings.racy { format!("{}_RACY", pass.scope_name()) } else { pass.scope_name() },
                first_entry: first,
                commands,
                last_used: self.updates,
            });
            indices.push(self.cache.passes.len() - 1);
        }
        Ok((indices, recorded))
    }
}
