//! The synchronization study (`sweeplab bench sync`): what one block boundary
//! of the IPSVI sweep costs under each way of synchronizing it.
//!
//! At one image size and scene, the line width varies (1, 2, 4, ... 32 lines
//! per dispatch): the number of blocks changes, the pixels and their work do
//! not (one workgroup size for every line width). Frame time against the
//! number of blocks is a line per strategy; its slope is the cost of one block
//! boundary (a dispatch and that strategy's sync). The no-barriers slope is the
//! dispatch's own cost, a strategy's slope minus it the cost of its sync.
//! Slopes are fitted round by round and compared round by round
//! ([`paired_slope_difference`]: a Hodges-Lehmann shift of the per-round
//! differences, against the mean of the baseline's two copies), so what a
//! round of the machine did to all its frames cancels.
//!
//! Two workloads: `sweep` (the scene's IPSVI frame) and `empty` (the same
//! dispatches and sync with shaders that return at once), so a boundary's
//! fixed cost is told apart from the drain of real work in flight.
//!
//! The baseline runs twice, as `no-barriers` and `no-barriers-again`: an A/A
//! control whose difference must come out within noise.

use super::sync_budget::{self, LeftOut};
use super::ExperimentError;
use crate::bench::cpu_time::{cpu_ms_between, process_cpu_time};
use crate::bench::estimate::{
    median_estimate, paired_difference, paired_slope_difference, quartiles, readable, slope_per_round, Estimate,
    Verdict, MIN_SAMPLES,
};
use crate::bench::protocol::{Next, Protocol, Rounds};
use crate::bench::run_info::RunInfo;
use crate::ipsvi::renderer::{plans, IpsviRenderer};
use crate::ipsvi::sync::EveryOther;
use crate::ipsvi::{BreakdownStep, IpsviSettings, IpsviStudy, SyncStrategy};
use crate::linear_image::LinearImage;
use crate::metrics::compare;
use crate::render::GpuScene;
use crate::scene::settings_table::SettingsTable as _;
use crate::vk::{Context, Profiler};
use ash::vk;
use serde::{Deserialize, Serialize};
use std::cell::{Cell, RefCell};
use std::collections::HashSet;
use std::time::{Duration, Instant};

/// Scopes a frame needs with a timestamp around every line dispatch.
const PROFILER_CAPACITY: u32 = 1 << 16;

/// Short frames (the empty workload) are run several times per run, so that
/// a run lasts at least this long and scheduler jitter averages out.
pub const MIN_RUN: Duration = Duration::from_millis(25);
const MAX_FRAMES_PER_RUN: u32 = 32;

/// What each line dispatch does.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Workload {
    /// The scene's IPSVI frame.
    Sweep,
    /// Every invocation returns at once: dispatches and sync alone.
    Empty,
}

impl Workload {
    pub const ALL: [Workload; 2] = [Workload::Empty, Workload::Sweep];

    pub fn name(self) -> &'static str {
        match self {
            Workload::Sweep => "sweep",
            Workload::Empty => "empty",
        }
    }

    fn breakdown_step(self) -> BreakdownStep {
        match self {
            Workload::Sweep => BreakdownStep::Full,
            Workload::Empty => BreakdownStep::Empty,
        }
    }
}

impl std::str::FromStr for Workload {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Workload::ALL
            .into_iter()
            .find(|w| w.name() == s)
            .ok_or_else(|| format!("unknown workload {s:?}; known: empty, sweep"))
    }
}

/// One arm of the study: the baseline, its A/A copy, or a strategy.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Arm {
    NoBarriers,
    NoBarriersAgain,
    Strategy(SyncStrategy),
}

/// The baseline's name in every output.
pub const BASELINE: &str = "no-barriers";
/// The A/A control's name.
pub const CONTROL: &str = "no-barriers-again";

impl Arm {
    pub fn name(self) -> &'static str {
        match self {
            Arm::NoBarriers => BASELINE,
            Arm::NoBarriersAgain => CONTROL,
            Arm::Strategy(s) => s.name(),
        }
    }

    fn sync(self) -> SyncStrategy {
        match self {
            Arm::NoBarriers | Arm::NoBarriersAgain => SyncStrategy::Racy,
            Arm::Strategy(s) => s,
        }
    }

    fn racy(self) -> bool {
        self.sync().is_racy()
    }
}

/// The interval asked for: a half-width of at most `relative` times the
/// estimate or at most `absolute_us`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Precision {
    pub relative: f64,
    pub absolute_us: f64,
}

impl Default for Precision {
    fn default() -> Self {
        Precision { relative: 0.25, absolute_us: 3.0 }
    }
}

/// What to measure.
#[derive(Clone, Debug)]
pub struct SyncPlan {
    /// Image size, pixels.
    pub width: u32,
    pub height: u32,
    /// Strategies compared with the baseline (`racy` is the baseline itself).
    pub strategies: Vec<SyncStrategy>,
    pub line_widths: Vec<u32>,
    pub workloads: Vec<Workload>,
    /// Frames at the narrowest line width with a timestamp around every
    /// dispatch: the gaps between dispatches and the timestamps' own cost.
    pub line_timestamps: bool,
    pub protocol: Protocol,
    pub precision: Precision,
    /// Rounds stop once the next would end past this (never before the
    /// protocol's fewest rounds).
    pub time_budget: Option<Duration>,
    /// Frames shorter than this are averaged, several to a run ([`MIN_RUN`]).
    pub min_run: Duration,
}

/// A configuration: workload, arm, line width, and whether its frames carry
/// per-line timestamps.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ConfigKey {
    pub workload: Workload,
    pub arm: Arm,
    pub line_width: u32,
    pub line_timestamps: bool,
}

impl ConfigKey {
    /// A strategy's per-line-timestamp frames synchronize after every other
    /// block only ([`EveryOther`]), to pair boundaries with and without the
    /// strategy in one frame: racy by design, like the baseline.
    pub fn every_other(&self) -> bool {
        self.line_timestamps && matches!(self.arm, Arm::Strategy(_))
    }

    /// Whether its frames leave blocks unsynchronized (hazards expected,
    /// images undefined).
    pub fn racy(&self) -> bool {
        self.arm.racy() || self.every_other()
    }
}

/// One run of a configuration: the mean of its frames.
#[derive(Clone, Debug, Default)]
pub struct Run {
    pub gpu_ms: f64,
    pub cpu_ms: f64,
    pub wall_ms: f64,
    /// Per-line timestamps only: gaps between consecutive line dispatches and
    /// their durations, us.
    pub gaps_us: Vec<f64>,
    pub lines_us: Vec<f64>,
    /// The median of `gaps_us` (NaN without per-line timestamps).
    pub gap_median_us: f64,
    /// Frames with the strategy after every other block only, per
    /// synchronized boundary: its period (its line's start to the next's) minus the mean of the periods of
    /// its two unsynchronized neighbours: a local, paired difference, in which
    /// the line's work (nearly that of its neighbours) and the machine's
    /// drift over the frame cancel, linear trends included.
    pub paired_sync_us: Vec<f64>,
    /// The median of `paired_sync_us` (NaN without).
    pub in_frame_sync_us: f64,
}

/// A configuration's frames, summed up.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct ConfigRow {
    pub workload: Workload,
    pub arm: String,
    pub racy: bool,
    pub line_width: u32,
    pub line_timestamps: bool,
    pub lines: u32,
    pub blocks: u32,
    pub dispatches: u32,
    pub barriers: u32,
    /// Timed runs, and frames per run (short frames are averaged).
    pub frames: usize,
    pub frames_per_run: u32,
    pub gpu_ms: Option<Estimate>,
    pub cpu_ms: Option<Estimate>,
    pub wall_ms: Option<Estimate>,
    /// Every frame's GPU and CPU time, ms, in round order (paired across
    /// configurations by index): the raw data behind the estimates.
    pub gpu_ms_runs: Vec<f64>,
    pub cpu_ms_runs: Vec<f64>,
    /// Synchronization hazards validation reported (racy arms, validation on).
    pub hazards_ignored: usize,
    /// RMSE of the last frame against barrier-global's at the same line width
    /// and workload (racy arms: undefined images, only their cost counts).
    pub rmse_vs_barrier_global: Option<f64>,
}

/// Per-line timestamps of one strategy: the gaps between consecutive line
/// dispatches (all rounds pooled), and what the timestamps themselves cost.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct LineGaps {
    pub line_width: u32,
    pub gap_median_us: f64,
    pub gap_q1_us: f64,
    pub gap_q3_us: f64,
    pub line_median_us: f64,
    /// The strategy's cost per boundary paired in the frame: in frames that
    /// synchronize after every other block, the median over a run's
    /// synchronized boundaries of the period (one line's start to the next's)
    /// after it minus the mean period after its two unsynchronized
    /// neighbours; one value per run, us (None for the baseline).
    #[serde(default)]
    pub in_frame_sync_us: Option<Estimate>,
    /// Frame time with the timestamps minus without, paired by round, ms
    /// (the baseline's; a strategy's timestamped frames sync half as often).
    pub perturbation_ms: Option<Estimate>,
    /// The gaps of the last run, for a histogram.
    pub last_gaps_us: Vec<f64>,
}

/// One strategy (or the baseline) in one workload.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct StrategyRow {
    pub workload: Workload,
    pub strategy: String,
    pub racy: bool,
    /// Slope of GPU frame time over blocks: the cost of one block boundary, us.
    pub boundary_us: Option<Estimate>,
    pub r_squared: Option<f64>,
    /// The fitted frame time at 0 blocks, ms (the work itself).
    pub intercept_ms: Option<f64>,
    /// `boundary_us` minus the baseline's, round by round: what the sync adds.
    /// None for the baseline.
    pub sync_us: Option<Estimate>,
    /// The same two from process CPU time (what lavapipe spends on the host).
    pub boundary_cpu_us: Option<Estimate>,
    pub sync_cpu_us: Option<Estimate>,
    pub line_gaps: Option<LineGaps>,
}

impl StrategyRow {
    /// The verdict's estimate of the sync cost per boundary, from its two
    /// estimates (frame slopes, and paired in the frame for strategies with
    /// per-line timestamps), by a rule that does not switch between them
    /// from run to run:
    /// - where the two agree (their intervals overlap), the narrower;
    /// - where they disagree, the frame slopes' value with an interval that
    ///   spans both: on lavapipe the per-line timestamps can change what a
    ///   boundary costs (a barrier after a timestamped dispatch drains what the
    ///   timestamp flushed), so either may be off by the other's bias, and
    ///   more rounds would not reconcile them.
    ///
    /// So a run whose estimators disagree is never precise, and two runs whose
    /// estimates each agree with their twins give overlapping verdicts.
    pub fn verdict_sync_us(&self) -> Option<Estimate> {
        let in_frame = self.line_gaps.as_ref().and_then(|g| g.in_frame_sync_us);
        match (self.sync_us, in_frame) {
            (Some(a), Some(b)) if self.estimates_agree() == Some(false) => {
                Some(Estimate { value: a.value, lo: a.lo.min(b.lo), hi: a.hi.max(b.hi), n: a.n.min(b.n) })
            }
            (Some(a), Some(b)) if b.half_width() < a.half_width() => Some(b),
            (a, b) => a.or(b),
        }
    }

    /// Whether the frame slopes' and the in-frame estimate's intervals overlap
    /// (None without both).
    pub fn estimates_agree(&self) -> Option<bool> {
        let in_frame = self.line_gaps.as_ref().and_then(|g| g.in_frame_sync_us)?;
        let slopes = self.sync_us?;
        Some(in_frame.lo <= slopes.hi && slopes.lo <= in_frame.hi)
    }
}

/// The whole study as measured so far.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct SyncReport {
    pub run: RunInfo,
    /// False while the study is still running (a partial report).
    pub complete: bool,
    /// Each workload's rounds (measured one workload after the other, each
    /// with its own shuffled rounds).
    pub workloads: Vec<WorkloadRounds>,
    pub warm_up_rounds: u32,
    pub min_rounds: u32,
    pub max_rounds: u32,
    pub seed: u64,
    pub precision: Precision,
    /// Which time the verdict reads: `gpu` (timestamps).
    pub verdict_metric: String,
    pub width: u32,
    pub height: u32,
    pub line_widths: Vec<u32>,
    pub configurations: Vec<ConfigRow>,
    pub strategies: Vec<StrategyRow>,
    /// Seconds since the study started (set-up and warm-up included).
    pub seconds: f64,
}

/// The rounds of one workload.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct WorkloadRounds {
    pub workload: Workload,
    pub rounds: usize,
    /// Each round's order of configurations (indices into `configurations`).
    pub orders: Vec<Vec<usize>>,
    /// Seconds of its timed rounds.
    pub seconds: f64,
    /// Frames its warm-up ran (configurations whose shaders had all run
    /// already, in a workload of long frames, run none).
    #[serde(default)]
    pub warm_up_frames: usize,
    /// The line widths its rounds measured (the plan's, less what was left out).
    #[serde(default)]
    pub line_widths: Vec<u32>,
    /// What it left out to fit its fewest rounds into the time budget.
    #[serde(default)]
    pub left_out: Option<LeftOut>,
}

/// Of the time budget, the share a workload that runs first keeps for the
/// ones after it. The sweep runs first: its fewest rounds take most of the
/// budget and cannot be shortened, while the empty workload's rounds take
/// about a second on lavapipe and narrow its intervals with what is left.
/// On lavapipe a third of a 10-minute budget gives the empty workload about
/// 150 rounds, what its near-zero costs need for a 3 us half-width, while the
/// sweep keeps its narrowest and widest line widths: at 256x256 its frame
/// slopes span +-500-1300 us after 6 rounds whether two or three widths run.
const LATER_WORKLOADS_SHARE: f64 = 0.35;

impl SyncReport {
    /// The strategy rows of `workload`.
    pub fn rows_of(&self, workload: Workload) -> impl Iterator<Item = &StrategyRow> {
        self.strategies.iter().filter(move |r| r.workload == workload)
    }

    /// Timed rounds per workload, e.g. `empty 30, sweep 6`.
    pub fn rounds_text(&self) -> String {
        self.workloads.iter().map(|w| format!("{} {}", w.workload.name(), w.rounds)).collect::<Vec<_>>().join(", ")
    }

    /// Timed rounds of `workload` (0 where it was not measured).
    pub fn rounds_of(&self, workload: Workload) -> usize {
        self.workloads.iter().find(|w| w.workload == workload).map_or(0, |w| w.rounds)
    }

    /// Whether every strategy's (and the control's) sync cost in `workload` is
    /// as precise as asked.
    pub fn precise_in(&self, workload: Workload) -> bool {
        self.rows_of(workload).filter(|r| r.strategy != BASELINE).all(|r| {
            r.verdict_sync_us().is_some_and(|e| e.precise_to(self.precision.relative, self.precision.absolute_us))
        })
    }

    /// Which sync interval of `workload` is the widest against what is asked,
    /// about how many rounds it would need to be as narrow as asked
    /// ([`Estimate::samples_for`]), and the minutes they take at the pace of
    /// its rounds so far.
    pub fn rounds_needed(&self, workload: Workload) -> Option<(&str, usize, f64)> {
        let (strategy, rounds) = self
            .rows_of(workload)
            .filter(|r| r.strategy != BASELINE && r.estimates_agree() != Some(false))
            .filter_map(|r| {
                let e = r.verdict_sync_us()?;
                if e.precise_to(self.precision.relative, self.precision.absolute_us) {
                    return None;
                }
                let rounds = e.samples_for(self.precision.relative, self.precision.absolute_us)?;
                Some((r.strategy.as_str(), rounds))
            })
            .max_by_key(|&(_, rounds)| rounds)?;
        let w = self.workloads.iter().find(|r| r.workload == workload)?;
        let pace_s = w.seconds / w.rounds.max(1) as f64;
        Some((strategy, rounds, rounds as f64 * pace_s / 60.0))
    }

    /// The strategies of `workload` whose two estimates disagree, e.g.
    /// `submits, events` (None where every one agrees).
    pub fn disagreeing(&self, workload: Workload) -> Option<String> {
        let names: Vec<&str> = self
            .rows_of(workload)
            .filter(|r| r.estimates_agree() == Some(false))
            .map(|r| r.strategy.as_str())
            .collect();
        (!names.is_empty()).then(|| names.join(", "))
    }

    /// One line per strategy and workload, e.g. `barrier-global: +2.10 us per
    /// boundary (95 % CI 0.800-3.40) over no barriers; dispatch 31.0 us (29.0-33.0)`.
    pub fn verdict(&self) -> Vec<String> {
        let mut out = Vec::new();
        for w in Workload::ALL {
            let Some(base) = self.rows_of(w).find(|r| r.strategy == BASELINE) else { continue };
            // A cost below zero is noise, never published as a cost.
            let dispatch = match base.boundary_us {
                Some(e) if e.verdict() == Verdict::Cost => {
                    format!("costs {} us ({}-{})", readable(e.value), readable(e.lo), readable(e.hi))
                }
                Some(e) => format!(
                    "cannot be told from noise here (95 % CI {}-{} us: the frames vary more than the boundaries add)",
                    readable(e.lo),
                    readable(e.hi)
                ),
                None => "is not measured".into(),
            };
            let precision = if self.precise_in(w) {
                "every interval as narrow as asked".to_string()
            } else {
                format!(
                    "not every interval as narrow as asked (half-width <= {} % of the estimate or <= {} us){}{}",
                    readable(self.precision.relative * 100.0),
                    readable(self.precision.absolute_us),
                    self.rounds_needed(w)
                        .map(|(widest, rounds, minutes)| if minutes > 600.0 {
                            format!("; the widest ({widest}) would need more than 10 hours of rounds at this pace")
                        } else {
                            format!(
                                "; the widest ({widest}) would need about {rounds} rounds, {} min at this pace",
                                readable(minutes)
                            )
                        })
                        .unwrap_or_default(),
                    self.disagreeing(w)
                        .map(|names| format!("; {names}: two estimates that disagree"))
                        .unwrap_or_default()
                )
            };
            out.push(format!(
                "{} workload ({} rounds; {precision}): a boundary with no barriers (the dispatch alone) {dispatch}",
                w.name(),
                self.rounds_of(w)
            ));
            if let Some(left) = self.workloads.iter().find(|r| r.workload == w).and_then(|r| r.left_out.as_ref()) {
                out.push(format!("  {}", left.describe()));
            }
            for r in self.rows_of(w).filter(|r| r.strategy != BASELINE) {
                let what =
                    if r.strategy == CONTROL { format!("{} (A/A control)", r.strategy) } else { r.strategy.clone() };
                let in_frame = r.line_gaps.as_ref().and_then(|g| g.in_frame_sync_us);
                let line = match (r.verdict_sync_us(), r.sync_us, in_frame) {
                    (None, ..) => format!("too few rounds (needs {MIN_SAMPLES})"),
                    (Some(v), Some(slopes), Some(paired)) => {
                        let (slopes, paired) = (slopes.describe("us"), paired.describe("us"));
                        let how = if r.estimates_agree() == Some(false) {
                            format!(
                                "spans both estimates, which disagree: frame slopes {slopes}, paired in the frame \
                                 {paired}; the per-line timestamps change what a boundary costs here, and more \
                                 rounds do not reconcile them"
                            )
                        } else if Some(v) == r.line_gaps.as_ref().and_then(|g| g.in_frame_sync_us) {
                            format!("paired in the frame; the frame slopes agree: {slopes}")
                        } else {
                            format!("frame slopes; paired in the frame agrees: {paired}")
                        };
                        format!("{} per boundary over no barriers ({how})", v.describe("us"))
                    }
                    (Some(v), Some(_), None) => {
                        format!("{} per boundary over no barriers (frame slopes)", v.describe("us"))
                    }
                    (Some(v), None, _) => {
                        format!("{} per boundary over no barriers (paired in the frame)", v.describe("us"))
                    }
                };
                out.push(format!("  {what}: {line}"));
            }
        }
        out
    }
}

/// Called after every round with the report so far, and how long the rounds
/// took and are expected to take.
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

struct Configuration<'a> {
    key: ConfigKey,
    renderer: IpsviRenderer<'a>,
    lines: u32,
    blocks: u32,
    dispatches: u32,
    barriers: u32,
    hazards: usize,
    frames_per_run: u32,
    last_image: Option<LinearImage>,
    /// Left out of the rounds to fit the time budget (`sync_budget`).
    left_out: bool,
}

/// Every configuration of `plan`, in a fixed order (workload, arm, line
/// width; then the per-line-timestamp frames).
pub fn configurations(plan: &SyncPlan) -> Vec<ConfigKey> {
    let mut arms = vec![Arm::NoBarriers, Arm::NoBarriersAgain];
    arms.extend(plan.strategies.iter().filter(|s| !s.is_racy()).map(|&s| Arm::Strategy(s)));
    let narrowest = plan.line_widths.iter().copied().min().unwrap_or(1);
    let mut keys = Vec::new();
    for &workload in &plan.workloads {
        for &arm in &arms {
            for &line_width in &plan.line_widths {
                keys.push(ConfigKey { workload, arm, line_width, line_timestamps: false });
            }
        }
    }
    if plan.line_timestamps {
        for &workload in &plan.workloads {
            // The control adds nothing the baseline does not show.
            for &arm in arms.iter().filter(|a| !matches!(a, Arm::NoBarriersAgain)) {
                keys.push(ConfigKey { workload, arm, line_width: narrowest, line_timestamps: true });
            }
        }
    }
    keys
}

/// Checks `plan` before any GPU work.
pub fn check(plan: &SyncPlan, base: &IpsviSettings) -> Result<(), ExperimentError> {
    let bad = |what: String| Err(ExperimentError::Invalid(what));
    if plan.line_widths.len() < 2 {
        return bad("a per-boundary cost is a slope: give at least two line widths (e.g. 1,2,4,8,16,32)".into());
    }
    if plan.workloads.is_empty() {
        return bad("give at least one workload (empty, sweep)".into());
    }
    for &line_width in &plan.line_widths {
        IpsviSettings { line_width, ..base.clone() }.validate().map_err(|e| ExperimentError::Invalid(e.to_string()))?;
    }
    Ok(())
}

/// Runs the study: sets up every configuration, then the protocol's rounds;
/// `observer` sees the report after every round. Validation messages of a
/// racy arm that are synchronization hazards are expected and counted; any
/// other message fails the study.
pub fn run(
    ctx: &Context,
    gpu: &GpuScene,
    base: &IpsviSettings,
    plan: &SyncPlan,
    run_info: RunInfo,
    observer: &mut dyn SyncObserver,
) -> Result<SyncReport, ExperimentError> {
    check(plan, base)?;
    // The time budget counts set-up and warm-up too.
    let started = Instant::now();
    let (width, height) = (plan.width, plan.height);
    let keys = configurations(plan);
    // One workgroup size for every line width, so the work per pixel is the
    // same and only the number of blocks changes.
    let narrowest = plan.line_widths.iter().copied().min().unwrap_or(1);
    let (s, study) = settings_for(base, narrowest, SyncStrategy::Racy, Workload::Sweep);
    let first = IpsviRenderer::build(gpu, &s, &study, width, height, None)?;
    let line_group = first.line_group();
    drop(first);
    let mut configs = Vec::with_capacity(keys.len());
    for key in keys {
        let (s, study) = settings_for(base, key.line_width, key.arm.sync(), key.workload);
        let plans = plans(gpu, &s, width, height);
        configs.push(Configuration {
            key,
            renderer: IpsviRenderer::build(gpu, &s, &study, width, height, Some(line_group))?,
            lines: plans.iter().map(|p| p.lines()).sum(),
            blocks: plans.iter().map(|p| p.dispatches()).sum(),
            dispatches: 0,
            barriers: 0,
            hazards: 0,
            frames_per_run: 1,
            last_image: None,
            left_out: false,
        });
    }
    let mut profiler = Profiler::new(ctx, PROFILER_CAPACITY)?;
    let mut measured = Measured { runs: vec![Vec::new(); configs.len()], workloads: Vec::new() };
    let order = execution_order(&plan.workloads);
    for (n, &workload) in order.iter().enumerate() {
        let members: Vec<usize> = (0..configs.len()).filter(|&i| configs[i].key.workload == workload).collect();
        let deadline = plan.time_budget.map(|budget| {
            let left = budget.saturating_sub(started.elapsed());
            let last = n + 1 == order.len();
            let keep = if last { Duration::ZERO } else { budget.mul_f64(LATER_WORKLOADS_SHARE) };
            Instant::now() + left.saturating_sub(keep)
        });
        measured.workloads.push(WorkloadRounds {
            workload,
            rounds: 0,
            orders: Vec::new(),
            seconds: 0.0,
            warm_up_frames: 0,
            line_widths: plan.line_widths.clone(),
            left_out: None,
        });
        observer.warm_up(workload, members.len());
        let mut report_of = |configs: &[Configuration], so_far: &Measured| {
            summarize(plan, configs, so_far, &run_info, false, started.elapsed())
        };
        run_workload(
            ctx,
            plan,
            &mut configs,
            &members,
            deadline,
            &mut profiler,
            &mut report_of,
            &mut measured,
            observer,
        )?;
    }
    Ok(summarize(plan, &configs, &measured, &run_info, true, started.elapsed()))
}

/// The order the workloads run in: the sweep first (see
/// [`LATER_WORKLOADS_SHARE`]); reports keep the plan's order.
fn execution_order(workloads: &[Workload]) -> Vec<Workload> {
    let mut order = workloads.to_vec();
    order.sort_by_key(|w| *w != Workload::Sweep);
    order
}

/// What the rounds measured so far: every configuration's runs (paired by
/// index within a workload), and each workload's rounds.
struct Measured {
    runs: Vec<Vec<Run>>,
    workloads: Vec<WorkloadRounds>,
}

impl Measured {
    fn series(&self, c: usize, value: impl Fn(&Run) -> f64) -> Vec<f64> {
        self.runs[c].iter().map(value).collect()
    }
}

/// One workload's configurations (`members`), in shuffled rounds until their
/// sync costs are precise enough, the deadline, or the most rounds.
#[allow(clippy::too_many_arguments)]
fn run_workload(
    ctx: &Context,
    plan: &SyncPlan,
    configs: &mut [Configuration],
    members: &[usize],
    deadline: Option<Instant>,
    profiler: &mut Profiler,
    report_of: &mut dyn FnMut(&[Configuration], &Measured) -> SyncReport,
    measured: &mut Measured,
    observer: &mut dyn SyncObserver,
) -> Result<(), ExperimentError> {
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
                report_of(&configs.borrow(), &m)
            };
            let mean = round_times.iter().sum::<Duration>() / round_times.len() as u32;
            let precise = rounds.count() >= MIN_SAMPLES && report.precise_in(workload);
            let out_of_time = deadline.is_some_and(|d| now + mean > d);
            let stop = precise || out_of_time;
            let min_rounds = plan.protocol.min_rounds as usize;
            let to_max = plan.protocol.max_rounds as usize - rounds.count();
            let to_min = min_rounds.saturating_sub(rounds.count());
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

/// The members whose fewest rounds fit before `deadline` ([`sync_budget`]),
/// from each run's time in the warm-up (a configuration that skipped its
/// warm-up takes the mean of those that ran); the rest are marked left out.
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
    let rounds = plan.protocol.min_rounds;
    let time_left = deadline.map_or(Duration::MAX, |d| d.saturating_duration_since(Instant::now()));
    let fit = sync_budget::fit(&keys, &run_s, rounds, time_left);
    let kept: Vec<usize> = fit.kept.iter().map(|&i| members[i]).collect();
    for &c in members {
        configs[c].left_out = !kept.contains(&c);
    }
    let workload = keys[0].workload;
    let w = measured.workloads.last_mut().expect("the workload's entry was pushed");
    if let Some(out) = &fit.left_out {
        w.line_widths.retain(|lw| !out.line_widths.contains(lw));
    }
    w.left_out = fit.left_out.clone();
    observer.planned(workload, kept.len(), Duration::from_secs_f64(fit.kept_rounds_s), fit.left_out.as_ref());
    kept
}

/// A configuration's settings and study. Every line width does the same work:
/// the claim pass, which a frame leaves out at line width 1 where it cannot
/// change the image (`IpsviSettings::records_claims`), stays in at every
/// width, or the slope over blocks would carry the pass's cost.
fn settings_for(
    base: &IpsviSettings,
    line_width: u32,
    sync: SyncStrategy,
    workload: Workload,
) -> (IpsviSettings, IpsviStudy) {
    let study =
        IpsviStudy { breakdown_step: workload.breakdown_step(), keep_redundant_claims: true, ..IpsviStudy::default() };
    (IpsviSettings { line_width, sync, merge_sweeps: false, ..base.clone() }, study)
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
/// whose every frame so far was long (judged on frames that compiled nothing), needs
/// neither: only its line width and sync differ from a warmed one's, so it
/// skips the frame (the sweep's warm-up shrinks from one frame per
/// configuration to two per set of shaders).
fn warm_up(
    ctx: &Context,
    c: &mut Configuration,
    profiler: &mut Profiler,
    warmed: &mut Warmed,
    min_run: Duration,
) -> Result<Run, ExperimentError> {
    let pipelines = c.renderer.pipelines();
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

/// One run of `c`: `frames_per_run` frames, their mean times and pooled gaps.
fn measure(ctx: &Context, c: &mut Configuration, profiler: &mut Profiler) -> Result<Run, ExperimentError> {
    let k = c.frames_per_run.max(1);
    let mut sum = Run::default();
    for _ in 0..k {
        let f = frame(ctx, c, profiler)?;
        sum.gpu_ms += f.gpu_ms / k as f64;
        sum.cpu_ms += f.cpu_ms / k as f64;
        sum.wall_ms += f.wall_ms / k as f64;
        sum.gaps_us.extend(f.gaps_us);
        sum.lines_us.extend(f.lines_us);
        sum.paired_sync_us.extend(f.paired_sync_us);
    }
    sum.gap_median_us = median_of_unsorted(&sum.gaps_us);
    sum.in_frame_sync_us = median_of_unsorted(&sum.paired_sync_us);
    Ok(sum)
}

/// The median of `values` (NaN for none).
fn median_of_unsorted(values: &[f64]) -> f64 {
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    crate::bench::estimate::median_of(&sorted)
}

/// One frame of `c`: GPU time from the profiler, process CPU time and wall
/// time around the submission; with per-line timestamps, the gaps.
fn frame(ctx: &Context, c: &mut Configuration, profiler: &mut Profiler) -> Result<Run, ExperimentError> {
    profiler.reset();
    profiler.set_detail(c.key.line_timestamps);
    let cpu_start = process_cpu_time();
    let wall_start = Instant::now();
    let frame = if c.key.every_other() {
        c.renderer.frame_every_other(profiler, c.key.arm.sync())
    } else {
        c.renderer.frame(profiler, c.key.arm.sync())
    };
    let wall_ms = wall_start.elapsed().as_secs_f64() * 1e3;
    let cpu_ms = cpu_ms_between(cpu_start, process_cpu_time());
    profiler.set_detail(false);
    let frame = frame?;
    let profile = profiler.resolve(ctx.memory.device_local_peak())?;
    c.hazards += expected_hazards(ctx, &c.key)?;
    c.dispatches = frame.dispatches;
    c.barriers = frame.barriers;
    c.last_image = Some(frame.image);
    let mut run = Run { gpu_ms: profile.gpu_ms_total, cpu_ms, wall_ms, ..Run::default() };
    if c.key.line_timestamps {
        let t = profile.timeline("ipsvi_line");
        if c.key.every_other() {
            // Scope i is block i (every block has one, in frame order); the
            // period after it spans its line and the boundary that follows.
            for (i, gap) in t.gaps_us.iter().enumerate() {
                if EveryOther::synchronizes_after(i) {
                    run.gaps_us.push(*gap);
                }
            }
            run.paired_sync_us = paired_sync_differences(&t.durations_us, &t.gaps_us);
        } else {
            run.gaps_us = t.gaps_us;
        }
        run.lines_us = t.durations_us;
    }
    Ok(run)
}

/// The baseline rounds `arm` is compared with. Where the A/A control ran, the
/// baseline was measured twice a round: a strategy is compared with both
/// copies (their mean, [`paired_slope_difference`]), the control itself with
/// the first copy alone.
fn baselines_for<'a>(
    arm: Arm,
    base: &'a [Vec<(f64, f64)>],
    again: &'a [Vec<(f64, f64)>],
) -> Vec<&'a [Vec<(f64, f64)>]> {
    if arm == Arm::NoBarriersAgain || again.is_empty() {
        vec![base]
    } else {
        vec![base, again]
    }
}

/// Per synchronized boundary of an [`EveryOther`] frame (block i's line
/// `durations_us[i]`, then the gap `gaps_us[i]` to the next line's start):
/// its period minus the mean period of its two unsynchronized neighbours.
fn paired_sync_differences(durations_us: &[f64], gaps_us: &[f64]) -> Vec<f64> {
    let period = |i: usize| durations_us[i] + gaps_us[i];
    (1..gaps_us.len().min(durations_us.len()).saturating_sub(1))
        .filter(|&i| EveryOther::synchronizes_after(i))
        .map(|i| period(i) - 0.5 * (period(i - 1) + period(i + 1)))
        .collect()
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

/// The report from the rounds so far.
fn summarize(
    plan: &SyncPlan,
    configs: &[Configuration],
    rounds: &Measured,
    run_info: &RunInfo,
    complete: bool,
    elapsed: Duration,
) -> SyncReport {
    let gpu = |c: usize| rounds.series(c, |r| r.gpu_ms);
    let cpu = |c: usize| rounds.series(c, |r| r.cpu_ms);
    let wall = |c: usize| rounds.series(c, |r| r.wall_ms);
    let reference = |key: &ConfigKey| {
        configs.iter().find(|o| {
            !o.left_out
                && o.key.workload == key.workload
                && o.key.line_width == key.line_width
                && !o.key.line_timestamps
                && o.key.arm == Arm::Strategy(SyncStrategy::BarrierGlobal)
        })
    };
    let configurations = configs
        .iter()
        .enumerate()
        .filter(|(_, c)| !c.left_out)
        .map(|(i, c)| ConfigRow {
            workload: c.key.workload,
            arm: c.key.arm.name().to_string(),
            racy: c.key.racy(),
            line_width: c.key.line_width,
            line_timestamps: c.key.line_timestamps,
            lines: c.lines,
            blocks: c.blocks,
            dispatches: c.dispatches,
            barriers: c.barriers,
            frames: rounds.runs[i].len(),
            frames_per_run: c.frames_per_run,
            gpu_ms: median_estimate(&gpu(i)).ok(),
            cpu_ms: median_estimate(&cpu(i)).ok(),
            wall_ms: median_estimate(&wall(i)).ok(),
            gpu_ms_runs: gpu(i),
            cpu_ms_runs: cpu(i),
            hazards_ignored: c.hazards,
            rmse_vs_barrier_global: match (c.last_image.as_ref(), reference(&c.key).and_then(|r| r.last_image.as_ref()))
            {
                (Some(a), Some(b)) if !c.key.racy() => compare(a, b).ok().map(|s| s.rmse),
                _ => None,
            },
        })
        .collect();
    // Per (workload, arm): each round's points (blocks, ms) over the line widths.
    let points = |workload: Workload, arm: Arm, value: &dyn Fn(&Run) -> f64| -> Vec<Vec<(f64, f64)>> {
        let members: Vec<usize> = (0..configs.len())
            .filter(|&i| {
                let c = &configs[i];
                !c.left_out && c.key.workload == workload && c.key.arm == arm && !c.key.line_timestamps
            })
            .collect();
        let count = members.iter().map(|&i| rounds.runs[i].len()).min().unwrap_or(0);
        (0..count)
            .map(|r| members.iter().map(|&i| (configs[i].blocks as f64, value(&rounds.runs[i][r]) * 1e3)).collect())
            .collect()
    };
    let mut strategies = Vec::new();
    for &workload in &plan.workloads {
        // The arms this workload measures (the control may have been left out).
        let mut arms: Vec<Arm> = Vec::new();
        for c in configs.iter().filter(|c| !c.left_out && c.key.workload == workload) {
            if !arms.contains(&c.key.arm) {
                arms.push(c.key.arm);
            }
        }
        let base_gpu = points(workload, Arm::NoBarriers, &|r| r.gpu_ms);
        let base_cpu = points(workload, Arm::NoBarriers, &|r| r.cpu_ms);
        let again_gpu = points(workload, Arm::NoBarriersAgain, &|r| r.gpu_ms);
        let again_cpu = points(workload, Arm::NoBarriersAgain, &|r| r.cpu_ms);
        for &arm in &arms {
            let arm_gpu = points(workload, arm, &|r| r.gpu_ms);
            let arm_cpu = points(workload, arm, &|r| r.cpu_ms);
            let fit = slope_per_round(&arm_gpu).ok();
            let is_base = arm == Arm::NoBarriers;
            strategies.push(StrategyRow {
                workload,
                strategy: arm.name().to_string(),
                racy: arm.racy(),
                boundary_us: fit.map(|f| f.slope),
                r_squared: fit.map(|f| f.r_squared),
                intercept_ms: fit.map(|f| f.intercept * 1e-3),
                sync_us: (!is_base)
                    .then(|| paired_slope_difference(&baselines_for(arm, &base_gpu, &again_gpu), &arm_gpu).ok())
                    .flatten(),
                boundary_cpu_us: slope_per_round(&arm_cpu).ok().map(|f| f.slope),
                sync_cpu_us: (!is_base)
                    .then(|| paired_slope_difference(&baselines_for(arm, &base_cpu, &again_cpu), &arm_cpu).ok())
                    .flatten(),
                line_gaps: line_gaps(configs, rounds, workload, arm),
            });
        }
    }
    SyncReport {
        run: run_info.clone(),
        complete,
        workloads: rounds.workloads.clone(),
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
        strategies,
        seconds: elapsed.as_secs_f64(),
    }
}

/// The per-line-timestamp frames of `arm`: pooled gaps, and the timestamps'
/// cost against the same line width's frames without them.
fn line_gaps(configs: &[Configuration], rounds: &Measured, workload: Workload, arm: Arm) -> Option<LineGaps> {
    let find = |stamped: bool, line_width: Option<u32>| {
        configs.iter().position(|c| {
            !c.left_out
                && c.key.workload == workload
                && c.key.arm == arm
                && c.key.line_timestamps == stamped
                && line_width.is_none_or(|w| c.key.line_width == w)
        })
    };
    let stamped = find(true, None)?;
    let line_width = configs[stamped].key.line_width;
    let plain = find(false, Some(line_width))?;
    let every_other = configs[stamped].key.every_other();
    let in_frame_sync_us =
        every_other.then(|| median_estimate(&rounds.series(stamped, |r| r.in_frame_sync_us)).ok()).flatten();
    let gaps: Vec<f64> = rounds.runs[stamped].iter().flat_map(|r| r.gaps_us.iter().copied()).collect();
    let lines: Vec<f64> = rounds.runs[stamped].iter().flat_map(|r| r.lines_us.iter().copied()).collect();
    if gaps.is_empty() {
        return None;
    }
    let (q1, q3) = quartiles(&gaps);
    let mut sorted = gaps.clone();
    sorted.sort_by(f64::total_cmp);
    let mut sorted_lines = lines;
    sorted_lines.sort_by(f64::total_cmp);
    Some(LineGaps {
        line_width,
        gap_median_us: crate::bench::estimate::median_of(&sorted),
        gap_q1_us: q1,
        gap_q3_us: q3,
        line_median_us: crate::bench::estimate::median_of(&sorted_lines),
        in_frame_sync_us,
        last_gaps_us: rounds.runs[stamped].last().map(|r| r.gaps_us.clone()).unwrap_or_default(),
        perturbation_ms: (!every_other)
            .then(|| paired_difference(&rounds.series(plain, |r| r.gpu_ms), &rounds.series(stamped, |r| r.gpu_ms)).ok())
            .flatten(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_sweep_runs_first_so_the_empty_workload_gets_what_is_left() {
        let both = execution_order(&[Workload::Empty, Workload::Sweep]);
        assert_eq!(both, [Workload::Sweep, Workload::Empty]);
        assert_eq!(execution_order(&[Workload::Empty]), [Workload::Empty]);
    }

    #[test]
    fn every_line_width_records_the_same_passes() {
        // The sample write pass, which leaves the claim pass out at line width 1.
        let base = IpsviSettings { write_pass: crate::ipsvi::WritePass::Sample, ..IpsviSettings::default() };
        assert!(!base.records_claims(), "line width 1 leaves the claim pass out of a frame");
        for line_width in [1, 2, 32] {
            let (s, study) = settings_for(&base, line_width, SyncStrategy::BarrierGlobal, Workload::Sweep);
            assert!(s.claims_recorded(study.keep_redundant_claims), "line width {line_width}");
        }
    }

    /// Two estimates of one cost: where they agree the verdict takes the
    /// narrower; where they do not, an interval that spans both (so it is not
    /// precise, and a second run's verdict overlaps it wherever either
    /// estimate overlaps its twin), never the narrow in-frame one alone.
    #[test]
    fn the_verdict_spans_two_estimates_that_disagree() {
        let e = |value: f64, lo: f64, hi: f64| Some(Estimate { value, lo, hi, n: 6 });
        let gaps = |in_frame: Option<Estimate>| LineGaps {
            line_width: 1,
            gap_median_us: 0.0,
            gap_q1_us: 0.0,
            gap_q3_us: 0.0,
            line_median_us: 0.0,
            in_frame_sync_us: in_frame,
            perturbation_ms: None,
            last_gaps_us: Vec::new(),
        };
        let row = |slopes: Option<Estimate>, in_frame: Option<Estimate>| StrategyRow {
            workload: Workload::Empty,
            strategy: "submits".into(),
            racy: false,
            boundary_us: e(60.0, 55.0, 65.0),
            r_squared: None,
            intercept_ms: None,
            sync_us: slopes,
            boundary_cpu_us: None,
            sync_cpu_us: None,
            line_gaps: Some(gaps(in_frame)),
        };
        // The previous record's two runs of submits, in us.
        let run1 = row(e(19.1, 15.6, 22.8), e(11.5, 10.5, 13.2));
        let run2 = row(e(16.9, 10.9, 23.1), e(11.7, 10.6, 13.1));
        assert_eq!(run1.estimates_agree(), Some(false));
        assert_eq!(run1.verdict_sync_us(), e(19.1, 10.5, 22.8), "the slopes' value, both intervals");
        assert_eq!(run2.estimates_agree(), Some(true));
        assert_eq!(run2.verdict_sync_us(), e(11.7, 10.6, 13.1), "the narrower of two that agree");
        let (v1, v2) = (run1.verdict_sync_us().unwrap(), run2.verdict_sync_us().unwrap());
        assert!(v1.lo <= v2.hi && v2.lo <= v1.hi, "the two runs' verdicts overlap");
        assert!(!v1.precise_to(0.25, 3.0), "a verdict over two disagreeing estimates is not precise");
        let wide_in_frame = row(e(1.0, 0.2, 1.8), e(1.5, -3.0, 6.0));
        assert_eq!(wide_in_frame.verdict_sync_us(), wide_in_frame.sync_us, "the narrower: here the slopes");
        assert_eq!(row(e(1.0, 0.2, 1.8), None).estimates_agree(), None);
        assert_eq!(row(e(1.0, 0.2, 1.8), None).verdict_sync_us(), e(1.0, 0.2, 1.8));
        assert_eq!(row(None, e(1.5, -3.0, 6.0)).verdict_sync_us(), e(1.5, -3.0, 6.0));
    }

    /// Lines whose work grows along the sweep (100 + 3 i us) and a sync that
    /// adds 7 us after every other one: the mean of both neighbours finds 7
    /// at every synchronized boundary, where one neighbour alone would read
    /// the 3 us of growth as part of the cost.
    #[test]
    fn the_paired_difference_cancels_work_that_changes_along_the_sweep() {
        let n = 41;
        let durations: Vec<f64> = (0..n).map(|i| 100.0 + 3.0 * i as f64).collect();
        let gaps: Vec<f64> = (0..n).map(|i| if EveryOther::synchronizes_after(i) { 12.0 } else { 5.0 }).collect();
        let paired = paired_sync_differences(&durations, &gaps);
        assert_eq!(paired.len(), (n - 2) / 2);
        for d in &paired {
            assert!((d - 7.0).abs() < 1e-9, "{paired:?}");
        }
    }
}
