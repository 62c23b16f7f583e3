//! `sweeplab bench ipsvi` as an experiment: error against GPU time over
//! IPSVI's parameters (line width, cache size, piecewise integration, early
//! termination, write rule), beside unshaded DVR and half-angle slicing, per
//! image size. Per size the DVR, the IPSVI configurations and the half-angle
//! slice spacings are measured in one [`Interleaved`] measurement, so each
//! `time_over_dvr` is a ratio of paired rounds; every row has its median GPU
//! time, with a 95 % interval from 6 rounds up. The Pareto front of (GPU time,
//! RMSE) is marked per size and charted.

pub mod breakdown;
mod experiment;
mod report;

pub use experiment::{BreakdownExperiment, IpsviExperiment};
use report::mark_pareto;
pub use report::IpsviReport;

use crate::bench::experiments::image_sizes::check_sizes;
use crate::bench::protocol::{Phase, Protocol};
use crate::bench::{
    ipsvi_frame, technique_frame, BenchRow, BenchTable, ExperimentError, Interleaved, OutFolder, Progress, RunInfo,
    Sample,
};
use crate::linear_image::LinearImage;
use crate::metrics::compare;
use crate::render::{GpuScene, RenderTechnique, VolumeTexels};
use crate::scene::settings_table::SettingsTable;
use crate::scene::{OpticalModel, Scene};
use crate::techniques::half_angle::HalfAngleSettings;
use crate::techniques::ipsvi::cache_plane::texel_pixels;
use crate::techniques::ipsvi::line_kernel::{self, LineKernel};
use crate::techniques::ipsvi::renderer::{plans, IpsviRenderer};
use crate::techniques::ipsvi::{
    CacheUpdate, EarlyTermination, IpsviSettings, ReadFronts, SyncStrategy, WritePass, WriteRule,
};
use crate::techniques::{render, Technique};
use crate::vk::{Context, Profiler};

/// Device-local bytes the IPSVI renderers of one interleaved group may hold
/// together (see [`IpsviPlan::group_bytes`]).
pub const DEFAULT_GROUP_BYTES: u64 = 1 << 30;

/// What `bench ipsvi` sweeps.
#[derive(Clone, Debug)]
pub struct IpsviPlan {
    /// Square image sizes.
    pub sizes: Vec<u32>,
    /// Lines per dispatch.
    pub line_widths: Vec<u32>,
    /// Illumination cache texels per side.
    pub cache_sizes: Vec<u32>,
    /// Only the scene's settings and one factor varied at a time (no full grid).
    pub one_at_a_time: bool,
    /// Half-angle slice spacings in voxels (none: no half-angle rows).
    pub half_angle_slices: Vec<f32>,
    /// The rounds every configuration of a size shares.
    pub interleaved: Interleaved,
    pub volume_texels: VolumeTexels,
    /// The IPSVI renderers measured side by side hold at most this many bytes
    /// (by their resource list); more configurations are measured in several
    /// groups, each with the DVR as its baseline. The full grid at 512x512
    /// (300 renderers, 60 of them with a 1024-texel cache) would hold about
    /// 5 GB at once.
    pub group_bytes: u64,
    /// The line kernels measured (`auto`: the device's): the whole grid with
    /// the first (the device's where listed), and every mode at every cache
    /// size with each other one that runs it.
    pub kernels: Vec<LineKernel>,
}

/// Every IPSVI configuration, checked as the scene file's `[ipsvi]` would be.
pub fn check_ipsvi(flags: &str, configurations: &[IpsviSettings]) -> Result<(), ExperimentError> {
    for c in configurations {
        c.validate().map_err(|e| ExperimentError::Invalid(format!("{flags}: {e}")))?;
    }
    Ok(())
}

/// The ways IPSVI feeds its cache, each measured at every point of the grid so
/// the plot shows which to pick at each budget: the view samples under each
/// write rule (the paper's data flow) and the light rays (a texel-parallel
/// advance). The scene's own mode comes first; light rays keep the scene's
/// write rule, which they do not use.
fn modes(base: &IpsviSettings) -> Vec<IpsviSettings> {
    let mut out = vec![base.clone()];
    let mut push = |s: IpsviSettings| {
        if !out.iter().any(|o| mode_name(o) == mode_name(&s)) {
            out.push(s)
        }
    };
    for write_rule in WriteRule::ALL {
        push(IpsviSettings { cache_update: CacheUpdate::ViewSamples, write_rule, ..base.clone() });
    }
    push(IpsviSettings { cache_update: CacheUpdate::LightRays, ..base.clone() });
    out
}

/// A mode as the plot's legend and the `mode` column name it.
fn mode_name(s: &IpsviSettings) -> String {
    let mode = match s.cache_update {
        CacheUpdate::ViewSamples => format!("view samples, {}", s.write_rule.name()),
        CacheUpdate::LightRays => "light rays".to_string(),
    };
    // The sample pass is named where `auto` would take the texel pass.
    let pass = if s.texel_pass_allowed() && !s.texel_pass() { ", sample pass" } else { "" };
    let fronts = match (s.piecewise, s.read_fronts) {
        (true, ReadFronts::PerTexel) => ", per-texel fronts",
        (true, ReadFronts::Blended) => ", blended fronts",
        _ => "",
    };
    let boxed = if s.fit_to_visible { ", visible box" } else { "" };
    let kernel = match s.line_kernel {
        LineKernel::Auto => String::new(),
        k => format!(", {}", k.name()),
    };
    format!("{mode}{pass}{fronts}{boxed}{kernel}")
}

impl IpsviPlan {
    /// The sizes and slice spacings in range; the error names the flag.
    pub fn check(&self) -> Result<(), ExperimentError> {
        check_sizes("--sizes", &self.sizes)?;
        for &step in &self.half_angle_slices {
            HalfAngleSettings { slice_step: Some(step), ..HalfAngleSettings::default() }
                .validate()
                .map_err(|e| ExperimentError::Invalid(format!("--half-angle-slices: {e}")))?;
        }
        Ok(())
    }

    /// Every IPSVI configuration of `base` (the scene's settings, its kernel
    /// resolved for the device: [`line_kernel::resolved`]), each checked as
    /// the scene file's `[ipsvi]` would be.
    pub fn configurations(&self, base: &IpsviSettings) -> Result<Vec<IpsviSettings>, ExperimentError> {
        let first = match self.kernels.first() {
            Some(&k) if !self.kernels.contains(&base.line_kernel) => IpsviSettings { line_kernel: k, ..base.clone() },
            _ => base.clone(),
        };
        let mut configs = self.grid(&first);
        // The other kernels: every mode at every cache size, where they run it.
        for &line_kernel in self.kernels.iter().filter(|&&k| k != first.line_kernel) {
            for mode in modes(&first) {
                for cache_size in std::iter::once(mode.cache_size).chain(self.cache_sizes.iter().copied()) {
                    let s = IpsviSettings { line_kernel, segments: 0, cache_size, ..mode.clone() };
                    let runs = line_kernel != LineKernel::Segmented || line_kernel::segmented_refusal(&s).is_none();
                    if runs && !configs.contains(&s) {
                        configs.push(s);
                    }
                }
            }
        }
        check_ipsvi("--line-widths/--cache-sizes/--kernels", &configs)?;
        Ok(configs)
    }

    fn grid(&self, base: &IpsviSettings) -> Vec<IpsviSettings> {
        let mut out = Vec::new();
        if self.one_at_a_time {
            let mut push = |s: IpsviSettings| {
                if !out.contains(&s) {
                    out.push(s)
                }
            };
            push(base.clone());
            // Every mode at every cache size: the cache's resolution moves the
            // error of each mode most (docs/ipsvi.md).
            for mode in modes(base) {
                push(mode.clone());
                // The box the cache is fitted to, the other way than the scene's.
                push(IpsviSettings { fit_to_visible: !mode.fit_to_visible, ..mode.clone() });
                // The write pass the other way, where the mode's writes allow the texel pass.
                if mode.texel_pass_allowed() {
                    let other = if mode.texel_pass() { WritePass::Sample } else { WritePass::Texel };
                    push(IpsviSettings { write_pass: other, ..mode.clone() });
                }
                // Per-texel fronts where the mode leaves them to `auto` (which
                // takes them only on texels finer than a pixel).
                if mode.piecewise && mode.read_fronts == ReadFronts::Auto {
                    push(IpsviSettings { read_fronts: ReadFronts::PerTexel, ..mode.clone() });
                }
                for &c in &self.cache_sizes {
                    push(IpsviSettings { cache_size: c, ..mode.clone() });
                }
            }
            for &lw in &self.line_widths {
                push(IpsviSettings { line_width: lw, ..base.clone() });
                push(IpsviSettings { line_width: lw, piecewise: false, ..base.clone() });
            }
            for ert in [EarlyTermination::Off, EarlyTermination::Plain, EarlyTermination::ExitPoints] {
                push(IpsviSettings { early_termination: ert, ..base.clone() });
            }
            return out;
        }
        for &line_width in &self.line_widths {
            for &cache_size in &self.cache_sizes {
                for piecewise in [true, false] {
                    for early_termination in
                        [EarlyTermination::Plain, EarlyTermination::Off, EarlyTermination::ExitPoints]
                    {
                        for mode in modes(base) {
                            out.push(IpsviSettings { line_width, cache_size, piecewise, early_termination, ..mode });
                        }
                    }
                }
            }
        }
        out
    }
}

/// What one frame of any configuration leaves to compare and count.
struct Frame {
    image: LinearImage,
    dispatches: u32,
    barriers: u32,
}

/// A configuration after its first, untimed frame (which compiled its shader
/// variants): its device-local peak as if it were alone on the device, and
/// what it measures with.
struct Prepared<R> {
    memory: u64,
    run: R,
}

/// Every size of `plan` on `scene` (model (ii) for IPSVI and DVR), the rows
/// saved in `out_folder` as they are measured; the reports and charts at the end.
pub fn run(
    ctx: &Context,
    scene: &Scene,
    plan: &IpsviPlan,
    run: RunInfo,
    out_folder: &OutFolder,
    profiler_capacity: u32,
) -> Result<IpsviReport, ExperimentError> {
    plan.check()?;
    let mut scene = scene.clone();
    scene.reference.model = OpticalModel::EmissiveScattering;
    // With several kernels, the one the device takes for the scene named, the others beside it.
    let subgroups = crate::vk::subgroups::SubgroupSupport::of(ctx);
    let scene_settings = scene.settings.get::<IpsviSettings>().into_owned();
    let base = match plan.kernels.as_slice() {
        [only] => IpsviSettings { line_kernel: *only, ..scene_settings },
        _ => line_kernel::resolved(&scene_settings, &ctx.info.device_type, &subgroups),
    };
    let configs = plan.configurations(&base)?;
    let groups = groups(&scene, &configs, plan);
    // Half-angle slicing runs beside IPSVI where the scene's light allows it;
    // where not, the rows are left out and the run says why.
    let half_angle_left_out =
        if plan.half_angle_slices.is_empty() { None } else { crate::techniques::half_angle::unavailable(&scene) };
    let half_angle = if half_angle_left_out.is_none() { plan.half_angle_slices.clone() } else { Vec::new() };
    let run = match &half_angle_left_out {
        Some(why) => run.input("half_angle", format!("left out: {why}")),
        None => run,
    };
    let gpu = GpuScene::upload_with(ctx, &scene, plan.volume_texels)?;
    let mut profiler = Profiler::new(ctx, profiler_capacity)?;
    let mut progress = Progress::weighted(step_weights(plan, &groups, half_angle.len()));
    let mut table = BenchTable::with_run(run_inputs(run, &plan.interleaved));
    let rounds = after_first_frames(&plan.interleaved);
    for &size in &plan.sizes {
        // Nothing of this size is alive yet: what each configuration's memory
        // counts besides its own resources (the scene's).
        let base_bytes = ctx.memory.device_local_bytes();
        progress.start_step(&format!("{size}x{size} ground truth (GPU, model ii)"));
        let reference = render(&gpu, Technique::Reference, size, size, &mut profiler)?;
        progress.finish_step();
        let mut row = size_row("reference", size);
        row.set("gpu_ms", reference.profile.gpu_ms_total).set("rmse", 0.0).set("max_abs", 0.0);
        row.set("dispatches", reference.dispatches).set("gpu_memory_bytes", reference.profile.gpu_memory_bytes);
        table.push(row);
        out_folder.save_rows("ipsvi", &table)?;

        // Half-angle slicing carries no emission along the light: its ground truth is model (i).
        let mut single = scene.clone();
        single.reference.model = OpticalModel::SingleScattering;
        let single_reference = if half_angle.is_empty() {
            None
        } else {
            progress.start_step(&format!("{size}x{size} ground truth (GPU, model i)"));
            let gpu = GpuScene::upload_with(ctx, &single, plan.volume_texels)?;
            let image = render(&gpu, Technique::Reference, size, size, &mut profiler)?.image;
            progress.finish_step();
            Some(image)
        };

        progress.start_step(&format!("{size}x{size} unshaded DVR, first frame"));
        let dvr = technique_frame(&gpu, Technique::Dvr, (size, size), &mut profiler)?.output;
        progress.finish_step();
        let dvr_bytes = dvr.profile.gpu_memory_bytes;
        let sliced: Vec<Scene> = half_angle
            .iter()
            .map(|&step| {
                let mut s = single.clone();
                s.settings.get_mut::<HalfAngleSettings>().slice_step = Some(step);
                s
            })
            .collect();
        let mut half_angle_scenes = Vec::new();
        for (&step, sliced) in half_angle.iter().zip(&sliced) {
            progress.start_step(&format!("{size}x{size} half-angle slices {step} voxel, first frame"));
            let before = ctx.memory.device_local_bytes();
            let ha = GpuScene::upload_with(ctx, sliced, plan.volume_texels)?;
            let out = technique_frame(&ha, Technique::HalfAngle, (size, size), &mut profiler)?.output;
            progress.finish_step();
            let memory = out.profile.gpu_memory_bytes - before.saturating_sub(base_bytes);
            half_angle_scenes.push(Prepared { memory, run: ha });
        }

        let mut half_angle_rows = Vec::new();
        for (g, group) in groups.iter().enumerate() {
            progress.start_step(&format!(
                "{size}x{size} IPSVI group {}: {} renderers, first frames",
                g + 1,
                group.len()
            ));
            let mut renderers = Vec::with_capacity(group.len());
            for &i in group {
                let before = ctx.memory.device_local_bytes();
                ctx.memory.reset_peak();
                let mut renderer = IpsviRenderer::new(&gpu, &configs[i], size, size)?;
                let first = ipsvi_frame(ctx, &mut renderer, &mut profiler, SyncStrategy::BarrierGlobal)?.output;
                let memory = first.profile.gpu_memory_bytes - before.saturating_sub(base_bytes);
                renderers.push(Prepared { memory, run: (renderer, first.frame.shape) });
            }
            progress.finish_step();
            // Configuration 0 is the DVR, then this group's IPSVI, then (in the first group) half-angle.
            let with_half_angle = if g == 0 { half_angle_scenes.len() } else { 0 };
            let label = format!("{size}x{size} DVR, {} IPSVI, {with_half_angle} half-angle", group.len());
            let mut timings =
                rounds.measure(&mut progress, &label, 1 + group.len() + with_half_angle, |c, _: Phase| {
                    let frame = if c == 0 {
                        technique_frame(&gpu, Technique::Dvr, (size, size), &mut profiler).map(from_output)?
                    } else if c <= group.len() {
                        let r = &mut renderers[c - 1].run.0;
                        ipsvi_frame(ctx, r, &mut profiler, SyncStrategy::BarrierGlobal).map(|s| Sample {
                            ms: s.ms,
                            output: Frame {
                                image: s.output.frame.image,
                                dispatches: s.output.frame.dispatches,
                                barriers: s.output.frame.barriers,
                            },
                        })?
                    } else {
                        let ha = &half_angle_scenes[c - 1 - group.len()].run;
                        technique_frame(ha, Technique::HalfAngle, (size, size), &mut profiler).map(from_output)?
                    };
                    Ok::<_, ExperimentError>(frame)
                })?;
            let half_angle_timings = timings.split_off(1 + group.len());
            let ipsvi_timings = timings.split_off(1);
            let dvr_group = timings.pop().expect("the DVR is configuration 0");
            if g == 0 {
                let stats = compare(&dvr_group.last.image, &reference.image)?;
                let mut row = size_row("dvr", size);
                row.set_timing("gpu_ms", &dvr_group);
                set_errors(&mut row, &stats).set("dispatches", dvr.dispatches).set("gpu_memory_bytes", dvr_bytes);
                table.push(row);
            }
            // The scene's own settings, where this group measured them: every
            // configuration's time against them, paired round by round.
            let own = group.iter().position(|&i| configs[i] == base).map(|k| &ipsvi_timings[k]);
            for ((&i, prepared), t) in group.iter().zip(&renderers).zip(&ipsvi_timings) {
                let s = &configs[i];
                let lines: u32 = plans(&gpu, s, size, size).iter().map(|p| p.lines()).sum();
                let stats = compare(&t.last.image, &reference.image)?;
                let gpu_ms = t.median();
                let mut row = size_row("ipsvi", size);
                // cache_size = 0 resolved once for this size (the cache as it ran), the setting beside it.
                let sized = s.sized_for(&scene, size, size);
                row.set("line_width", s.line_width).set("cache_size", sized.cache_size);
                row.set("cache_sizing", if s.cache_size == 0 { "auto" } else { "set" });
                row.set("piecewise", s.piecewise).set("early_termination", s.early_termination.name());
                row.set("mode", mode_name(s)).set("cache_update", s.cache_update.name());
                row.set("fit_to_visible", s.fit_to_visible);
                row.set("line_kernel", prepared.run.0.kernel().label());
                if let Some(shape) = &prepared.run.1 {
                    set_shape(&mut row, shape);
                }
                // Light rays have no view-sample writes.
                if let Some(pass) = s.write_pass_run() {
                    row.set("write_rule", s.write_rule.name()).set("write_pass", pass.name());
                }
                if s.piecewise {
                    let per_texel = sized.per_texel_fronts(&scene, size, size);
                    row.set("read_fronts", if per_texel { "per-texel" } else { "blended" });
                }
                // Which side of the view samples' optimum (about a pixel) the cache is on.
                if let Some(px) = texel_pixels(&scene, &sized, size, size) {
                    row.set("cache_texel_px", px as f64);
                }
                row.set_timing("gpu_ms", t);
                set_errors(&mut row, &stats);
                row.set("lines", lines).set("dispatches", t.last.dispatches).set("barriers", t.last.barriers);
                row.set("gpu_memory_bytes", prepared.memory);
                row.set("extra_memory_bytes_over_dvr", prepared.memory as i64 - dvr_bytes as i64);
                // Against this group's DVR, which saw the same rounds.
                row.set("time_over_dvr", gpu_ms / dvr_group.median());
                row.set_estimate("time_over_dvr", t.paired_ratio(&dvr_group));
                row.set("ms_per_dispatch", gpu_ms / t.last.dispatches.max(1) as f64);
                if let Some(own) = own {
                    row.set_estimate("time_over_scene_settings", t.paired_ratio(own));
                }
                table.push(row);
            }
            out_folder.save_rows("ipsvi", &table)?;
            // Without half-angle runs (`--half-angle-slices` with no value) there is no model (i) truth.
            if let (0, Some(truth)) = (g, single_reference.as_ref()) {
                for ((&step, prepared), t) in half_angle.iter().zip(&half_angle_scenes).zip(&half_angle_timings) {
                    let stats = compare(&t.last.image, truth)?;
                    let mut row = size_row("half-angle", size);
                    row.set("slice_step_voxels", step);
                    row.set_timing("gpu_ms", t);
                    set_errors(&mut row, &stats).set("dispatches", t.last.dispatches);
                    row.set("gpu_memory_bytes", prepared.memory).set("reference_model", "single-scattering");
                    half_angle_rows.push(row);
                }
            }
        }
        // Measured with the first group, listed after every IPSVI row of the size.
        table.rows.extend(half_angle_rows);
        out_folder.save_rows("ipsvi", &table)?;
    }
    progress.finish();
    drop(gpu);
    mark_pareto(&mut table, &plan.sizes);
    let report = IpsviReport { table, half_angle_left_out };
    report.write(out_folder.path(), plan, &base)?;
    Ok(report)
}

fn from_output(s: Sample<crate::techniques::RenderOutput>) -> Sample<Frame> {
    let o = s.output;
    Sample { ms: s.ms, output: Frame { image: o.image, dispatches: o.dispatches, barriers: o.barriers } }
}

fn size_row(technique: &str, size: u32) -> BenchRow {
    BenchRow::new().with("technique", technique).with("width", size).with("height", size)
}

/// A frame's line shape (device-independent): its shading line dispatches,
/// the invocations per line dispatch and the longest serial chain of an
/// invocation, medians and maxima, the median of each role's and the lines
/// each role is the longest in; the segmented kernel's view-stops pass (once
/// a frame) where it ran.
pub fn set_shape(row: &mut BenchRow, shape: &crate::render::LineShape) {
    row.set("line_dispatches", shape.line_dispatches);
    row.set("invocations_per_dispatch", shape.invocations_median);
    row.set("invocations_per_dispatch_max", shape.invocations_max);
    row.set("longest_chain", shape.chain_median).set("longest_chain_max", shape.chain_max);
    let roles = &shape.chain_median_by_role;
    row.set("longest_chain_pixels", roles.pixels);
    row.set("longest_chain_texels", roles.texels).set("longest_chain_claims", roles.claims);
    let bound = &shape.lines_bound_by;
    row.set("lines_bound_by_pixels", bound.pixels);
    row.set("lines_bound_by_texels", bound.texels).set("lines_bound_by_claims", bound.claims);
    if let Some(pass) = shape.stops_pass {
        row.set("view_stops_invocations", pass.invocations).set("view_stops_chain", pass.chain);
    }
}

fn set_errors<'r>(row: &'r mut BenchRow, stats: &crate::metrics::ErrorStats) -> &'r mut BenchRow {
    row.set("rmse", stats.rmse).set("max_abs", stats.max_abs).set("psnr", stats.psnr)
}

/// The rounds after each configuration's first frame, run alone: it compiled
/// the configuration's shader variants and measured its memory by itself, so
/// it stands for the first warm-up round.
pub fn after_first_frames(interleaved: &Interleaved) -> Interleaved {
    let protocol = interleaved.protocol;
    Interleaved {
        protocol: Protocol { warm_up_rounds: protocol.warm_up_rounds.saturating_sub(1), ..protocol },
        ..*interleaved
    }
}

/// The seed and the rounds with the run's other inputs.
pub fn run_inputs(run: RunInfo, interleaved: &Interleaved) -> RunInfo {
    let p = interleaved.protocol;
    let rounds = if p.min_rounds == p.max_rounds {
        p.min_rounds.to_string()
    } else {
        format!(
            "{}..={} (until every 95 % interval is within {} of its median)",
            p.min_rounds, p.max_rounds, interleaved.target_ci
        )
    };
    run.input("seed", p.seed).input("rounds", rounds).input("warm_up_rounds", p.warm_up_rounds)
}

/// The IPSVI configurations in groups whose renderers' resources add up to at
/// most `plan.group_bytes` (a configuration larger than that alone), in order.
fn groups(scene: &Scene, configs: &[IpsviSettings], plan: &IpsviPlan) -> Vec<Vec<usize>> {
    let largest = plan.sizes.iter().copied().max().unwrap_or(1);
    let mut scene = scene.clone();
    let mut out: Vec<Vec<usize>> = vec![Vec::new()];
    let mut held = 0u64;
    for (i, s) in configs.iter().enumerate() {
        *scene.settings.get_mut::<IpsviSettings>() = s.clone();
        let bytes: u64 =
            crate::techniques::ipsvi::Ipsvi.resources(&scene, largest, largest).iter().map(|r| r.bytes).sum();
        let current = out.last_mut().expect("never empty");
        if !current.is_empty() && held + bytes > plan.group_bytes {
            out.push(vec![i]);
            held = bytes;
        } else {
            current.push(i);
            held += bytes;
        }
    }
    out
}

/// The relative size of each progress step, in the order `run` takes them:
/// pixels x frames x a rough cost per pixel of the technique (the ground truth
/// and IPSVI about one unit, half-angle half, DVR a twentieth), so the time
/// left weighs a 512x512 step four times a 256x256 one.
fn step_weights(plan: &IpsviPlan, groups: &[Vec<usize>], half_angle: usize) -> Vec<f64> {
    let rounds = f64::from(plan.interleaved.most_runs().saturating_sub(1).max(1));
    let mut weights = Vec::new();
    for &size in &plan.sizes {
        let pixels = f64::from(size) * f64::from(size);
        weights.push(pixels);
        if half_angle > 0 {
            weights.push(pixels);
        }
        weights.push(pixels * 0.05);
        weights.extend(std::iter::repeat_n(pixels * 0.5, half_angle));
        for (g, group) in groups.iter().enumerate() {
            let n = group.len() as f64;
            let ha = if g == 0 { half_angle as f64 * 0.5 } else { 0.0 };
            weights.push(pixels * n);
            weights.push(pixels * rounds * (n + 0.05 + ha));
        }
    }
    weights
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plan() -> IpsviPlan {
        IpsviPlan {
            sizes: vec![16],
            line_widths: vec![1, 4],
            cache_sizes: vec![64],
            one_at_a_time: false,
            half_angle_slices: vec![1.0],
            interleaved: Interleaved::fixed(1, 0).unwrap(),
            volume_texels: VolumeTexels::Native,
            group_bytes: DEFAULT_GROUP_BYTES,
            kernels: vec![LineKernel::Auto],
        }
    }

    #[test]
    fn the_other_kernel_measures_every_mode_at_every_cache_size_where_it_runs() {
        // A scene that sets its cache (256), listed again below: measured once.
        let base = IpsviSettings { line_kernel: LineKernel::Serial, cache_size: 256, ..IpsviSettings::default() };
        let both = IpsviPlan {
            one_at_a_time: true,
            cache_sizes: vec![64, 256],
            kernels: vec![LineKernel::Serial, LineKernel::Segmented],
            ..plan()
        };
        let one = both.configurations(&base).unwrap();
        let serial = IpsviPlan { kernels: vec![LineKernel::Serial], ..both.clone() }.configurations(&base).unwrap();
        assert_eq!(one[..serial.len()], serial[..], "the device's kernel's grid first");
        let segmented: Vec<String> = one[serial.len()..].iter().map(mode_name).collect();
        for mode in ["view samples, every-sample", "view samples, non-empty", "light rays"] {
            let name = format!("{mode}, segmented");
            // The scene's cache (256) and 64.
            assert_eq!(segmented.iter().filter(|n| **n == name).count(), 2, "{name}: {segmented:?}");
        }
        assert!(!segmented.iter().any(|n| n.contains("sample pass")), "the segmented kernel runs no sample pass");
        assert_eq!(mode_name(&base), "view samples, every-sample, serial");
    }

    #[test]
    fn the_grid_crosses_every_list_and_one_at_a_time_varies_one_factor() {
        let base = IpsviSettings { cache_update: CacheUpdate::ViewSamples, ..IpsviSettings::default() };
        // 2 line widths x 1 cache x piecewise on/off x 3 early terminations x 3 modes.
        let grid = plan().configurations(&base).unwrap();
        assert_eq!(grid.len(), 36);
        let names: Vec<String> = modes(&base).iter().map(mode_name).collect();
        assert_eq!(names, ["view samples, every-sample", "view samples, non-empty", "light rays"]);
        for name in &names {
            assert_eq!(grid.iter().filter(|s| mode_name(s) == *name).count(), 12, "{name}");
        }
        let rays = IpsviSettings { cache_update: CacheUpdate::LightRays, ..base.clone() };
        assert_eq!(mode_name(&modes(&rays)[0]), "light rays", "the scene's own mode first");
        assert_eq!(plan().configurations(&rays).unwrap().len(), 36);
        let sizes = IpsviPlan { one_at_a_time: true, cache_sizes: vec![64, 256], ..plan() };
        let one = sizes.configurations(&base).unwrap();
        assert!(one.contains(&base) && one.len() < 36, "{one:?}");
        assert!(one.iter().enumerate().all(|(i, s)| !one[..i].contains(s)), "no configuration twice");
        for name in &names {
            for c in [64, 256] {
                assert!(one.iter().any(|s| mode_name(s) == *name && s.cache_size == c), "{name} at cache {c}");
            }
            let boxed = format!("{name}, visible box");
            assert!(one.iter().any(|s| mode_name(s) == boxed && s.fit_to_visible), "{boxed}");
        }
        // Each view-sample mode with the other write pass; light rays have none.
        for rule in ["non-empty", "every-sample"] {
            let sample = format!("view samples, {rule}, sample pass");
            assert!(one.iter().any(|s| mode_name(s) == sample && !s.texel_pass()), "{sample}");
            let texel = format!("view samples, {rule}");
            assert!(one.iter().any(|s| mode_name(s) == texel && s.texel_pass()), "{texel}");
        }
        assert!(!one.iter().any(|s| s.cache_update == CacheUpdate::LightRays && s.write_pass != base.write_pass));
        // Each mode with per-texel fronts beside `auto`.
        for name in &names {
            let fronts = format!("{name}, per-texel fronts");
            assert!(one.iter().any(|s| mode_name(s) == fronts && s.read_fronts == ReadFronts::PerTexel), "{fronts}");
        }
        let sample_writes = IpsviSettings { write_value: crate::techniques::ipsvi::WriteValue::Sample, ..base.clone() };
        let one = sizes.configurations(&sample_writes).unwrap();
        assert!(!one.iter().any(|s| s.texel_pass()), "sample writes have no texel pass");
        assert!(!one.iter().any(|s| mode_name(s).contains("pass")), "nor a pass to name");
    }

    #[test]
    fn bad_lists_name_their_flag_before_any_gpu_work() {
        let e = |r: Result<(), ExperimentError>| r.unwrap_err().to_string();
        assert!(e(IpsviPlan { sizes: vec![0], ..plan() }.check()).starts_with("--sizes: a 0x0 image is empty"));
        assert!(e(IpsviPlan { sizes: vec![], ..plan() }.check()).starts_with("--sizes"));
        assert!(e(IpsviPlan { sizes: vec![64, 20000], ..plan() }.check()).contains("20000"));
        let slices = e(IpsviPlan { half_angle_slices: vec![0.5, 100.0], ..plan() }.check());
        assert!(slices.starts_with("--half-angle-slices") && slices.contains("slice_step = 100"), "{slices}");
        let widths = IpsviPlan { line_widths: vec![1, 0], ..plan() }.configurations(&IpsviSettings::default());
        let widths = widths.unwrap_err().to_string();
        assert!(widths.starts_with("--line-widths") && widths.contains("line_width = 0"), "{widths}");
        assert!(plan().check().is_ok());
    }

    #[test]
    fn groups_hold_what_the_budget_allows_and_at_least_one_configuration() {
        let scene = crate::techniques::scene_from_toml_str(
            "[volume]\nsynthetic = \"cornell-box\"\nsize = 8\n[[lights]]\ntype = \"directional\"\ndirection = [0.0, -1.0, 0.0]\n",
            std::path::Path::new(""),
            "tiny",
            &[],
        )
        .unwrap();
        let configs = plan().configurations(&IpsviSettings::default()).unwrap();
        assert_eq!(groups(&scene, &configs, &plan()), vec![(0..configs.len()).collect::<Vec<_>>()]);
        let alone = groups(&scene, &configs, &IpsviPlan { group_bytes: 1, ..plan() });
        assert_eq!(alone, (0..configs.len()).map(|i| vec![i]).collect::<Vec<_>>());
    }

    #[test]
    fn the_run_names_its_seed_and_rounds() {
        let fixed = run_inputs(RunInfo::host(), &Interleaved::fixed(6, 42).unwrap());
        assert!(fixed.inputs.contains(&("seed".into(), "42".into())), "{:?}", fixed.inputs);
        assert!(fixed.inputs.contains(&("rounds".into(), "6".into())), "{:?}", fixed.inputs);
        let adaptive = run_inputs(RunInfo::host(), &Interleaved::adaptive(1, 6, 20, 0.05, 7).unwrap());
        assert!(adaptive.inputs.iter().any(|(k, v)| k == "rounds" && v.starts_with("6..=20")), "{:?}", adaptive.inputs);
        assert_eq!(after_first_frames(&Interleaved::fixed(6, 1).unwrap()).protocol.warm_up_rounds, 0);
    }
}
