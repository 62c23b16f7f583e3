//! `sweeplab bench ipsvi --breakdown` as an experiment: where the time of one
//! IPSVI frame goes, in both cache-update modes (view samples under each write
//! rule). Each step adds one part of the frame to the one before; its cost is
//! its GPU time minus the previous step's, a paired difference over shared
//! rounds with its 95 % interval, published only where the interval lies
//! above 0. Beside it, the whole frame at each line width with its speed-up
//! over line width 1 (a paired ratio).
//!
//! Per image size, the DVR, every step of every mode and every line width
//! run in one [`Interleaved`] measurement (about forty renderers at the
//! scene's cache size, a few hundred MB at 512x512).

use super::super::image_sizes::check_sizes;
use super::{after_first_frames, check_ipsvi, run_inputs};
use crate::bench::estimate::Estimate;
use crate::bench::protocol::Phase;
use crate::bench::{
    ipsvi_frame, plot_stacked_bars, technique_frame, BenchError, BenchRow, BenchTable, Chart, ExperimentError,
    Interleaved, OutFolder, Progress, RunInfo, StackedBar, Timings,
};
use crate::render::{GpuScene, VolumeTexels};
use crate::scene::Scene;
use crate::techniques::ipsvi::line_kernel::{self, LineKernel};
use crate::techniques::ipsvi::renderer::{plans, IpsviRenderer};
use crate::techniques::ipsvi::{
    BreakdownStep, CacheUpdate, IpsviSettings, IpsviStudy, SyncStrategy, WritePass, WriteRule,
};
use crate::techniques::Technique;
use crate::vk::{Context, Profiler};
use std::path::Path;

/// (step label, breakdown step, synchronization) after the single-dispatch DVR.
/// e1-e5 split the write path (f minus e) of view samples; light rays, whose
/// writes are all in their texel advance, skip them (f is then e's next step).
pub const STEPS: [(&str, BreakdownStep, SyncStrategy); 10] = [
    ("b: lines, no barriers", BreakdownStep::Lines, SyncStrategy::Racy),
    ("c: + barriers", BreakdownStep::Lines, SyncStrategy::BarrierGlobal),
    ("d: + cache reads", BreakdownStep::CacheReads, SyncStrategy::BarrierGlobal),
    ("e: + piecewise integration", BreakdownStep::Piecewise, SyncStrategy::BarrierGlobal),
    ("e1: + history carry", BreakdownStep::Carry, SyncStrategy::BarrierGlobal),
    ("e2: + the two stores (racy, as read)", BreakdownStep::Stores, SyncStrategy::BarrierGlobal),
    ("e3: + claim pass", BreakdownStep::ClaimPass, SyncStrategy::BarrierGlobal),
    ("e4: + claim check", BreakdownStep::ClaimCheck, SyncStrategy::BarrierGlobal),
    ("e5: + own segment", BreakdownStep::OwnSegment, SyncStrategy::BarrierGlobal),
    ("f: + cache writes = IPSVI", BreakdownStep::Full, SyncStrategy::BarrierGlobal),
];

const DVR_STEP: &str = "a: DVR, one dispatch";

/// What `bench ipsvi --breakdown` measures.
#[derive(Clone, Debug)]
pub struct BreakdownPlan {
    /// Square image sizes.
    pub sizes: Vec<u32>,
    /// Line widths the whole frame is timed at.
    pub line_widths: Vec<u32>,
    /// The rounds every configuration of a size shares.
    pub interleaved: Interleaved,
    pub volume_texels: VolumeTexels,
    /// The line kernels every mode runs with, where it can (the segmented
    /// kernel does not run the sample write pass).
    pub kernels: Vec<LineKernel>,
}

/// Whether a configuration runs a step (see [`STEPS`]).
fn runs_step(s: &IpsviSettings, step: BreakdownStep) -> bool {
    s.cache_update == CacheUpdate::ViewSamples
        || matches!(
            step,
            BreakdownStep::Lines | BreakdownStep::CacheReads | BreakdownStep::Piecewise | BreakdownStep::Full
        )
}

/// A bar label's name for a configuration.
fn short_mode(s: &IpsviSettings) -> String {
    let mode = match (s.cache_update, s.write_rule, s.write_pass_run()) {
        (CacheUpdate::ViewSamples, WriteRule::NonEmpty, Some(WritePass::Sample)) => "view, sample pass",
        (CacheUpdate::ViewSamples, WriteRule::NonEmpty, _) => "view",
        (CacheUpdate::ViewSamples, WriteRule::EverySample, Some(WritePass::Sample)) => "view every, sample pass",
        (CacheUpdate::ViewSamples, WriteRule::EverySample, _) => "view every",
        (CacheUpdate::LightRays, ..) => "rays",
    };
    match s.line_kernel {
        LineKernel::Segmented => format!("{mode}, segmented"),
        _ => mode.to_string(),
    }
}

impl BreakdownPlan {
    /// The sizes in range and every configuration (the scene's settings in
    /// each mode, and at each line width) valid; the error names the flag.
    pub fn check(&self, base: &IpsviSettings) -> Result<(), ExperimentError> {
        check_sizes("--sizes", &self.sizes)?;
        check_ipsvi("the scene's [ipsvi] settings", &configurations(base, &self.kernels))?;
        let widths: Vec<IpsviSettings> =
            self.line_widths.iter().map(|&line_width| IpsviSettings { line_width, ..base.clone() }).collect();
        check_ipsvi("--line-widths", &widths)
    }
}

/// The modes of `base`: view samples with both write rules, each with both
/// write passes where `base`'s writes allow the texel pass, then light rays;
/// all with each of `kernels` that runs them (the segmented kernel runs no
/// sample write pass).
pub fn configurations(base: &IpsviSettings, kernels: &[LineKernel]) -> Vec<IpsviSettings> {
    kernels
        .iter()
        .flat_map(|&line_kernel| {
            let view = move |write_rule, write_pass| IpsviSettings {
                cache_update: CacheUpdate::ViewSamples,
                write_rule,
                write_pass,
                line_kernel,
                segments: 0,
                ..base.clone()
            };
            let rays = IpsviSettings { cache_update: CacheUpdate::LightRays, ..view(base.write_rule, base.write_pass) };
            WriteRule::ALL
                .iter()
                .flat_map(move |&rule| WritePass::RUN.map(|pass| view(rule, pass)))
                .filter(|s| s.write_pass == WritePass::Sample || s.texel_pass_allowed())
                .chain(std::iter::once(rays))
                .filter(|s| s.line_kernel != LineKernel::Segmented || line_kernel::segmented_refusal(s).is_none())
        })
        .collect()
}

/// A row's `write_rule` and `write_pass`, for view samples only (light rays
/// have neither), and the line kernel as it ran (`serial`, `segmented x8`:
/// `auto` resolved for the device).
fn set_view_sample_writes(row: &mut BenchRow, s: &IpsviSettings, kernel: &str) {
    if let Some(pass) = s.write_pass_run() {
        row.set("write_rule", s.write_rule.name()).set("write_pass", pass.name());
    }
    row.set("line_kernel", kernel).set("cache_size", s.cache_size);
}

/// The steps of one mode, in the order they stack: the DVR, then [`STEPS`].
fn steps_of(s: &IpsviSettings) -> impl Iterator<Item = (&'static str, BreakdownStep, SyncStrategy)> + '_ {
    STEPS.into_iter().filter(|(_, step, _)| runs_step(s, *step))
}

/// What a run measured: the steps, and the whole frame per line width.
pub struct BreakdownReport {
    pub table: BenchTable,
    pub widths_table: BenchTable,
    pub bars: Vec<StackedBar>,
}

/// One IPSVI renderer of the measurement, by mode (index into
/// [`configurations`]), the step's label (or the line width) and its sync.
struct Run<'a> {
    mode: usize,
    label: &'static str,
    line_width: Option<u32>,
    sync: SyncStrategy,
    renderer: IpsviRenderer<'a>,
}

/// The frame's counts a row needs.
struct Counts {
    dispatches: u32,
    barriers: u32,
    shape: Option<crate::render::LineShape>,
}

/// Every size of `plan` on `scene`, rows saved in `out_folder` per size; the
/// reports and the stacked bars at the end.
pub fn run(
    ctx: &Context,
    scene: &Scene,
    plan: &BreakdownPlan,
    run: RunInfo,
    out_folder: &OutFolder,
    profiler_capacity: u32,
) -> Result<BreakdownReport, ExperimentError> {
    let base = scene.settings.get::<IpsviSettings>().into_owned();
    plan.check(&base)?;
    let configs = configurations(&base, &plan.kernels);
    let gpu = GpuScene::upload_with(ctx, scene, plan.volume_texels)?;
    let mut profiler = Profiler::new(ctx, profiler_capacity)?;
    let per_size = configs.iter().map(|s| steps_of(s).count() + plan.line_widths.len()).sum::<usize>();
    let rounds = f64::from(plan.interleaved.most_runs().saturating_sub(1).max(1));
    // Each size: first frames, then the rounds; DVR a twentieth of an IPSVI
    // frame per pixel, so a 512x512 size counts as four 256x256 ones.
    let weights = plan
        .sizes
        .iter()
        .flat_map(|&size| {
            let units = f64::from(size) * f64::from(size) * (per_size as f64 + 0.05);
            [units, units * rounds]
        })
        .collect();
    let mut progress = Progress::weighted(weights);
    let run = run_inputs(run, &plan.interleaved);
    let mut report = BreakdownReport {
        table: BenchTable::with_run(run.clone()),
        widths_table: BenchTable::with_run(run),
        bars: Vec::new(),
    };
    let rounds = after_first_frames(&plan.interleaved);
    for &size in &plan.sizes {
        progress.start_step(&format!("{size}x{size} DVR and {per_size} IPSVI renderers, first frames"));
        let dvr_first = technique_frame(&gpu, Technique::Dvr, (size, size), &mut profiler)?.output;
        let mut runs = Vec::with_capacity(per_size);
        for (mode, s) in configs.iter().enumerate() {
            let steps = steps_of(s).map(|(label, breakdown_step, sync)| {
                (label, None, s.clone(), IpsviStudy { breakdown_step, ..IpsviStudy::default() }, sync)
            });
            let widths = plan.line_widths.iter().map(|&lw| {
                let settings = IpsviSettings { line_width: lw, ..s.clone() };
                ("", Some(lw), settings, IpsviStudy::default(), SyncStrategy::BarrierGlobal)
            });
            for (label, line_width, settings, study, sync) in steps.chain(widths).collect::<Vec<_>>() {
                let mut renderer = IpsviRenderer::build(&gpu, &settings, &study, size, size, None)?;
                ipsvi_frame(ctx, &mut renderer, &mut profiler, sync)?;
                runs.push(Run { mode, label, line_width, sync, renderer });
            }
        }
        progress.finish_step();
        let label = format!("{size}x{size} DVR and every step and line width");
        let mut timings = rounds.measure(&mut progress, &label, 1 + runs.len(), |c, _: Phase| {
            Ok::<_, ExperimentError>(if c == 0 {
                let s = technique_frame(&gpu, Technique::Dvr, (size, size), &mut profiler)?;
                crate::bench::Sample {
                    ms: s.ms,
                    output: Counts { dispatches: s.output.dispatches, barriers: s.output.barriers, shape: None },
                }
            } else {
                let r = &mut runs[c - 1];
                let s = ipsvi_frame(ctx, &mut r.renderer, &mut profiler, r.sync)?;
                let f = &s.output.frame;
                let output = Counts { dispatches: f.dispatches, barriers: f.barriers, shape: f.shape.clone() };
                crate::bench::Sample { ms: s.ms, output }
            })
        })?;
        let measured = timings.split_off(1);
        let dvr = timings.pop().expect("the DVR is configuration 0");
        debug_assert_eq!(dvr.last.dispatches, dvr_first.dispatches);
        for (mode, s) in configs.iter().enumerate() {
            let of_mode = || runs.iter().zip(&measured).filter(move |(r, _)| r.mode == mode);
            let steps: Vec<(&str, &Timings<Counts>)> = std::iter::once((DVR_STEP, &dvr))
                .chain(of_mode().filter(|(r, _)| r.line_width.is_none()).map(|(r, t)| (r.label, t)))
                .collect();
            let lines: u32 = plans(&gpu, s, size, size).iter().map(|p| p.lines()).sum();
            // The rows name the cache as it ran (cache_size = 0 resolved for the size).
            let s = &s.sized_for(scene, size, size);
            let kernel = of_mode().next().map(|(r, _)| r.renderer.kernel().label()).unwrap_or_default();
            report.step_rows(size, s, &kernel, lines, &steps);
            let widths: Vec<(u32, &Timings<Counts>)> =
                of_mode().filter_map(|(r, t)| r.line_width.map(|lw| (lw, t))).collect();
            report.width_rows(size, s, &kernel, &widths);
        }
        out_folder.save_rows("ipsvi_breakdown", &report.table)?;
        out_folder.save_rows("ipsvi_line_widths", &report.widths_table)?;
    }
    progress.finish();
    drop(gpu);
    report.write(out_folder.path())?;
    Ok(report)
}

/// A step's cost over the one below it: the paired difference where the
/// rounds give an interval, else the difference of medians; drawn as 0 (and
/// no `step_ms` written) unless it is a cost.
fn step_cost(this: &Timings<Counts>, previous: Option<&Timings<Counts>>) -> (Option<Estimate>, Option<f64>) {
    let estimate = match previous {
        Some(p) => this.paired_difference(p),
        None => this.estimate(),
    };
    let cost = match &estimate {
        Some(e) => (e.verdict() == crate::bench::Verdict::Cost).then_some(e.value),
        None => Some(this.median() - previous.map_or(0.0, Timings::median)).filter(|d| *d > 0.0),
    };
    (estimate, cost)
}

impl BreakdownReport {
    /// The rows and the bar of one mode's steps (the DVR first).
    fn step_rows(
        &mut self,
        size: u32,
        s: &IpsviSettings,
        kernel: &str,
        lines: u32,
        steps: &[(&str, &Timings<Counts>)],
    ) {
        let total = steps.last().map_or(f64::NAN, |(_, t)| t.median());
        let mut bar = StackedBar { label: String::new(), segments: Vec::new() };
        let (mut as_zero, mut below) = (Vec::new(), Vec::new());
        let intervals = steps.iter().all(|(_, t)| t.estimate().is_some());
        for (k, (label, t)) in steps.iter().enumerate() {
            let (estimate, cost) = step_cost(t, k.checked_sub(1).map(|p| steps[p].1));
            let mut row = BenchRow::new();
            row.set("width", size).set("height", size).set("cache_update", s.cache_update.name()).set("step", *label);
            set_view_sample_writes(&mut row, s, kernel);
            row.set_timing("gpu_ms", t);
            match estimate {
                Some(_) => {
                    row.set_cost("step_ms", estimate);
                }
                None => {
                    row.set(
                        "step_ms_verdict",
                        if cost.is_some() { "median only" } else { "not above the previous step" },
                    );
                    if let Some(c) = cost {
                        row.set("step_ms", c);
                    }
                }
            }
            row.set("step_share", cost.unwrap_or(0.0) / total);
            let short = label.split(':').next().unwrap_or(label).to_string();
            if let Some(c) = cost {
                row.set("step_us_per_line", c * 1000.0 / lines.max(1) as f64);
            } else if estimate.is_some_and(|e| e.verdict() == crate::bench::Verdict::BelowBaseline) {
                below.push(short);
            } else {
                as_zero.push(short);
            }
            row.set("lines", lines).set("dispatches", t.last.dispatches).set("barriers", t.last.barriers);
            if let Some(shape) = &t.last.shape {
                super::set_shape(&mut row, shape);
            }
            self.table.push(row);
            bar.segments.push((label.to_string(), cost.unwrap_or(0.0)));
        }
        bar.label = format!("{size} {}", short_mode(s));
        if !as_zero.is_empty() {
            let why = if intervals { "within noise" } else { "not above the step below" };
            bar.label += &format!(" ({} {why}: 0)", as_zero.join(", "));
        }
        // A step faster than the one below it means the steps change each
        // other's work (e.g. stores shortening later marches): the bar's
        // segments then add up to more than the frame, which the label says.
        if !below.is_empty() {
            bar.label += &format!(" ({} below the step before: 0; frame {total:.0} ms)", below.join(", "));
        }
        self.bars.push(bar);
    }

    /// The whole frame at each line width, with its speed-up over line width 1.
    fn width_rows(&mut self, size: u32, s: &IpsviSettings, kernel: &str, widths: &[(u32, &Timings<Counts>)]) {
        let lw1 = widths.iter().find(|w| w.0 == 1).map(|w| w.1);
        for &(line_width, t) in widths {
            let mut row = BenchRow::new();
            row.set("width", size).set("height", size).set("cache_update", s.cache_update.name());
            row.set("line_width", line_width);
            set_view_sample_writes(&mut row, s, kernel);
            row.set_timing("gpu_ms", t).set("dispatches", t.last.dispatches);
            if let Some(shape) = &t.last.shape {
                super::set_shape(&mut row, shape);
            }
            if let Some(lw1) = lw1 {
                row.set("speedup_over_lw1", lw1.median() / t.median());
                row.set_estimate("speedup_over_lw1", lw1.paired_ratio(t));
            }
            self.widths_table.push(row);
        }
    }

    /// ipsvi_breakdown.{csv,json,md,png,svg} and ipsvi_line_widths.{csv,json,md} in `out`.
    pub fn write(&self, out: &Path) -> Result<(), ExperimentError> {
        for (table, stem) in [(&self.table, "ipsvi_breakdown"), (&self.widths_table, "ipsvi_line_widths")] {
            table.write_csv(out.join(format!("{stem}.csv")))?;
            table.write_json(out.join(format!("{stem}.json")))?;
            let md = out.join(format!("{stem}.md"));
            std::fs::write(&md, table.to_markdown_report()).map_err(|source| BenchError::Write { path: md, source })?;
        }
        let chart =
            Chart::new("One IPSVI frame, step by step", "bars: size, view samples or light rays", "GPU time (ms)")
                .size(960, 600)
                .run_caption(self.table.run.as_ref());
        plot_stacked_bars(out.join("ipsvi_breakdown.png"), &chart, &self.bars)?;
        Ok(())
    }

    /// What the terminal shows: per size and mode the whole frame against DVR
    /// and its largest step; every step is in the files.
    pub fn print_summary(&self) {
        let table = &self.table;
        let mode = |r: &BenchRow| {
            format!(
                "{} {} {} {}",
                r.text("cache_update"),
                r.text("write_rule"),
                r.text("write_pass"),
                r.text("line_kernel")
            )
            .trim_end()
            .to_string()
        };
        let mut groups: Vec<(String, String)> = Vec::new();
        for r in &table.rows {
            let key = (r.text("width"), mode(r));
            if !groups.contains(&key) {
                groups.push(key);
            }
        }
        for (size, m) in groups {
            let rows: Vec<&BenchRow> = table.rows.iter().filter(|r| r.text("width") == size && mode(r) == m).collect();
            let (Some(first), Some(last)) = (rows.first(), rows.last()) else { continue };
            let ms = |r: &BenchRow, k: &str| r.get_f64(k).unwrap_or(f64::NAN);
            let cost = |r: &BenchRow| r.get_f64("step_ms").unwrap_or(0.0);
            let largest = rows.iter().max_by(|a, b| cost(a).total_cmp(&cost(b)));
            let (dvr, frame) = (ms(first, "gpu_ms"), ms(last, "gpu_ms"));
            print!("{size}x{size} {m}: IPSVI {frame:.0} ms, {:.1}x DVR ({dvr:.0} ms)", frame / dvr);
            if let Some(step) = largest {
                print!("; largest step {} ({:.0} %)", step.text("step"), 100.0 * ms(step, "step_share"));
            }
            println!();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn timings(rounds: &[f64]) -> Timings<Counts> {
        Timings {
            rounds: rounds.iter().map(|&r| Some(r)).collect(),
            last: Counts { dispatches: 1, barriers: 0, shape: None },
        }
    }

    #[test]
    fn a_step_within_noise_has_no_cost_and_a_real_one_has() {
        let below = timings(&[10.0, 11.0, 9.0, 10.0, 12.0, 10.0]);
        let same = timings(&[10.5, 10.0, 9.5, 10.5, 11.0, 10.2]);
        let (estimate, cost) = step_cost(&same, Some(&below));
        assert_eq!(estimate.map(|e| e.verdict()), Some(crate::bench::Verdict::WithinNoise));
        assert_eq!(cost, None, "never a cost, let alone a negative one, within noise");
        let more = timings(&[12.0, 13.0, 11.0, 12.0, 14.0, 12.0]);
        assert_eq!(step_cost(&more, Some(&below)).1, Some(2.0));
        // Fewer than six rounds: the difference of medians, only when above 0.
        assert_eq!(step_cost(&timings(&[3.0]), Some(&timings(&[1.0]))), (None, Some(2.0)));
        assert_eq!(step_cost(&timings(&[1.0]), Some(&timings(&[3.0]))), (None, None));
    }

    #[test]
    fn a_step_below_the_one_before_is_named_on_its_bar_with_the_frame_time() {
        let mut report =
            BreakdownReport { table: BenchTable::new(), widths_table: BenchTable::new(), bars: Vec::new() };
        let dvr = timings(&[1.0, 1.1, 0.9, 1.0, 1.2, 1.0]);
        let noise = timings(&[1.05, 1.0, 0.95, 1.05, 1.1, 1.02]);
        let slow = timings(&[9.0, 9.5, 8.5, 9.0, 9.8, 9.1]);
        let fast = timings(&[5.0, 5.2, 4.8, 5.0, 5.4, 5.1]);
        let steps = [("a: x", &dvr), ("b: y", &noise), ("c: z", &slow), ("d: w", &fast)];
        report.step_rows(16, &IpsviSettings::default(), "serial", 16, &steps);
        let label = &report.bars[0].label;
        assert!(label.contains("(b within noise: 0)"), "{label}");
        assert!(label.contains("(d below the step before: 0; frame 5 ms)"), "{label}");
        let verdicts: Vec<String> = report.table.rows.iter().map(|r| r.text("step_ms_verdict")).collect();
        assert_eq!(verdicts, ["cost", "within noise", "cost", "below baseline"]);
    }

    #[test]
    fn both_write_passes_are_measured_where_the_writes_allow_the_texel_pass() {
        let both = [LineKernel::Serial, LineKernel::Segmented];
        let modes = |base: &IpsviSettings| configurations(base, &both).iter().map(short_mode).collect::<Vec<_>>();
        let all = [
            "view, sample pass",
            "view",
            "view every, sample pass",
            "view every",
            "rays",
            "view, segmented",
            "view every, segmented",
            "rays, segmented",
        ];
        assert_eq!(modes(&IpsviSettings::default()), all);
        // The scene's kernel does not matter either: both are measured.
        let segmented = IpsviSettings { line_kernel: LineKernel::Segmented, segments: 8, ..Default::default() };
        assert_eq!(modes(&segmented), all);
        let sample_writes =
            IpsviSettings { write_value: crate::techniques::ipsvi::WriteValue::Sample, ..Default::default() };
        assert_eq!(modes(&sample_writes), ["view, sample pass", "view every, sample pass", "rays", "rays, segmented"]);
        // The scene's own pass does not matter: both are measured.
        let sample = IpsviSettings { write_pass: WritePass::Sample, ..Default::default() };
        assert_eq!(modes(&sample), all);
    }

    #[test]
    fn the_line_widths_are_checked_by_name() {
        let plan = BreakdownPlan {
            sizes: vec![16],
            line_widths: vec![1, 99],
            interleaved: Interleaved::fixed(1, 0).unwrap(),
            volume_texels: VolumeTexels::Native,
            kernels: vec![LineKernel::Serial],
        };
        let e = plan.check(&IpsviSettings::default()).unwrap_err().to_string();
        assert!(e.starts_with("--line-widths") && e.contains("line_width"), "{e}");
        let e = BreakdownPlan { sizes: vec![0], ..plan.clone() }.check(&IpsviSettings::default()).unwrap_err();
        assert!(e.to_string().starts_with("--sizes"), "{e}");
        // View samples under each write rule and write pass, light rays once;
        // the texel pass and light rays again segmented.
        assert_eq!(configurations(&IpsviSettings::default(), &[LineKernel::Serial, LineKernel::Segmented]).len(), 8);
        assert_eq!(configurations(&IpsviSettings::default(), &[LineKernel::Segmented]).len(), 3);
    }
}
