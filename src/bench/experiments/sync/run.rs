//! The rounds of the study: per workload (the sweep first, then the chain,
//! then the empty workload), its configurations set up, a warm-up round, what
//! fits the time budget kept, shuffled timed rounds until every interval the
//! workload answers with is as narrow as asked (or the budget or the most
//! rounds end them), then one traced frame per strategy. The report is summed
//! up after every round ([`summarize`]) and handed to the observer.

use super::budget;
use super::chain::ChainLines;
use super::chain_plan::{self, ChainSetup};
use super::lines::StudyLines;
use super::plan::{self, settings_for, SyncPlan};
use super::report::{ConfigRow, SyncReport, WorkloadRounds};
use super::traces::{self, TraceSummary};
use super::{Arm, ConfigKey, LeftOut, Workload};
use crate::bench::cpu_time::{cpu_ms_between, process_cpu_time};
use crate::bench::estimate::{median_estimate, median_of, MIN_SAMPLES};
use crate::bench::experiments::ExperimentError;
use crate::bench::protocol::{Next, Protocol, Rounds};
use crate::bench::run_info::RunInfo;
use crate::linear_image::LinearImage;
use crate::metrics::compare;
use crate::render::GpuScene;
use crate::techniques::ipsvi::renderer::{plans, IpsviRenderer};
use crate::techniques::ipsvi::{IpsviSettings, SyncStrategy};
use crate::vk::{Context, Profiler};
use ash::vk;
use std::cell::{Cell, RefCell};
use std::collections::HashSet;
use std::time::{Duration, Instant};

const MAX_FRAMES_PER_RUN: u32 = 32;

/// Called as the study goes: before and after each workload's warm-up,
/// after every round with the report so far, and with each trace.
pub trait SyncObserver {
    /// Before a workload's warm-up round.
    fn warm_up(&mut self, _workload: Workload, _configurations: usize) {}
    /// After it: the configurations its rounds measure, how long its fewest
    /// rounds take (predicted from the warm-up), and what it left out to fit
    /// the time budget.
    fn planned(
        &mut self,
        _workload: Workload,
        _configurations: usize,
        _fewest_rounds: Duration,
        _left_out: Option<&LeftOut>,
    ) {
    }
    fn round(&mut self, report: &SyncReport, eta: Eta) -> Result<(), ExperimentError>;
    /// A traced frame's Perfetto trace, to be written as `file`.
    fn trace(&mut self, _file: &str, _trace: &serde_json::Value) -> Result<(), ExperimentError> {
        Ok(())
    }
}

/// Where the rounds stand.
#[derive(Clone, Copy, Debug)]
pub struct Eta {
    pub workload: Workload,
    pub round: usize,
    pub last_round: Duration,
    /// Rounds still to come at most, and the time they take at the mean pace.
    pub rounds_left: usize,
    pub time_left: Duration,
}

/// One run of a configuration: the mean of its frames.
#[derive(Clone, Copy, Debug, Default)]
struct Run {
    gpu_ms: f64,
    cpu_ms: f64,
    wall_ms: f64,
}

struct Configuration<'a> {
    key: ConfigKey,
    lines: StudyLines<'a>,
    line_count: u32,
    blocks: u32,
    dispatches: u32,
    barriers: u32,
    hazards: usize,
    frames_per_run: u32,
    last_image: Option<LinearImage>,
    /// Left out of the rounds to fit the time budget ([`budget`]).
    left_out: bool,
}

impl<'a> Configuration<'a> {
    fn new(key: ConfigKey, lines: StudyLines<'a>, line_count: u32, blocks: u32) -> Configuration<'a> {
        Configuration {
            key,
            lines,
            line_count,
            blocks,
            dispatches: 0,
            barriers: 0,
            hazards: 0,
            frames_per_run: 1,
            last_image: None,
            left_out: false,
        }
    }
}

/// What the rounds measured so far: every configuration's runs (paired by
/// index within a workload), each workload's rounds, the chain's set-up and
/// the traces.
#[derive(Default)]
struct Measured {
    runs: Vec<Vec<Run>>,
    workloads: Vec<WorkloadRounds>,
    chain: Option<ChainSetup>,
    traces: Vec<TraceSummary>,
}

impl Measured {
    fn series(&self, c: usize, value: impl Fn(&Run) -> f64) -> Vec<f64> {
        self.runs[c].iter().map(value).collect()
    }
}

/// Everything a workload needs from the study around it.
struct Study<'s, 'a> {
    ctx: &'a Context,
    gpu: &'s GpuScene<'a>,
    base: &'s IpsviSettings,
    plan: &'s SyncPlan,
    run_info: &'s RunInfo,
    started: Instant,
    line_group: Option<u32>,
}

/// Runs the study; `observer` sees the report after every round. Validation
/// messages of a racy arm that are synchronization hazards are expected and
/// counted; any other message fails the study.
pub fn run(
    ctx: &Context,
    gpu: &GpuScene,
    base: &IpsviSettings,
    plan: &SyncPlan,
    run_info: RunInfo,
    observer: &mut dyn SyncObserver,
) -> Result<SyncReport, ExperimentError> {
    plan::check(plan, base)?;
    // The time budget counts set-up and warm-up too.
    let started = Instant::now();
    // One workgroup size for every line width, so the work per pixel is the
    // same and only the number of blocks changes.
    let line_group = if plan.workloads.iter().any(|w| *w != Workload::Chain) {
        let (s, ipsvi_study) = settings_for(base, plan.narrowest(), SyncStrategy::Racy, Workload::Sweep);
        Some(IpsviRenderer::build(gpu, &s, &ipsvi_study, plan.width, plan.height, None)?.line_group())
    } else {
        None
    };
    let study = Study { ctx, gpu, base, plan, run_info: &run_info, started, line_group };
    let mut profiler = Profiler::new(ctx, Profiler::FRAME_CAPACITY)?;
    let mut configs: Vec<Configuration> = Vec::new();
    let mut measured = Measured::default();
    let order = plan::execution_order(&plan.workloads);
    for (n, &workload) in order.iter().enumerate() {
        let deadline = plan.time_budget.map(|budget| {
            let left = budget.saturating_sub(started.elapsed());
            let keep: f64 = order[n + 1..].iter().map(|&w| plan::later_share(w)).sum();
            Instant::now() + left.saturating_sub(budget.mul_f64(keep))
        });
        let first = configs.len();
        match workload {
            Workload::Chain => {
                let setup = chain_setup(&study, &configs, &measured, deadline, &mut profiler)?;
                add_chain_configs(&study, &setup, &mut configs)?;
                measured.chain = Some(setup);
            }
            _ => add_line_configs(&study, workload, &mut configs)?,
        }
        measured.runs.resize(configs.len(), Vec::new());
        let members: Vec<usize> = (first..configs.len()).collect();
        measured.workloads.push(WorkloadRounds {
            workload,
            rounds: 0,
            orders: Vec::new(),
            seconds: 0.0,
            warm_up_frames: 0,
            line_widths: if workload == Workload::Chain { vec![1] } else { plan.line_widths.clone() },
            left_out: None,
        });
        observer.warm_up(workload, members.len());
        run_workload(&study, &mut configs, &members, deadline, &mut profiler, &mut measured, observer)?;
        if plan.line_timestamps {
            trace_workload(&study, &mut configs, &members, &mut profiler, &mut measured, observer)?;
        }
    }
    Ok(summarize(&study, &configs, &measured, true))
}

/// The sweep's or the empty workload's configurations, each an IPSVI renderer.
fn add_line_configs<'a>(
    study: &Study<'_, 'a>,
    workload: Workload,
    configs: &mut Vec<Configuration<'a>>,
) -> Result<(), ExperimentError> {
    let (width, height) = (study.plan.width, study.plan.height);
    for key in plan::configurations(study.plan, workload) {
        let (s, ipsvi_study) = settings_for(study.base, key.line_width, key.arm.sync(), key.workload);
        let plans = plans(study.gpu, &s, width, height);
        let renderer = IpsviRenderer::build(study.gpu, &s, &ipsvi_study, width, height, study.line_group)?;
        let (lines, blocks) = (plans.iter().map(|p| p.lines()).sum(), plans.iter().map(|p| p.dispatches()).sum());
        configs.push(Configuration::new(key, StudyLines::Ipsvi(Box::new(renderer)), lines, blocks));
    }
    Ok(())
}

/// A sweep line's latency, us: the frame with a barrier after every line (the
/// reference strategy's, where each line's latency is exposed) over its
/// lines, at the narrowest line width; else the baseline's.
fn sweep_line_latency(configs: &[Configuration], measured: &Measured) -> Option<(f64, String)> {
    let candidates = [Arm::Strategy(SyncStrategy::BarrierGlobal), Arm::NoBarriers];
    let narrowest = configs.iter().filter(|c| c.key.workload == Workload::Sweep).map(|c| c.key.line_width).min()?;
    for arm in candidates {
        let found = configs.iter().enumerate().find(|(_, c)| {
            c.key.workload == Workload::Sweep
                && c.key.arm == arm
                && c.key.line_width == narrowest
                && !c.key.line_timestamps
        });
        if let Some((i, c)) = found {
            let mut ms = measured.series(i, |r| r.gpu_ms);
            ms.sort_by(f64::total_cmp);
            if !ms.is_empty() {
                let us = median_of(&ms) * 1e3 / c.blocks.max(1) as f64;
                return Some((
                    us,
                    format!("the sweep's {} frame at line width {narrowest} over its lines", arm.name()),
                ));
            }
        }
    }
    None
}

/// One line alone at `trips`: the fastest of three frames (the first compiles), ms.
fn alone_ms(ctx: &Context, profiler: &mut Profiler, invocations: u32, trips: u32) -> Result<f64, ExperimentError> {
    let lines = ChainLines::new(ctx, 1, invocations, trips)?;
    let mut best = f64::INFINITY;
    for _ in 0..3 {
        profiler.reset();
        lines.frame(profiler, SyncStrategy::Racy)?;
        best = best.min(profiler.resolve(0)?.gpu_ms_total);
    }
    Ok(best)
}

/// Probes one trip's time and plans the chain's lengths and lines from the
/// sweep's line latency and the time left.
fn chain_setup(
    study: &Study,
    configs: &[Configuration],
    measured: &Measured,
    deadline: Option<Instant>,
    profiler: &mut Profiler,
) -> Result<ChainSetup, ExperimentError> {
    let ctx = study.ctx;
    let invocations = study.plan.width.div_ceil(super::chain::GROUP) * super::chain::GROUP;
    let zero = alone_ms(ctx, profiler, invocations, 0)?;
    let mut probe = 64u32;
    let mut probed = alone_ms(ctx, profiler, invocations, probe)?;
    // Long enough that the chain, not the dispatch or the clock, is measured.
    while probed - zero < (5.0 * zero).max(0.5) && probe < chain_plan::MAX_TRIPS {
        probe = (probe * 4).min(chain_plan::MAX_TRIPS);
        probed = alone_ms(ctx, profiler, invocations, probe)?;
    }
    let trip_ns = ((probed - zero) * 1e6 / probe as f64).max(1e-3);
    let (line_latency_us, line_latency_from) = sweep_line_latency(configs, measured).unwrap_or((
        chain_plan::DEFAULT_LINE_LATENCY_US,
        "no sweep ran before the chain: a default length".to_string(),
    ));
    let arms = study.plan.arms().into_iter().filter(|a| *a != Arm::NoBarriersAgain).count();
    let time_left = deadline.map_or(f64::INFINITY, |d| d.saturating_duration_since(Instant::now()).as_secs_f64());
    let (lines, max_multiple, reduced) =
        chain_plan::fit(line_latency_us, trip_ns, zero * 1e3, arms, study.plan.protocol.min_rounds, time_left);
    Ok(ChainSetup {
        lines,
        invocations,
        steps_per_trip: super::chain::STEPS_PER_TRIP,
        trips: chain_plan::trips_for(line_latency_us, trip_ns, max_multiple),
        line_latency_us,
        line_latency_from,
        trip_ns,
        max_multiple,
        reduced,
    })
}

fn add_chain_configs<'a>(
    study: &Study<'_, 'a>,
    setup: &ChainSetup,
    configs: &mut Vec<Configuration<'a>>,
) -> Result<(), ExperimentError> {
    for key in chain_plan::configurations(&study.plan.arms(), &setup.trips) {
        let lines = if key.arm == Arm::Alone { 1 } else { setup.lines };
        let chain = ChainLines::new(study.ctx, lines, setup.invocations, key.chain_trips)?;
        configs.push(Configuration::new(key, StudyLines::Chain(Box::new(chain)), lines, lines));
    }
    Ok(())
}

/// One workload's configurations (`members`): warm-up, what fits the
/// deadline, then shuffled rounds until its intervals are as narrow as asked,
/// the deadline, or the most rounds.
fn run_workload(
    study: &Study,
    configs: &mut [Configuration],
    members: &[usize],
    deadline: Option<Instant>,
    profiler: &mut Profiler,
    measured: &mut Measured,
    observer: &mut dyn SyncObserver,
) -> Result<(), ExperimentError> {
    let (ctx, plan) = (study.ctx, study.plan);
    let workload = configs[members[0]].key.workload;
    // The warm-up first, on its own: how long its frames took decides what
    // the fewest rounds can hold before the deadline.
    let mut warmed = Warmed::default();
    let mut warm_ms: Vec<Option<f64>> = vec![None; members.len()];
    plan.protocol.warm_up(members.len(), |i| {
        let run = warm_up(ctx, &mut configs[members[i]], profiler, &mut warmed, plan.min_run)?;
        // A skipped warm-up runs no frame (its time is 0).
        warm_ms[i] = (run.wall_ms > 0.0).then_some(run.wall_ms * configs[members[i]].frames_per_run as f64);
        Ok::<_, ExperimentError>(())
    })?;
    let members = fit_members(plan, configs, members, &warm_ms, deadline, measured, observer);
    // Both closures of the protocol see the configurations: one runs them,
    // the other sums them up after each round.
    let configs = RefCell::new(configs);
    let measured = RefCell::new(measured);
    let round_started: Cell<Option<Instant>> = Cell::new(None);
    let first_round: Cell<Option<Instant>> = Cell::new(None);
    let mut round_times: Vec<Duration> = Vec::new();
    let warm_up_frames = warmed.frames;
    Protocol { warm_up_rounds: 0, ..plan.protocol }.run(
        members.len(),
        |i, _| {
            let config = &mut configs.borrow_mut()[members[i]];
            // The first timed run starts the clock of the rounds.
            if round_started.get().is_none() {
                round_started.set(Some(Instant::now()));
                first_round.set(Some(Instant::now()));
            }
            measure(ctx, config, profiler)
        },
        |rounds: &Rounds<Run>| {
            let now = Instant::now();
            let since = round_started.replace(Some(now)).unwrap_or(now);
            round_times.push(now - since);
            let report = {
                let mut m = measured.borrow_mut();
                for (i, &c) in members.iter().enumerate() {
                    m.runs[c] = rounds.runs[i].clone();
                }
                let w = m.workloads.last_mut().expect("the workload's entry was pushed");
                w.rounds = rounds.count();
                w.orders = rounds.orders.iter().map(|o| o.iter().map(|&i| members[i]).collect()).collect();
                w.seconds = first_round.get().map(|t| t.elapsed().as_secs_f64()).unwrap_or(0.0);
                w.warm_up_frames = warm_up_frames;
                summarize(study, &configs.borrow(), &m, false)
            };
            let mean = round_times.iter().sum::<Duration>() / round_times.len() as u32;
            let precise = rounds.count() >= MIN_SAMPLES && report.precise_in(workload);
            let out_of_time = deadline.is_some_and(|d| now + mean > d);
            let stop = precise || out_of_time;
            let to_max = plan.protocol.max_rounds as usize - rounds.count();
            let to_min = (plan.protocol.min_rounds as usize).saturating_sub(rounds.count());
            let rounds_left = if stop {
                to_min
            } else {
                let by_deadline = deadline
                    .map(|d| (d.saturating_duration_since(now).as_secs_f64() / mean.as_secs_f64().max(1e-9)) as usize)
                    .unwrap_or(usize::MAX);
                by_deadline.max(to_min).min(to_max)
            };
            let eta = Eta {
                workload,
                round: rounds.count(),
                last_round: now - since,
                rounds_left,
                time_left: mean * rounds_left as u32,
            };
            observer.round(&report, eta)?;
            Ok(if stop { Next::Stop } else { Next::Continue })
        },
    )?;
    Ok(())
}

/// The arms traced per workload, and the configuration each traces: the
/// narrowest line width (sweep, empty) or the chain nearest one sweep line.
fn traced(configs: &[Configuration], members: &[usize]) -> Vec<usize> {
    let mut picked: Vec<usize> = Vec::new();
    for &i in members {
        let c = &configs[i];
        if c.left_out || c.key.line_timestamps || matches!(c.key.arm, Arm::NoBarriersAgain | Arm::Alone) {
            continue;
        }
        let better = |j: usize| {
            let o = &configs[j].key;
            (c.key.line_width, c.key.chain_trips.abs_diff(middle_trips(configs, members)))
                < (o.line_width, o.chain_trips.abs_diff(middle_trips(configs, members)))
        };
        match picked.iter().position(|&j| configs[j].key.arm == c.key.arm) {
            Some(p) if better(picked[p]) => picked[p] = i,
            Some(_) => {}
            None => picked.push(i),
        }
    }
    picked
}

/// The chain length of one sweep line's latency (the middle of the planned ones).
fn middle_trips(configs: &[Configuration], members: &[usize]) -> u32 {
    let mut trips: Vec<u32> = members.iter().map(|&i| configs[i].key.chain_trips).collect();
    trips.sort_unstable();
    trips.dedup();
    trips.get(trips.len() / 2).copied().unwrap_or(0)
}

/// One frame with per-line scopes per traced arm of the workload: its trace
/// to the observer, its summary into the report.
fn trace_workload(
    study: &Study,
    configs: &mut [Configuration],
    members: &[usize],
    profiler: &mut Profiler,
    measured: &mut Measured,
    observer: &mut dyn SyncObserver,
) -> Result<(), ExperimentError> {
    for i in traced(configs, members) {
        let c = &mut configs[i];
        profiler.reset();
        profiler.set_detail(true);
        let frame = c.lines.frame(profiler, c.key.arm.sync());
        profiler.set_detail(false);
        frame?;
        let profile = profiler.resolve(study.ctx.memory.device_local_peak())?;
        c.hazards += expected_hazards(study.ctx, &c.key)?;
        let (summary, json) = traces::trace(&profile, c.lines.line_scope(), study.run_info, &c.key);
        observer.trace(&summary.file, &json)?;
        measured.traces.push(summary);
    }
    Ok(())
}

/// The members whose fewest rounds (and traced frames) fit before
/// `deadline` ([`budget`]), from each run's time in the warm-up (a
/// configuration that skipped its warm-up takes the mean of those that ran);
/// the rest are marked left out.
fn fit_members(
    plan: &SyncPlan,
    configs: &mut [Configuration],
    members: &[usize],
    warm_ms: &[Option<f64>],
    deadline: Option<Instant>,
    measured: &mut Measured,
    observer: &mut dyn SyncObserver,
) -> Vec<usize> {
    let known: Vec<f64> = warm_ms.iter().flatten().copied().collect();
    let mean_ms = if known.is_empty() { 0.0 } else { known.iter().sum::<f64>() / known.len() as f64 };
    let run_s: Vec<f64> = warm_ms.iter().map(|m| m.unwrap_or(mean_ms) / 1e3).collect();
    let keys: Vec<ConfigKey> = members.iter().map(|&c| configs[c].key).collect();
    let workload = keys[0].workload;
    let traced_s = if plan.line_timestamps { traced(configs, members).len() as f64 * mean_ms / 1e3 } else { 0.0 };
    let time_left = deadline.map_or(Duration::MAX, |d| d.saturating_duration_since(Instant::now()));
    let fit = if workload == Workload::Chain {
        // Planned to fit already (`chain_plan::fit`): every length stays.
        budget::fit(&keys, &run_s, plan.protocol.min_rounds, traced_s, Duration::MAX)
    } else {
        budget::fit(&keys, &run_s, plan.protocol.min_rounds, traced_s, time_left)
    };
    let kept: Vec<usize> = fit.kept.iter().map(|&i| members[i]).collect();
    for &c in members {
        configs[c].left_out = !kept.contains(&c);
    }
    let w = measured.workloads.last_mut().expect("the workload's entry was pushed");
    if let Some(out) = &fit.left_out {
        w.line_widths.retain(|lw| !out.line_widths.contains(lw));
    }
    w.left_out = fit.left_out.clone();
    observer.planned(workload, kept.len(), Duration::from_secs_f64(fit.kept_rounds_s), fit.left_out.as_ref());
    kept
}

/// What one workload's warm-up has run so far.
#[derive(Default)]
struct Warmed {
    /// Pipelines that have dispatched (llvmpipe compiles on the first dispatch).
    pipelines: HashSet<vk::Pipeline>,
    /// The shortest frame that compiled nothing, ms: where even it is a run
    /// on its own, every frame of the workload is.
    shortest_ms: Option<f64>,
    frames: usize,
}

impl Warmed {
    fn saw(&mut self, wall_ms: f64) {
        self.shortest_ms = Some(self.shortest_ms.map_or(wall_ms, |m| m.min(wall_ms)));
    }
}

/// A warm-up frame (the first of new pipelines compiles them, so a second
/// follows); where it is short, a second one sets how many frames a run
/// averages. A configuration whose pipelines have all run, in a workload
/// whose every frame so far was long (judged on frames that compiled
/// nothing), needs neither: only its line width and sync differ from a warmed
/// one's, so it skips the frame (the sweep's warm-up shrinks from one frame
/// per configuration to two per set of shaders).
fn warm_up(
    ctx: &Context,
    c: &mut Configuration,
    profiler: &mut Profiler,
    warmed: &mut Warmed,
    min_run: Duration,
) -> Result<Run, ExperimentError> {
    let pipelines = c.lines.pipelines();
    let compiles = !pipelines.iter().all(|p| warmed.pipelines.contains(p));
    let min_run_ms = min_run.as_secs_f64() * 1e3;
    let long_frames = warmed.shortest_ms.is_some_and(|ms| ms >= min_run_ms);
    if long_frames && !compiles {
        c.frames_per_run = 1;
        return Ok(Run::default());
    }
    let first = frame(ctx, c, profiler)?;
    warmed.frames += 1;
    warmed.pipelines.extend(pipelines);
    if !compiles {
        warmed.saw(first.wall_ms);
        if first.wall_ms >= min_run_ms {
            return Ok(first);
        }
    }
    let second = frame(ctx, c, profiler)?;
    warmed.frames += 1;
    warmed.saw(second.wall_ms);
    c.frames_per_run = ((min_run_ms / second.wall_ms.max(1e-3)).ceil() as u32).clamp(1, MAX_FRAMES_PER_RUN);
    Ok(second)
}

/// One run of `c`: `frames_per_run` frames, their mean times.
fn measure(ctx: &Context, c: &mut Configuration, profiler: &mut Profiler) -> Result<Run, ExperimentError> {
    let k = c.frames_per_run.max(1);
    let mut sum = Run::default();
    for _ in 0..k {
        let f = frame(ctx, c, profiler)?;
        sum.gpu_ms += f.gpu_ms / k as f64;
        sum.cpu_ms += f.cpu_ms / k as f64;
        sum.wall_ms += f.wall_ms / k as f64;
    }
    Ok(sum)
}

/// One frame of `c`: GPU time from the profiler (per-line scopes in the
/// baseline's timestamped frames), process CPU time and wall time around it.
fn frame(ctx: &Context, c: &mut Configuration, profiler: &mut Profiler) -> Result<Run, ExperimentError> {
    profiler.reset();
    profiler.set_detail(c.key.line_timestamps);
    let cpu_start = process_cpu_time();
    let wall_start = Instant::now();
    let frame = c.lines.frame(profiler, c.key.arm.sync());
    let wall_ms = wall_start.elapsed().as_secs_f64() * 1e3;
    let cpu_ms = cpu_ms_between(cpu_start, process_cpu_time());
    profiler.set_detail(false);
    let frame = frame?;
    let profile = profiler.resolve(ctx.memory.device_local_peak())?;
    c.hazards += expected_hazards(ctx, &c.key)?;
    c.dispatches = frame.dispatches;
    c.barriers = frame.barriers;
    if frame.image.is_some() {
        c.last_image = frame.image;
    }
    Ok(Run { gpu_ms: profile.gpu_ms_total, cpu_ms, wall_ms })
}

/// Racy arms have no barriers, so synchronization validation reports their
/// hazards by design: those are counted; any other message is an error.
fn expected_hazards(ctx: &Context, key: &ConfigKey) -> Result<usize, ExperimentError> {
    let messages = ctx.take_validation_messages();
    let (hazards, other): (Vec<String>, Vec<String>) =
        messages.into_iter().partition(|m| key.racy() && m.contains("SYNC-HAZARD"));
    if !other.is_empty() {
        return Err(ExperimentError::Validation { what: key.arm.name().to_string(), messages: other });
    }
    Ok(hazards.len())
}

/// The report from the rounds so far, every estimate derived.
fn summarize(study: &Study, configs: &[Configuration], measured: &Measured, complete: bool) -> SyncReport {
    let plan = study.plan;
    let reference = |key: &ConfigKey| {
        configs.iter().find(|o| {
            !o.left_out
                && o.key.workload == key.workload
                && o.key.line_width == key.line_width
                && !o.key.line_timestamps
                && o.key.arm == Arm::Strategy(SyncStrategy::BarrierGlobal)
        })
    };
    // Indices of the kept configurations in the report, for the rounds' orders.
    let mut index = vec![usize::MAX; configs.len()];
    let mut configurations = Vec::new();
    for (i, c) in configs.iter().enumerate().filter(|(_, c)| !c.left_out) {
        index[i] = configurations.len();
        let gpu = measured.series(i, |r| r.gpu_ms);
        let cpu = measured.series(i, |r| r.cpu_ms);
        let wall = measured.series(i, |r| r.wall_ms);
        let rmse = match (c.last_image.as_ref(), reference(&c.key).and_then(|r| r.last_image.as_ref())) {
            (Some(a), Some(b)) => compare(a, b).ok().map(|s| s.rmse),
            _ => None,
        };
        configurations.push(ConfigRow {
            workload: c.key.workload,
            arm: c.key.arm.name().to_string(),
            racy: c.key.racy(),
            line_width: c.key.line_width,
            line_timestamps: c.key.line_timestamps,
            chain_trips: c.key.chain_trips,
            lines: c.line_count,
            blocks: c.blocks,
            dispatches: c.dispatches,
            barriers: c.barriers,
            frames: measured.runs[i].len(),
            frames_per_run: c.frames_per_run,
            gpu_ms: median_estimate(&gpu).ok(),
            cpu_ms: median_estimate(&cpu).ok(),
            wall_ms: median_estimate(&wall).ok(),
            gpu_ms_runs: gpu,
            cpu_ms_runs: cpu,
            hazards_ignored: c.hazards,
            rmse_vs_barrier_global: rmse,
        });
    }
    let mut workloads = measured.workloads.clone();
    for w in &mut workloads {
        for order in &mut w.orders {
            *order = order.iter().map(|&i| index[i]).filter(|&i| i != usize::MAX).collect();
        }
    }
    let mut report = SyncReport {
        run: study.run_info.clone(),
        complete,
        workloads,
        warm_up_rounds: plan.protocol.warm_up_rounds,
        min_rounds: plan.protocol.min_rounds,
        max_rounds: plan.protocol.max_rounds,
        seed: plan.protocol.seed,
        precision: plan.precision,
        verdict_metric: "gpu".into(),
        width: plan.width,
        height: plan.height,
        line_widths: plan.line_widths.clone(),
        configurations,
        chain: measured.chain.clone(),
        traces: measured.traces.clone(),
        seconds: study.started.elapsed().as_secs_f64(),
        strategies: Vec::new(),
        timestamps: Vec::new(),
        calibration: Vec::new(),
    };
    report.derive();
    report
}
