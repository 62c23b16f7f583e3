//! The study's answer in words, one block per quantity: (a) the fixed cost of
//! a boundary (empty workload), (b) what a strategy costs the sweep per line
//! and as a share of its frame, beside the frame without barriers (sweep
//! workload, frames without per-line timestamps), (c) the per-line
//! timestamps' own effect and whether they serialize the lines here, and the
//! calibration's fitted pair per strategy (chain workload). Each line names
//! the estimate it reads; none joins two.

use super::estimates::{Serializes, StrategyRow, TimestampEffect};
use super::report::SyncReport;
use super::{Workload, BASELINE, CONTROL};
use crate::bench::estimate::{readable, Estimate, Verdict, MIN_SAMPLES};

/// A fraction's interval is as narrow as asked at this half-width.
pub const FRACTION_HALF_WIDTH: f64 = 0.1;

/// `1.14 us (0.965-1.54)`.
fn value_ci(e: &Estimate, unit: &str) -> String {
    format!("{} {unit} ({}-{})", readable(e.value), readable(e.lo), readable(e.hi))
}

/// `0.99 (0.97-1.01)`.
fn plain_ci(e: &Estimate) -> String {
    format!("{} ({}-{})", readable(e.value), readable(e.lo), readable(e.hi))
}

/// A frame time in ms, or in s above a second.
fn frame_time(ms: f64) -> String {
    if ms >= 1000.0 {
        format!("{} s", readable(ms / 1e3))
    } else {
        format!("{} ms", readable(ms))
    }
}

impl SyncReport {
    /// The strategy rows of `workload` the verdict reads (not the baseline).
    fn compared(&self, workload: Workload) -> impl Iterator<Item = &StrategyRow> {
        self.rows_of(workload).filter(|r| r.strategy != BASELINE)
    }

    /// Whether every estimate `workload`'s rounds aim at is as precise as asked.
    pub fn precise_in(&self, workload: Workload) -> bool {
        let p = self.precision;
        match workload {
            Workload::Chain => {
                !self.calibration.is_empty()
                    && self.calibration.iter().all(|f| {
                        f.fraction.is_some_and(|e| e.half_width() <= FRACTION_HALF_WIDTH)
                            && f.fixed_us.is_some_and(|e| e.precise_to(p.relative, p.absolute_us))
                    })
            }
            _ => self.compared(workload).all(|r| r.answer().is_some_and(|e| e.precise_to(p.relative, p.absolute_us))),
        }
    }

    /// Which interval of `workload` is the widest against what is asked,
    /// about how many rounds it would need ([`Estimate::samples_for`]), and
    /// the minutes they take at the pace of its rounds so far.
    pub fn rounds_needed(&self, workload: Workload) -> Option<(&str, usize, f64)> {
        let p = self.precision;
        let (strategy, rounds) = self
            .compared(workload)
            .filter_map(|r| {
                let e = r.answer()?;
                if e.precise_to(p.relative, p.absolute_us) {
                    return None;
                }
                Some((r.strategy.as_str(), e.samples_for(p.relative, p.absolute_us)?))
            })
            .max_by_key(|&(_, rounds)| rounds)?;
        let w = self.workload(workload)?;
        let pace_s = w.seconds / w.rounds.max(1) as f64;
        Some((strategy, rounds, rounds as f64 * pace_s / 60.0))
    }

    /// `(6 rounds; every interval as narrow as asked)` and what was left out.
    fn precision_text(&self, workload: Workload) -> String {
        let rounds = self.rounds_of(workload);
        if self.precise_in(workload) {
            return format!("{rounds} rounds; every interval as narrow as asked");
        }
        let asked = match workload {
            Workload::Chain => format!("fractions to +-{FRACTION_HALF_WIDTH}"),
            _ => format!(
                "half-width <= {} % of the estimate or <= {} us",
                readable(self.precision.relative * 100.0),
                readable(self.precision.absolute_us)
            ),
        };
        let needed = self
            .rounds_needed(workload)
            .map(|(widest, rounds, minutes)| {
                if minutes > 600.0 {
                    format!("; the widest ({widest}) would need more than 10 hours of rounds at this pace")
                } else {
                    format!("; the widest ({widest}) would need about {rounds} rounds, {} min", readable(minutes))
                }
            })
            .unwrap_or_default();
        format!("{rounds} rounds; not every interval as narrow as asked ({asked}){needed}")
    }

    /// The verdict: a block per workload measured, (a), (b), (c) and the calibration.
    pub fn verdict(&self) -> Vec<String> {
        let mut out = Vec::new();
        if self.rounds_of(Workload::Empty) > 0 {
            out.extend(self.fixed_cost_lines());
        }
        if self.rounds_of(Workload::Sweep) > 0 {
            out.extend(self.serialization_lines());
        }
        if !self.timestamps.is_empty() {
            out.push(
                "(c) per-line timestamps (the baseline's frame with a timestamp around every line, against \
                      without):"
                    .into(),
            );
            for t in &self.timestamps {
                out.push(format!("  {} workload: {}", t.workload.name(), timestamps_line(t)));
            }
        }
        out.extend(self.calibration_lines());
        out
    }

    fn left_out_line(&self, workload: Workload) -> Option<String> {
        self.workload(workload).and_then(|w| w.left_out.as_ref()).map(|l| format!("  {}", l.describe()))
    }

    fn control_line(&self, workload: Workload, per: &str) -> Option<String> {
        let r = self.row(workload, CONTROL)?;
        let e = r.answer()?;
        Some(format!("  {CONTROL} (A/A control): {} {per}", e.describe("us")))
    }

    /// What leaving the line barrier out did to the sweep's image: nothing
    /// where the device ran the lines in order (lavapipe), a different image
    /// where they overlapped. Validation reports the hazard either way.
    fn racy_image_line(&self, line_width: u32) -> Option<String> {
        let racy = self.configurations.iter().find(|c| {
            c.workload == Workload::Sweep && c.arm == BASELINE && c.line_width == line_width && !c.line_timestamps
        })?;
        let rmse = racy.rmse_vs_barrier_global?;
        Some(if rmse == 0.0 {
            "  its image (no barriers: racy): barrier-global's bit for bit; this device ran the lines in order".into()
        } else {
            format!(
                "  its image (no barriers: racy): RMSE {rmse:.3e} against barrier-global's; the lines overlapped, the \
                 barrier is load-bearing"
            )
        })
    }

    /// (a): the empty workload.
    fn fixed_cost_lines(&self) -> Vec<String> {
        let w = Workload::Empty;
        let how = match self.row(w, BASELINE) {
            Some(b) if b.boundary_us.is_some() => "frame slopes over the line widths",
            _ => "frame differences at one line width",
        };
        let mut out = vec![format!(
            "(a) the fixed cost of a line boundary, nothing in flight (empty workload, {how}; {}):",
            self.precision_text(w)
        )];
        out.extend(self.left_out_line(w));
        if let Some(base) = self.row(w, BASELINE) {
            let dispatch = match base.boundary_us {
                Some(e) if e.verdict() == Verdict::Cost => value_ci(&e, "us"),
                Some(e) => format!("cannot be told from noise (95 % CI {}-{} us)", readable(e.lo), readable(e.hi)),
                None => "not measured (one line width)".into(),
            };
            out.push(format!("  a boundary with no barriers (the dispatch alone): {dispatch}"));
        }
        out.extend(self.control_line(w, "per boundary"));
        for r in self.compared(w).filter(|r| r.strategy != CONTROL) {
            let line = match r.fixed_cost() {
                Some(e) => format!("{} per boundary over no barriers", e.describe("us")),
                None => format!("too few rounds (needs {MIN_SAMPLES})"),
            };
            out.push(format!("  {}: {line}", r.strategy));
        }
        out
    }

    /// (b): the sweep workload, each strategy with its fixed cost beside.
    fn serialization_lines(&self) -> Vec<String> {
        let w = Workload::Sweep;
        let Some(base) = self.row(w, BASELINE) else { return Vec::new() };
        let mut out = vec![format!(
            "(b) what each strategy costs the sweep, frames without per-line timestamps (sweep workload, {}, line \
             width {}: {} line boundaries per frame; {}):",
            self.line_kernel().map_or("line kernel not recorded: serial".to_string(), |k| format!("line kernel {k}")),
            base.line_width,
            base.boundaries,
            self.precision_text(w)
        )];
        out.extend(self.left_out_line(w));
        if let Some(f) = base.frame_ms {
            let ci = format!("{}-{}", frame_time(f.lo), frame_time(f.hi));
            out.push(format!("  the frame without barriers: {} ({ci})", frame_time(f.value)));
        }
        out.extend(self.racy_image_line(base.line_width));
        out.extend(self.control_line(w, "per line"));
        for r in self.compared(w).filter(|r| r.strategy != CONTROL) {
            let own = self.row(Workload::Empty, &r.strategy).and_then(StrategyRow::fixed_cost);
            out.push(format!("  {}: {}", r.strategy, sweep_line(r, own, base)));
        }
        out
    }

    /// The calibration: the chain workload's fit per arm.
    fn calibration_lines(&self) -> Vec<String> {
        let Some(setup) = &self.chain else {
            return vec!["calibration (chain workload): not measured in this run (a record from before the chain \
                         workload, or --workloads left it out; tools/gpu_check.sh measures it)"
                .into()];
        };
        let longest = self.calibration.first().and_then(|f| f.latencies_us.last().copied()).unwrap_or(f64::NAN);
        let mut out = vec![format!(
            "calibration: time per line boundary = fixed cost + serialized fraction x chain latency (chain \
             workload, {} lines of {} invocations; chains 0-{} us, up to {} sweep lines of {} us ({}); {}):",
            setup.lines,
            setup.invocations,
            readable(longest),
            readable(longest / setup.line_latency_us),
            readable(setup.line_latency_us),
            setup.line_latency_from,
            self.precision_text(Workload::Chain)
        )];
        if let Some(reduced) = &setup.reduced {
            out.push(format!("  {reduced}"));
        }
        for f in &self.calibration {
            let (Some(fixed), Some(fraction)) = (f.fixed_us, f.fraction) else {
                out.push(format!("  {}: too few rounds (needs {MIN_SAMPLES})", f.strategy));
                continue;
            };
            let mut line = format!(
                "  {}: fixed {}, fraction {} of the chain, r^2 {}",
                f.strategy,
                value_ci(&fixed, "us"),
                plain_ci(&fraction),
                f.r_squared.map_or("-".into(), |r| format!("{r:.4}"))
            );
            if let (Some(dfixed), Some(dfraction)) = (f.fixed_over_baseline_us, f.fraction_over_baseline) {
                line += &format!(
                    "; over no barriers: fixed {}, fraction {}",
                    dfixed.describe("us"),
                    dfraction.describe("of the chain")
                );
            }
            out.push(line);
        }
        out
    }
}

/// One strategy's sweep line in the user's terms.
fn sweep_line(r: &StrategyRow, own: Option<Estimate>, base: &StrategyRow) -> String {
    let own = match own {
        Some(e) if e.verdict() == Verdict::Cost => {
            format!("each line boundary costs {} of its own", value_ci(&e, "us"))
        }
        Some(e) => format!("each line boundary's own cost is {}", e.describe("us")),
        None => "its own cost per boundary is not measured here (the empty workload did not run)".into(),
    };
    let frames = match (r.frame_ms, base.frame_ms) {
        (Some(with), Some(without)) => {
            format!("{} with it, {} without barriers", frame_time(with.value), frame_time(without.value))
        }
        _ => String::new(),
    };
    let share =
        r.frame_share.map_or(String::new(), |s| format!(", {} % of the frame", readable((s.value * 100.0).max(0.0))));
    match r.serialization() {
        Some(e) if e.verdict() == Verdict::Cost => {
            format!("{own} and serializes the sweep: +{} per line{share} ({frames})", value_ci(&e, "us"))
        }
        Some(e) if e.verdict() == Verdict::WithinNoise => {
            format!(
                "{own}; what it adds to the sweep is within noise (95 % CI {}-{} us per line; {frames})",
                readable(e.lo),
                readable(e.hi)
            )
        }
        Some(e) => format!("{own}; the sweep ran faster with it, {} per line ({frames}): not a cost", e.describe("us")),
        None => format!("{own}; too few rounds of the sweep (needs {MIN_SAMPLES})"),
    }
}

/// The timestamps' effect in one workload.
fn timestamps_line(t: &TimestampEffect) -> String {
    let added = match (t.added_ms, t.added_per_line_us()) {
        (Some(frame), Some(line)) => {
            format!("{} per frame, {} per line", frame.describe("ms"), line.describe("us"))
        }
        _ => format!("too few rounds (needs {MIN_SAMPLES})"),
    };
    if t.workload != Workload::Sweep {
        // Nothing is in flight to serialize: what they add is the whole answer.
        return added;
    }
    let reference = t.reference.as_deref().unwrap_or("a barrier");
    let statement = match (t.serializes(), t.serialization_ratio) {
        (Serializes::Yes, Some(r)) => format!(
            "; they serialize the lines on this device: they add {}x what {reference} adds (95 % CI {}-{}), so \
             per-line timings here show lines one after another, not how they overlap",
            readable(r.value),
            readable(r.lo),
            readable(r.hi)
        ),
        (Serializes::Partly, Some(r)) => format!(
            "; they partly serialize the lines: they add {}x what {reference} adds (95 % CI {}-{})",
            readable(r.value),
            readable(r.lo),
            readable(r.hi)
        ),
        (Serializes::No, Some(r)) => format!(
            "; they do not serialize the lines: they add {}x what {reference} adds (95 % CI {}-{})",
            readable(r.value),
            readable(r.lo),
            readable(r.hi)
        ),
        (Serializes::NothingToSerialize, _) => format!(
            "; the lines do not overlap here without barriers ({reference}'s frame is not measurably slower), so \
             there is nothing for the timestamps to serialize"
        ),
        _ => "; whether they serialize the lines is not measured (no strategy beside them)".into(),
    };
    format!("{added}{statement}")
}
