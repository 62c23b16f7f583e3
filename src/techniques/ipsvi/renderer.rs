//! Records one IPSVI frame: clear the output to the background, then per light
//! and per sweep zone: initialise the cache, and one dispatch per line block,
//! with the synchronization of the frame's strategy (`super::sync`) before and
//! after each. With `merge_sweeps` (and more than one sweep): every sweep's
//! cache initialised at once, one dispatch per step of all sweeps
//! (`super::merged_steps`), then their colour accumulations summed.

use super::block_records::{block_params, SweepRecords};
use super::breakdown::BreakdownStep;
use super::cache_images::Cache;
use super::cache_plane::{cache_planes, CachePlanes};
use super::cache_update::{CacheUpdate, CacheWrite, WriteRule, WriteValue};
use super::exit_points::{self, ExitPoints};
use super::gpu_params::{line_planes, sweep_params, BlockParams, SweepInputs, SweepParams, FLAG_FIRST_LIGHT};
use super::line_group::{lavapipe_threads, line_group_size, median_pixels};
use super::line_kernel::{self, KernelChoice};
use super::line_shape::ShapeCounters;
use super::merged_output::MergedOutput;
use super::merged_steps::{self, LineDispatch, MergedSteps};
use super::settings::{EarlyTermination, IpsviSettings};
use super::study::IpsviStudy;
use super::sweep_plan::{plan, LineBlock, SweepPlan};
use super::sync::{
    record_sweeps, GlobalBarrier, ImageBarriers, LineSync, ReplayedSweeps, RerecordedSweeps, SplitBarriers,
    SubmissionPerBlock, Unsynchronized,
};
use super::sync_strategy::SyncStrategy;
use super::view_stops::{ViewStops, ViewStopsInputs};
use crate::render::frame_params::{frame_params, MarchSteps};
use crate::render::frame_result::FrameResult;
use crate::render::image_space::ImageSpace;
use crate::render::{GpuScene, LineShape, OutputImage, RecordedFrame, RenderError};
use crate::scene::settings_table::SettingsTable;
use crate::scene::Scene;
use crate::shaders::{ipsvi_cache_init, ipsvi_line, ipsvi_line_segmented};
use crate::vk::barriers::{Access, Barrier};
use crate::vk::commands::{submit_and_wait_or, SecondaryCommands};
use crate::vk::descriptors::Resource;
use crate::vk::pipeline::{ComputePipeline, ComputePipelineDesc};
use crate::vk::subgroups::SubgroupSupport;
use crate::vk::{Buffer, Image, Profiler, Recorder, VkError};
use ash::vk;
use std::cell::OnceCell;
use std::sync::Arc;

/// Plans for every light, in light order.
pub fn plans(gpu: &GpuScene, settings: &IpsviSettings, width: u32, height: u32) -> Vec<SweepPlan> {
    scene_plans(gpu.scene, settings, width, height)
}

/// [`plans`] from the scene alone (what a frame will allocate, before it is rendered).
pub fn scene_plans(scene: &Scene, settings: &IpsviSettings, width: u32, height: u32) -> Vec<SweepPlan> {
    study_plans(scene, settings, &IpsviStudy::default(), width, height)
}

/// [`scene_plans`] for a study (its single-dispatch baseline).
pub fn study_plans(
    scene: &Scene,
    settings: &IpsviSettings,
    study: &IpsviStudy,
    width: u32,
    height: u32,
) -> Vec<SweepPlan> {
    let space = ImageSpace { basis: scene.camera.basis(width, height), width, height };
    let bbox = space.projected_box(&scene.volume_box());
    scene
        .rendered_lights()
        .iter()
        .map(|l| {
            let mut p = plan(bbox, space.light_anchor(&l.kind), settings.line_width, settings.zone_blend_px);
            if study.single_dispatch_baseline {
                for sweep in &mut p.sweeps {
                    sweep.blocks = vec![single_block(&sweep.blocks)];
                }
            }
            p
        })
        .collect()
}

/// All of a sweep's lines as one block (the single-dispatch study baseline).
fn single_block(blocks: &[LineBlock]) -> LineBlock {
    let first = blocks.iter().map(|b| b.first).min().unwrap_or(0);
    let end = blocks.iter().map(|b| b.first + b.width).max().unwrap_or(0);
    let span_start = blocks.iter().map(|b| b.span_start).min().unwrap_or(0);
    let span_end = blocks.iter().map(|b| b.span_start + b.span_len).max().unwrap_or(0);
    let last_line = blocks.last().map(|b| b.last_line).unwrap_or(0);
    LineBlock { first, width: end - first, span_start, span_len: span_end - span_start, last_line }
}

pub fn render(gpu: &GpuScene, width: u32, height: u32, profiler: &mut Profiler) -> Result<FrameResult, RenderError> {
    let settings = &gpu.scene.settings.get::<IpsviSettings>();
    render_with(gpu, settings, width, height, profiler, settings.sync)
}

pub fn render_with(
    gpu: &GpuScene,
    settings: &IpsviSettings,
    width: u32,
    height: u32,
    profiler: &mut Profiler,
    sync: SyncStrategy,
) -> Result<FrameResult, RenderError> {
    if gpu.scene.lights.is_empty() {
        // No light, no sweep: emission-absorption ray casting, nothing else allocated.
        return crate::render::raycast::emission_only(gpu, width, height, profiler);
    }
    IpsviRenderer::new(gpu, settings, width, height)?.frame(profiler, sync)
}

/// [`render_with`] for a study or test ([`IpsviStudy`]).
pub fn render_study(
    gpu: &GpuScene,
    settings: &IpsviSettings,
    study: &IpsviStudy,
    width: u32,
    height: u32,
    profiler: &mut Profiler,
    sync: SyncStrategy,
) -> Result<FrameResult, RenderError> {
    IpsviRenderer::build(gpu, settings, study, width, height, None)?.frame(profiler, sync)
}

/// Everything one IPSVI configuration needs, created once: plans, parameter
/// buffers, cache, pipelines, descriptor sets. `frame` records and runs a frame;
/// benchmarks call it repeatedly without re-creating anything.
pub struct IpsviRenderer<'a> {
    ctx: &'a crate::vk::Context,
    background: glam::Vec3,
    settings: IpsviSettings,
    study: IpsviStudy,
    plans: Vec<SweepPlan>,
    /// The line kernel and its segments per pixel.
    kernel: KernelChoice,
    /// The block records, as the line dispatches read them.
    block_records: Vec<BlockParams>,
    /// Merged: the step table (which blocks each dispatch runs).
    step_table: Vec<u32>,
    shape: ShapeCounters,
    /// The line dispatches of a frame, in order.
    dispatches: Vec<LineDispatch>,
    /// (first dispatch, dispatch count) of every sweep, in frame order; one
    /// sweep of steps when merged.
    sweep_dispatches: Vec<SweepRecords>,
    _frame: Buffer,
    _planes: Buffer,
    _sweeps: Buffer,
    _blocks: Buffer,
    _steps: Buffer,
    /// `merge_sweeps` with more than one sweep: the accumulation and its sum.
    merged: Option<MergedOutput>,
    output: Arc<OutputImage>,
    cache: Cache,
    exit_points: Option<ExitPoints>,
    placeholder: Option<Arc<Image>>,
    /// The segmented kernel's stops (the serial one finds its own as it marches).
    view_stops: Option<ViewStops>,
    init: ComputePipeline,
    init_set: vk::DescriptorSet,
    line: ComputePipeline,
    line_set: vk::DescriptorSet,
    /// Set 1 per block parity: 0 reads side a of the pairs and writes b, 1 the opposite.
    line_sides: [vk::DescriptorSet; 2],
    /// Invocations per workgroup of the line dispatches (glsl/ipsvi_line.comp's
    /// local_size_x_id).
    line_group: u32,
    readback: Buffer,
    /// The sweeps recorded once for `SyncStrategy::Secondary`, on first use.
    secondaries: OnceCell<SecondaryCommands>,
}

impl<'a> IpsviRenderer<'a> {
    /// For a scene with at least one light.
    pub fn new(gpu: &GpuScene<'a>, settings: &IpsviSettings, width: u32, height: u32) -> Result<Self, RenderError> {
        Self::build(gpu, settings, &IpsviStudy::default(), width, height, None)
    }

    /// [`new`](Self::new) with the line dispatches' workgroup size given
    /// (a power of two, 1..=64) instead of chosen for the device (`line_group`).
    pub fn with_line_group(
        gpu: &GpuScene<'a>,
        settings: &IpsviSettings,
        width: u32,
        height: u32,
        line_group: Option<u32>,
    ) -> Result<Self, RenderError> {
        Self::build(gpu, settings, &IpsviStudy::default(), width, height, line_group)
    }

    /// [`new`](Self::new) for a study or test ([`IpsviStudy`]), optionally with
    /// the workgroup size given.
    pub fn build(
        gpu: &GpuScene<'a>,
        settings: &IpsviSettings,
        study: &IpsviStudy,
        width: u32,
        height: u32,
        line_group: Option<u32>,
    ) -> Result<Self, RenderError> {
        if let Some(g) = line_group.filter(|g| !g.is_power_of_two() || *g > super::line_group::WIDEST) {
            return Err(RenderError::Invalid(format!("line workgroup size {g} is not a power of two up to 64")));
        }
        let scene = gpu.scene;
        if scene.lights.is_empty() {
            return Err(RenderError::Invalid("IPSVI sweeps need a light; render a scene without one with DVR".into()));
        }
        if width == 0 || height == 0 {
            return Err(RenderError::Invalid(format!("image size {width}x{height} is empty")));
        }
        settings.validate()?;
        let settings = &settings.sized_for(scene, width, height);
        let ctx = gpu.ctx;
        // glsl/ipsvi_line.comp declares 64-bit atomics (the claims of the
        // deterministic cache writes) for every variant of the module.
        if !ctx.int64_atomics {
            return Err(RenderError::Invalid(format!(
                "IPSVI's line shader needs shaderInt64 and shaderBufferInt64Atomics, which {} lacks",
                ctx.info.name
            )));
        }
        let kernel = line_kernel::choose(settings, &ctx.info.device_type, &SubgroupSupport::of(ctx))
            .map_err(RenderError::Invalid)?;
        let space = ImageSpace { basis: scene.camera.basis(width, height), width, height };
        let plans = study_plans(scene, settings, study, width, height);
        let claims = settings.claims_recorded(study.keep_redundant_claims);

        let steps = MarchSteps { shadow_step_voxels: settings.light_step_voxels, ..MarchSteps::render(scene) };
        let params = frame_params(scene, width, height, gpu.lut_size, steps);
        let frame = Buffer::with_data(ctx, "frame params", &[params], vk::BufferUsageFlags::STORAGE_BUFFER)?;
        let output = gpu.frame_images.output(ctx, "ipsvi output", width, height)?;
        let sweep_count = plans.iter().map(|p| p.sweeps.len() as u32).sum::<u32>();
        // One sweep has nothing to merge with: the unmerged frame, no sum pass.
        let slots = if settings.merge_sweeps && sweep_count > 1 { sweep_count } else { 1 };
        let tallest = settings.cache_size.max(height) * slots;
        if tallest > ctx.limits.max_image_dimension2_d {
            return Err(RenderError::Invalid(format!(
                "ipsvi.merge_sweeps stacks {slots} sweeps' caches and colours in images {tallest} texels tall, \
                 over this device's {}; set ipsvi.merge_sweeps = false",
                ctx.limits.max_image_dimension2_d
            )));
        }
        let cache = Cache::new(gpu, settings, claims, slots)?;

        let max_piecewise_steps = super::view_budget::piecewise_steps(scene)?;

        let exit_points = match settings.early_termination {
            EarlyTermination::ExitPoints => Some(ExitPoints::new(gpu, &frame, width, height, settings, &plans[0])?),
            _ => None,
        };
        let placeholder = if exit_points.is_none() { Some(exit_points::placeholder(gpu)?) } else { None };
        let lmax: &Image = match (&exit_points, &placeholder) {
            (Some(e), _) => &e.lmax,
            (None, Some(p)) => p,
            (None, None) => unreachable!("one of them is always created"),
        };
        let planes_host = line_planes(&space.basis, width, height);
        let planes = Buffer::with_data(ctx, "ipsvi line planes", &planes_host, vk::BufferUsageFlags::STORAGE_BUFFER)?;
        let lights = scene.rendered_lights();
        // The box the cache is fitted to and the light rays are clipped to.
        let CachePlanes { lit, planes: geometries } = cache_planes(scene, settings);
        let lit_corners = lit.corners();
        let light_scale = |i: usize| lights[i].radiance().max_element().max(scene.render.emission).max(1e-30);
        let sweep_records: Vec<SweepParams> = (0..scene.lights.len())
            .map(|i| {
                sweep_params(&SweepInputs {
                    geometry: &geometries[i],
                    anchor: plans[i].anchor,
                    blend_px: settings.zone_blend_px,
                    light_scale: light_scale(i),
                    light_index: i as u32,
                    flags: if i == 0 { FLAG_FIRST_LIGHT } else { 0 },
                    max_piecewise_steps,
                    albedo: settings.albedo,
                    cone_angle_deg: settings.cone_angle_deg,
                    ert_scale: settings.ert_scale,
                    lit_box: lit,
                })
            })
            .collect();
        let sweeps = Buffer::with_data(ctx, "ipsvi sweeps", &sweep_records, vk::BufferUsageFlags::STORAGE_BUFFER)?;
        let (mut block_records, sweep_records) =
            block_params(&plans, &geometries, &lit_corners, &planes_host, height, settings, study)?;
        if slots > 1 {
            for (slot, &(first, count)) in sweep_records.iter().enumerate() {
                for r in &mut block_records[first..first + count] {
                    r.cache_row = slot as u32 * settings.cache_size;
                    r.out_row = slot as u32 * height;
                }
            }
        }
        let blocks = Buffer::with_data(ctx, "ipsvi blocks", &block_records, vk::BufferUsageFlags::STORAGE_BUFFER)?;

        let emissive = scene.render.emission > 0.0;
        let scatter = settings.albedo > 0.0;
        let mut init = ComputePipeline::new(
            ctx,
            &ComputePipelineDesc {
                name: "ipsvi_cache_init",
                shader: &ipsvi_cache_init::INTERFACE,
                specialization: &[],
                max_sets: 1,
            },
        )?;
        let view_samples = settings.cache_update == CacheUpdate::ViewSamples;
        let nearest = settings.cache_write == CacheWrite::Nearest;
        let termination = match settings.early_termination {
            EarlyTermination::Off => 0,
            EarlyTermination::Plain => 1,
            EarlyTermination::ExitPoints => 2,
        };
        let segments = kernel.segments;
        // Segments over several subgroups: the workgroup is one pixel's, so
        // that every invocation reaching its barriers is that pixel's.
        if kernel.cross_subgroups && line_group.is_some_and(|g| g != segments) {
            return Err(RenderError::Invalid(format!(
                "ipsvi.segments = {segments} spans subgroups: the line workgroup must be one pixel's {segments} \
                 invocations, not {}",
                line_group.unwrap_or(0)
            )));
        }
        let line_group = line_group.unwrap_or_else(|| {
            if kernel.cross_subgroups {
                return segments;
            }
            line_group_size(
                &ctx.info.device_type,
                lavapipe_threads(),
                median_pixels(block_records.iter().map(|r| r.pixel_count)) * segments,
            )
        });
        if kernel.segmented
            && !kernel.cross_subgroups
            && !line_group.is_multiple_of(SubgroupSupport::of(ctx).size.max(segments))
        {
            return Err(RenderError::Invalid(format!(
                "the segmented line kernel needs whole subgroups per workgroup; {line_group} invocations is not a \
                 multiple of this device's subgroup of {}",
                SubgroupSupport::of(ctx).size
            )));
        }
        let specialization = [
            (0, emissive as u32),
            (1, scatter as u32),
            (2, view_samples as u32),
            (3, claims as u32),
            (4, nearest as u32),
            (5, study.breakdown_step.shader_step()),
            (6, settings.piecewise as u32),
            (7, termination),
            (8, line_group),
            (9, (slots > 1) as u32),
            (10, (view_samples && settings.write_value == WriteValue::TexelRay) as u32),
            (11, (view_samples && settings.write_rule == WriteRule::EverySample) as u32),
            (12, (view_samples && settings.empty_runs_move_depth) as u32),
            (13, settings.packed_store as u32),
            (14, settings.texel_pass() as u32),
            (15, settings.per_texel_fronts(gpu.scene, width, height) as u32),
            // The segmented kernel's (the serial one has no constants 16, 17, 19 and 20).
            (16, segments),
            (17, kernel.rounds),
            (18, study.digests as u32),
            (19, kernel.cross_subgroups as u32),
            (20, kernel.texel_lanes),
        ];
        // Both kernels declare the same bindings (glsl/ipsvi_line_interface.glsl):
        // the sets below serve either.
        let (name, shader) = if kernel.segmented {
            ("ipsvi_line_segmented", &ipsvi_line_segmented::INTERFACE)
        } else {
            ("ipsvi_line", &ipsvi_line::INTERFACE)
        };
        let line_desc = ComputePipelineDesc { name, shader, specialization: &specialization, max_sets: 1 };
        // One pipeline: set 0 bound once per sweep, a block's parity picks its set 1.
        let mut line = ComputePipeline::new(ctx, &line_desc)?;
        let (dispatches, sweep_dispatches, step_table) = if slots > 1 {
            let merged = merged_steps::merge(&sweep_records, &block_records, line_group, kernel.lanes());
            let all = vec![(0, merged.dispatches.len())];
            (merged.dispatches, all, merged.table)
        } else {
            // Read only by the merged shader; a storage buffer is never empty.
            (merged_steps::per_block(&block_records, line_group, kernel.lanes()), sweep_records, vec![0; 4])
        };
        let steps = Buffer::with_data(ctx, "ipsvi steps", &step_table, vk::BufferUsageFlags::STORAGE_BUFFER)?;
        let shape = ShapeCounters::new(ctx, block_records.len())?;
        let merged = if slots > 1 { Some(MergedOutput::new(gpu, &output, slots)?) } else { None };
        let [a, b] = [&cache.light[0], &cache.light[1]];
        let [fa, fb] = [&cache.front[0], &cache.front[1]];
        let init_set = init.create_set(&[
            (ipsvi_cache_init::SWEEPS, Resource::StorageBuffer(&sweeps)),
            (ipsvi_cache_init::CACHE_A, Resource::StorageImage(a)),
            (ipsvi_cache_init::FRONT_A, Resource::StorageImage(fa)),
            (ipsvi_cache_init::CACHE_B, Resource::StorageImage(b)),
            (ipsvi_cache_init::FRONT_B, Resource::StorageImage(fb)),
            (ipsvi_cache_init::STAMPS_A, Resource::StorageImage(&cache.stamps[0])),
            (ipsvi_cache_init::STAMPS_B, Resource::StorageImage(&cache.stamps[1])),
            (ipsvi_cache_init::HISTORY_A, Resource::StorageImage(&cache.history[0])),
            (ipsvi_cache_init::HISTORY_B, Resource::StorageImage(&cache.history[1])),
            (ipsvi_cache_init::PACKED_SAMPLES_A, Resource::StorageImage(&cache.packed_samples[0])),
            (ipsvi_cache_init::PACKED_SAMPLES_B, Resource::StorageImage(&cache.packed_samples[1])),
        ])?;
        let view_stops = match kernel.segmented {
            true => Some(ViewStops::new(
                gpu,
                &ViewStopsInputs {
                    frame: &frame,
                    lmax,
                    shape: &shape.counters,
                    width,
                    height,
                    // The empty workload marches nothing: no stops to find.
                    termination: if study.breakdown_step == BreakdownStep::Empty { 0 } else { termination },
                    segments,
                    cross_subgroups: kernel.cross_subgroups,
                    line_group,
                    ert_scale: settings.ert_scale,
                },
            )?),
            false => None,
        };
        let mut line_bindings = vec![
            (ipsvi_line::FRAME_BUFFER, Resource::StorageBuffer(&frame)),
            (ipsvi_line::VOLUME_TEX, Resource::SampledImage(&gpu.volume, &gpu.sampler)),
            (ipsvi_line::TRANSFER_LUT, Resource::StorageBuffer(&gpu.lut)),
            (ipsvi_line::LIGHTS, Resource::StorageBuffer(&gpu.lights)),
            (ipsvi_line::SWEEPS, Resource::StorageBuffer(&sweeps)),
            (ipsvi_line::PLANES, Resource::StorageBuffer(&planes)),
            (ipsvi_line::OUT_IMAGE, Resource::StorageImage(merged.as_ref().map_or(&output.image, |m| &m.accumulation))),
            (ipsvi_line::BLOCKS, Resource::StorageBuffer(&blocks)),
            (ipsvi_line::KEYS, Resource::StorageBuffer(&cache.claim_keys)),
            (ipsvi_line::STEPS, Resource::StorageBuffer(&steps)),
            (ipsvi_line::SHAPE, Resource::StorageBuffer(&shape.counters)),
        ];
        // The serial kernel stops as it marches (reading l_max), the segmented
        // one where the view-stops pass found.
        match &view_stops {
            Some(v) => line_bindings.push((ipsvi_line_segmented::VIEW_STOPS, Resource::StorageBuffer(&v.stops))),
            None => line_bindings.push((ipsvi_line::LMAX, Resource::StorageImage(lmax))),
        }
        let line_set = line.create_set(&line_bindings)?;
        let mut side = |from: usize, to: usize| {
            line.create_set1(&[
                (ipsvi_line::CACHE_IN, Resource::StorageImage(&cache.light[from])),
                (ipsvi_line::FRONT_IN, Resource::StorageImage(&cache.front[from])),
                (ipsvi_line::CACHE_OUT, Resource::StorageImage(&cache.light[to])),
                (ipsvi_line::FRONT_OUT, Resource::StorageImage(&cache.front[to])),
                (ipsvi_line::SAMPLES_IN, Resource::StorageImage(&cache.samples[from])),
                (ipsvi_line::STAMPS_IN, Resource::StorageImage(&cache.stamps[from])),
                (ipsvi_line::SAMPLES_OUT, Resource::StorageImage(&cache.samples[to])),
                (ipsvi_line::STAMPS_OUT, Resource::StorageImage(&cache.stamps[to])),
                (ipsvi_line::HISTORY_IN, Resource::StorageImage(&cache.history[from])),
                (ipsvi_line::HISTORY_OUT, Resource::StorageImage(&cache.history[to])),
                (ipsvi_line::PACKED_SAMPLES_IN, Resource::StorageImage(&cache.packed_samples[from])),
                (ipsvi_line::PACKED_SAMPLES_OUT, Resource::StorageImage(&cache.packed_samples[to])),
            ])
        };
        let line_sides = [side(0, 1)?, side(1, 0)?];

        let readback = output.readback_buffer(ctx)?;
        Ok(IpsviRenderer {
            ctx,
            background: scene.render.background,
            settings: settings.clone(),
            study: *study,
            plans,
            kernel,
            block_records,
            step_table,
            shape,
            dispatches,
            sweep_dispatches,
            _frame: frame,
            _planes: planes,
            _sweeps: sweeps,
            _blocks: blocks,
            _steps: steps,
            merged,
            output,
            cache,
            exit_points,
            placeholder,
            view_stops,
            init,
            init_set,
            line,
            line_set,
            line_sides,
            line_group,
            readback,
            secondaries: OnceCell::new(),
        })
    }

    /// Invocations per workgroup of the line dispatches.
    pub fn line_group(&self) -> u32 {
        self.line_group
    }

    /// The line kernel this renderer runs.
    pub fn kernel(&self) -> KernelChoice {
        self.kernel
    }

    /// The last frame's shape (its submission finished).
    fn read_shape(&self) -> Result<LineShape, RenderError> {
        let merged = self.merged.is_some();
        let blocks_of = |d: &LineDispatch| {
            if merged {
                MergedSteps::blocks_of(&self.step_table, d.index)
            } else {
                vec![d.index]
            }
        };
        let records = &self.block_records;
        let digests = self.study.digests;
        let stops = self.view_stops.as_ref().and_then(ViewStops::invocations);
        self.shape.read(self.kernel.label(), &self.dispatches, blocks_of, records, self.line_group, digests, stops)
    }

    /// Every pipeline a frame dispatches (shared with other renderers of the
    /// same shaders and specialization through the context's store): a bench
    /// warms up a renderer whose pipelines have all run already without a frame.
    pub fn pipelines(&self) -> Vec<vk::Pipeline> {
        let mut all = vec![self.init.raw, self.line.raw];
        all.extend(self.merged.iter().map(|m| m.sum.raw));
        if let Some(e) = &self.exit_points {
            all.extend(e.pipelines());
        }
        all.extend(self.view_stops.as_ref().and_then(ViewStops::pipeline));
        all
    }

    /// Secondary command buffers recorded so far (`secondary`: one per sweep,
    /// on the first frame that replays them; none for the other strategies).
    pub fn recorded_secondaries(&self) -> usize {
        self.secondaries.get().map_or(0, |s| s.buffers.len())
    }

    /// The sweeps as secondary command buffers, recorded on first use.
    fn recorded_sweeps(&self) -> Result<&SecondaryCommands, RenderError> {
        if let Some(recorded) = self.secondaries.get() {
            return Ok(recorded);
        }
        let recorded = record_sweeps(
            self.ctx,
            &self.sweep_dispatches,
            &self.dispatches,
            &self.line,
            self.line_set,
            self.line_sides,
        )?;
        Ok(self.secondaries.get_or_init(|| recorded))
    }

    /// The synchronization object of `sync` for one frame; `timed_lines`
    /// (the profiler's per-line scopes on): `secondary` records its sweeps
    /// into secondaries for this frame, since a recording replayed every frame
    /// cannot hold one frame's queries (`bench sync`'s traces).
    fn line_sync(&self, sync: SyncStrategy, timed_lines: bool) -> Result<Box<dyn LineSync + '_>, RenderError> {
        if timed_lines && sync == SyncStrategy::Secondary {
            return Ok(Box::new(RerecordedSweeps::default()));
        }
        let cache = &self.cache;
        Ok(match sync {
            SyncStrategy::BarrierGlobal => Box::new(GlobalBarrier),
            SyncStrategy::BarrierImage => {
                let claims = self.settings.claims_recorded(self.study.keep_redundant_claims);
                let mut images = cache.images().to_vec();
                images.push(&self.output.image);
                images.extend(self.merged.as_ref().map(|m| &*m.accumulation));
                let mut buffers = vec![&self.shape.counters];
                buffers.extend(claims.then_some(&cache.claim_keys));
                Box::new(ImageBarriers::new(&images, &buffers))
            }
            SyncStrategy::Events => Box::new(SplitBarriers::new(self.ctx, self.dispatches.len())?),
            SyncStrategy::Secondary => Box::new(ReplayedSweeps::new(self.recorded_sweeps()?)),
            SyncStrategy::Submits => Box::new(SubmissionPerBlock),
            SyncStrategy::Racy => Box::new(Unsynchronized),
        })
    }

    /// Records, submits and waits for one frame with the given synchronization:
    /// [`record`](Self::record) and the read-back, in one submission (several
    /// for `submits`). With the profiler's per-line scopes on, `secondary`'s
    /// sweeps are recorded for the frame so that its lines are timed too.
    pub fn frame(&mut self, profiler: &mut Profiler, sync: SyncStrategy) -> Result<FrameResult, RenderError> {
        let this = &*self;
        let timed_lines = profiler.detail();
        // The recorded frame (and what it keeps alive) outlives the submission.
        let (frame, dispatches, barriers) = submit_and_wait_or(this.ctx, "frame", |rec| {
            let frame = this.record_with(rec, profiler, this.line_sync(sync, timed_lines)?)?;
            frame.output.record_readback(rec, &this.readback);
            Ok::<_, RenderError>((frame, rec.dispatch_count, rec.barrier_count))
        })?;
        let shape = Some(this.read_shape()?);
        Ok(FrameResult { image: frame.output.read(&this.readback)?, dispatches, barriers, shape })
    }

    /// Records one frame into `rec` (see [`RecordedFrame`]): what `frame` submits
    /// and the viewer records into its own command buffer. `submits` splits
    /// `rec`, which only a recorder that owns its submission can. The frame
    /// reuses the renderer's images and (for `secondary`) its recorded sweeps:
    /// the previous frame must have finished.
    pub fn record(
        &self,
        rec: &mut Recorder,
        profiler: &mut Profiler,
        sync: SyncStrategy,
    ) -> Result<RecordedFrame, RenderError> {
        self.record_with(rec, profiler, self.line_sync(sync, false)?)
    }

    fn record_with(
        &self,
        rec: &mut Recorder,
        profiler: &mut Profiler,
        mut line_sync: Box<dyn LineSync + '_>,
    ) -> Result<RecordedFrame, RenderError> {
        let IpsviRenderer {
            background,
            settings,
            plans,
            dispatches,
            sweep_dispatches,
            output,
            cache,
            exit_points,
            placeholder,
            view_stops,
            merged,
            init,
            init_set,
            line,
            line_set,
            line_sides,
            ctx,
            ..
        } = self;
        let (init_set, line_set, line_sides) = (*init_set, *line_set, *line_sides);
        let bg = *background;
        // Records the line dispatches of one sweep (or, merged, of all steps).
        let record_lines = |rec: &mut Recorder,
                            profiler: &mut Profiler,
                            line_sync: &mut dyn LineSync,
                            sweep: usize|
         -> Result<(), VkError> {
            if line_sync.replay_sweep(rec, sweep) {
                return Ok(());
            }
            let mut record_blocks = |rec: &mut Recorder, line_sync: &mut dyn LineSync| -> Result<(), VkError> {
                // Bound once per sweep: dispatches find their parameters by index.
                rec.bind(line, line_set);
                let (first, count) = sweep_dispatches[sweep];
                for (n, d) in dispatches.iter().enumerate().skip(first).take(count) {
                    line_sync.before_block(rec, n);
                    line_sync.bind_line(rec, line, line_set, line_sides[d.parity as usize]);
                    let line_scope = profiler.begin_detail(rec, "ipsvi_line")?;
                    rec.push(line, &d.index);
                    rec.dispatch(d.groups, 1, 1);
                    profiler.end(rec, line_scope)?;
                    line_sync.after_block(rec, n)?;
                }
                Ok(())
            };
            if line_sync.records_sweeps_per_frame() {
                let recorded =
                    SecondaryCommands::record(ctx, "ipsvi sweep (timed)", 1, |_, srec| record_blocks(srec, line_sync))?;
                rec.execute(&recorded, 0);
                line_sync.keep_secondary(recorded);
                return Ok(());
            }
            record_blocks(rec, line_sync)
        };
        // The first sweep's initialisation shares its barrier with the
        // view-stops pass, recorded just before it (neither reads the other).
        let init_caches = |rec: &mut Recorder, profiler: &mut Profiler, light: u32, slots: u32, first: bool| {
            let stops = match (first, view_stops) {
                (true, Some(v)) => v.record(rec, profiler)?,
                _ => false,
            };
            let init_scope = profiler.begin(rec, "ipsvi_cache_init")?;
            rec.bind(init, init_set);
            let n = settings.cache_size.div_ceil(8);
            rec.push(init, &[light, slots]);
            rec.dispatch(n, (settings.cache_size * slots).div_ceil(8), 1);
            profiler.end(rec, init_scope)?;
            let name = match stops {
                true if self.study.omit_view_stops_barrier => return Ok(()),
                true => "cache_init_and_view_stops_write_to_first_line_read",
                false => "cache_init_write_to_first_line_read",
            };
            // Read-write: the lines write the caches, and add to the shape counters the pass adds to.
            rec.barrier(&Barrier::memory(name, Access::COMPUTE_WRITE, Access::COMPUTE_READ_WRITE));
            Ok::<(), VkError>(())
        };
        rec.clear_for_compute(
            &output.image,
            [bg.x, bg.y, bg.z, 1.0],
            "output_discard_to_clear",
            "output_clear_to_line_accumulate",
        );
        if let Some(m) = merged {
            // Each sweep adds its weighted colour to its own rows, from zero.
            rec.clear_for_compute(
                &m.accumulation,
                [0.0; 4],
                "accumulation_discard_to_clear",
                "accumulation_clear_to_line_accumulate",
            );
        }
        rec.discard_for_compute("cache_discard_to_init_write", &cache.images());
        // Claims carry a frame-wide block number: cleared once per frame.
        rec.barrier(&Barrier::memory("claim_keys_previous_frame_to_clear", Access::ANY, Access::CLEAR_WRITE));
        rec.fill_buffer(&cache.claim_keys, 0);
        self.shape.record_clear(rec);
        rec.barrier(&Barrier::memory(
            "claim_keys_clear_to_first_claim",
            Access::CLEAR_WRITE,
            Access::COMPUTE_READ_WRITE,
        ));
        if let Some(p) = &placeholder {
            rec.discard_for_compute("lmax_placeholder_to_shader_read", &[p]);
        }
        let frame_scope = profiler.begin(rec, "ipsvi")?;
        if let Some(e) = &exit_points {
            e.record(rec, profiler)?;
        }
        if let Some(m) = merged {
            line_sync.before_sweep(rec);
            init_caches(rec, profiler, 0, m.slots, true)?;
            let sweeps_scope = profiler.begin(rec, "ipsvi_sweeps_merged")?;
            record_lines(rec, profiler, &mut *line_sync, 0)?;
            profiler.end(rec, sweeps_scope)?;
            // The last step's writes, whatever the strategy put after it.
            line_sync.before_sweep(rec);
            rec.barrier(&Barrier::memory(
                "sweep_accumulation_to_sum_read",
                Access::COMPUTE_WRITE,
                Access::COMPUTE_READ_WRITE,
            ));
            let sum_scope = profiler.begin(rec, "ipsvi_sweep_sum")?;
            rec.bind(&m.sum, m.sum_set);
            rec.dispatch(output.width.div_ceil(8), output.height.div_ceil(8), 1);
            profiler.end(rec, sum_scope)?;
        } else {
            let mut next_sweep = 0usize;
            for (li, plan) in plans.iter().enumerate() {
                for sweep in &plan.sweeps {
                    line_sync.before_sweep(rec);
                    init_caches(rec, profiler, li as u32, 1, next_sweep == 0)?;
                    let sweep_scope = profiler.begin(rec, &format!("ipsvi_sweep_{}", sweep.zone.name()))?;
                    record_lines(rec, profiler, &mut *line_sync, next_sweep)?;
                    next_sweep += 1;
                    profiler.end(rec, sweep_scope)?;
                }
            }
        }
        line_sync.end_frame(rec);
        self.shape.record_readback(rec);
        profiler.end(rec, frame_scope)?;
        let keep_alive = line_sync.frame_resources();
        Ok(RecordedFrame::counted(rec, output.clone(), keep_alive))
    }
}
