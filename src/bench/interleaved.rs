//! The configurations of a bench measured side by side on the [`Protocol`]:
//! one warm-up round, then rounds in which every configuration runs once in a
//! shuffled order, each configuration's time kept round by round so two of
//! them can be compared pair by pair ([`Timings::paired_difference`],
//! [`Timings::paired_ratio`]), every figure a median with its 95 % interval.
//!
//! Why not one configuration's repeats after the other: on a shared machine a
//! block of repeats sees one state of the machine, the next block another,
//! and that drift reads as a difference between configurations.

use super::estimate::{median_estimate, median_of, paired_difference, Estimate, MIN_SAMPLES};
use super::harness::Sample;
use super::progress::Progress;
use super::protocol::{Next, Phase, Protocol, ProtocolError};
use super::run_info::RunInfo;
use std::cell::RefCell;
use std::io::Write;

/// One configuration's timed runs, one entry per round (`None` where the run
/// did not count: see [`Sample::left_out`]), and the output of its last run.
#[derive(Clone, Debug)]
pub struct Timings<T> {
    pub rounds: Vec<Option<f64>>,
    pub last: T,
}

impl<T> Timings<T> {
    /// The times that counted, in round order.
    pub fn samples(&self) -> Vec<f64> {
        self.rounds.iter().flatten().copied().collect()
    }

    /// Timed runs that did not count.
    pub fn left_out(&self) -> usize {
        self.rounds.iter().filter(|r| r.is_none()).count()
    }

    /// The median of the counted times (the mean of the middle two for an
    /// even count, as in [`Timings::estimate`]; NaN for none).
    pub fn median(&self) -> f64 {
        let mut sorted = self.samples();
        sorted.sort_by(f64::total_cmp);
        median_of(&sorted)
    }

    /// The median with its 95 % interval; `None` below [`MIN_SAMPLES`] counted runs.
    pub fn estimate(&self) -> Option<Estimate> {
        median_estimate(&self.samples()).ok()
    }

    /// `self - baseline`, round by round over the rounds both counted, with
    /// its interval; `None` below [`MIN_SAMPLES`] such rounds.
    pub fn paired_difference<U>(&self, baseline: &Timings<U>) -> Option<Estimate> {
        let (b, t) = paired(&baseline.rounds, &self.rounds);
        paired_difference(&b, &t).ok()
    }

    /// `self / baseline`, round by round (how many times the baseline's cost),
    /// with its interval; `None` below [`MIN_SAMPLES`] such rounds.
    pub fn paired_ratio<U>(&self, baseline: &Timings<U>) -> Option<Estimate> {
        let (b, t) = paired(&baseline.rounds, &self.rounds);
        let ratios: Vec<f64> = b.iter().zip(&t).filter(|(b, _)| **b > 0.0).map(|(b, t)| t / b).collect();
        median_estimate(&ratios).ok()
    }
}

/// The rounds in which both series counted, as two aligned series.
fn paired(baseline: &[Option<f64>], treatment: &[Option<f64>]) -> (Vec<f64>, Vec<f64>) {
    baseline.iter().zip(treatment).filter_map(|(b, t)| Some(((*b)?, (*t)?))).unzip()
}

/// When the rounds stop, past the protocol's fewest: once every
/// configuration's interval has a half-width of at most `target_ci` times
/// its median, at the protocol's most rounds, or (with `max_seconds`) after
/// the round that the next one would take past that many seconds of the
/// measurement.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interleaved {
    pub protocol: Protocol,
    pub target_ci: f64,
    pub max_seconds: Option<f64>,
}

impl Interleaved {
    /// Exactly `rounds` timed rounds after one warm-up round. Fewer than
    /// [`MIN_SAMPLES`] rounds are allowed (a quick look, a test at a tiny
    /// size) and give medians without intervals, which the reports say.
    pub fn fixed(rounds: u32, seed: u64) -> Result<Interleaved, ProtocolError> {
        if rounds == 0 {
            return Err(ProtocolError::NoRounds);
        }
        let protocol = Protocol { warm_up_rounds: 1, min_rounds: rounds, max_rounds: rounds, seed };
        Ok(Interleaved { protocol, target_ci: 0.0, max_seconds: None })
    }

    /// At least `min_rounds` (6 or more) and at most `max_rounds` timed rounds
    /// after `warm_up` untimed ones, stopping early once every interval is
    /// within `target_ci` of its median.
    pub fn adaptive(
        warm_up: u32,
        min_rounds: u32,
        max_rounds: u32,
        target_ci: f64,
        seed: u64,
    ) -> Result<Interleaved, ProtocolError> {
        Ok(Interleaved {
            protocol: Protocol::new(warm_up, min_rounds, max_rounds, seed)?,
            target_ci,
            max_seconds: None,
        })
    }

    /// These rounds within a time budget: past the fewest rounds (never
    /// before them), stop after the round whose duration, once more, would
    /// end past `minutes` since the measurement began. A budget that binds on
    /// a slow device (lavapipe) and not on a fast one, where the rounds end
    /// on their own first.
    pub fn within_minutes(self, minutes: f64) -> Result<Interleaved, ProtocolError> {
        if !(minutes.is_finite() && minutes > 0.0) {
            return Err(ProtocolError::NoTime);
        }
        Ok(Interleaved { max_seconds: Some(minutes * 60.0), ..self })
    }

    /// The most runs of one configuration (warm-up included): what a progress
    /// estimate should weigh a configuration by.
    pub fn most_runs(&self) -> u32 {
        self.protocol.warm_up_rounds + self.protocol.max_rounds
    }

    /// `run` with these rounds and their seed as inputs, so a result says how
    /// it was measured and the shuffles can be replayed.
    pub fn recorded_in(&self, run: RunInfo) -> RunInfo {
        let p = &self.protocol;
        let rounds = if p.min_rounds == p.max_rounds {
            format!("{} (after {} warm-up)", p.min_rounds, p.warm_up_rounds)
        } else {
            format!(
                "{}..={} until the 95 % intervals are within {} (after {} warm-up)",
                p.min_rounds, p.max_rounds, self.target_ci, p.warm_up_rounds
            )
        };
        let run = run.input("rounds", rounds).input("seed", p.seed);
        match self.max_seconds {
            Some(s) => run.input("time_budget", format!("{:.1} min (never before {} rounds)", s / 60.0, p.min_rounds)),
            None => run,
        }
    }

    /// Whether intervals can come out of these rounds.
    pub fn gives_intervals(&self) -> bool {
        self.protocol.min_rounds as usize >= MIN_SAMPLES
    }

    /// Measures `configurations` configurations as one step of `progress`
    /// labelled `label` (each round a message of its own): `measure(c, phase)`
    /// runs configuration `c` once. The first error ends the measurement.
    pub fn measure<T, E, W: Write>(
        &self,
        progress: &mut Progress<W>,
        label: &str,
        configurations: usize,
        measure: impl FnMut(usize, Phase) -> Result<Sample<T>, E>,
    ) -> Result<Vec<Timings<T>>, E>
    where
        E: From<ProtocolError>,
    {
        progress.start_step(label);
        let progress = RefCell::new(progress);
        let measured = self.measure_rounds(configurations, measure, |round| {
            progress.borrow_mut().message(&format!("{label}: round {round} of at most {}", self.protocol.max_rounds));
        });
        let progress = progress.into_inner();
        match &measured {
            Ok(_) => progress.finish_step(),
            Err(_) => progress.fail_step("error"),
        };
        measured
    }

    /// [`Interleaved::measure`] without a progress line; `after_round(n)` is
    /// told each round's number.
    pub fn measure_rounds<T, E>(
        &self,
        configurations: usize,
        measure: impl FnMut(usize, Phase) -> Result<Sample<T>, E>,
        after_round: impl FnMut(usize),
    ) -> Result<Vec<Timings<T>>, E>
    where
        E: From<ProtocolError>,
    {
        let start = std::time::Instant::now();
        self.measure_rounds_timed(configurations, measure, after_round, || start.elapsed().as_secs_f64())
    }

    /// [`Interleaved::measure_rounds`] on the clock `seconds` (seconds since
    /// the measurement began), which the time budget reads.
    fn measure_rounds_timed<T, E>(
        &self,
        configurations: usize,
        mut measure: impl FnMut(usize, Phase) -> Result<Sample<T>, E>,
        mut after_round: impl FnMut(usize),
        seconds: impl Fn() -> f64,
    ) -> Result<Vec<Timings<T>>, E>
    where
        E: From<ProtocolError>,
    {
        let round_began = std::cell::Cell::new(None);
        let rounds = self.protocol.run(
            configurations,
            |c, phase| {
                if phase == Phase::Timed && round_began.get().is_none() {
                    round_began.set(Some(seconds()));
                }
                let sample = measure(c, phase)?;
                Ok::<_, E>((sample.ms, sample.output))
            },
            |rounds| {
                after_round(rounds.count());
                let now = seconds();
                let last_round = now - round_began.take().unwrap_or(now);
                let out_of_time = self.max_seconds.is_some_and(|budget| now + last_round > budget);
                let precise = (0..configurations).all(|c| {
                    let samples: Vec<f64> = rounds.runs[c].iter().filter_map(|r| r.0).collect();
                    median_estimate(&samples).is_ok_and(|e| e.precise_to(self.target_ci, 0.0))
                });
                Ok(if precise || out_of_time { Next::Stop } else { Next::Continue })
            },
        )?;
        Ok(rounds
            .runs
            .into_iter()
            .map(|runs| {
                let mut rounds = Vec::with_capacity(runs.len());
                let mut last = None;
                for (ms, output) in runs {
                    rounds.push(ms);
                    last = Some(output);
                }
                Timings { rounds, last: last.expect("the protocol runs every configuration at least once") }
            })
            .collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bench::estimate::Verdict;

    #[derive(Debug, PartialEq)]
    enum Failure {
        Protocol(ProtocolError),
    }
    impl From<ProtocolError> for Failure {
        fn from(e: ProtocolError) -> Self {
            Failure::Protocol(e)
        }
    }

    /// Configuration `c` costs `work[c]` on a machine whose load grows by
    /// 2.5 % a round; run numbers (from 1) are the outputs.
    fn drifting(work: &'static [f64]) -> impl FnMut(usize, Phase) -> Result<Sample<usize>, Failure> {
        let mut t = 0usize;
        move |c, _| {
            let round = t / work.len();
            t += 1;
            Ok(Sample::timed(work[c] * (1.0 + round as f64 / 40.0), t))
        }
    }

    #[test]
    fn every_configuration_is_timed_every_round_with_its_last_output() {
        let m = Interleaved::fixed(8, 3).unwrap();
        let timings = m.measure_rounds(3, drifting(&[1.0, 2.0, 3.0]), |_| {}).unwrap();
        assert_eq!(timings.len(), 3);
        for t in &timings {
            assert_eq!((t.rounds.len(), t.left_out()), (8, 0));
        }
        // 3 warm-up runs and 24 timed ones; some configuration ran last.
        assert_eq!(timings.iter().map(|t| t.last).max(), Some(27));
        assert!(timings.iter().all(|t| t.estimate().is_some()));
    }

    #[test]
    fn a_paired_difference_finds_a_real_cost_and_an_a_a_control_within_noise() {
        let m = Interleaved::fixed(12, 7).unwrap();
        let timings = m.measure_rounds(3, drifting(&[10.0, 10.0, 11.0]), |_| {}).unwrap();
        let control = timings[1].paired_difference(&timings[0]).unwrap();
        assert_eq!(control.verdict(), Verdict::WithinNoise, "{control:?}");
        let cost = timings[2].paired_difference(&timings[0]).unwrap();
        assert_eq!(cost.verdict(), Verdict::Cost, "{cost:?}");
        let ratio = timings[2].paired_ratio(&timings[0]).unwrap();
        assert!((ratio.lo..=ratio.hi).contains(&1.1) && ratio.hi - ratio.lo < 1e-9, "{ratio:?}");
    }

    #[test]
    fn fewer_than_six_rounds_give_medians_without_intervals() {
        let m = Interleaved::fixed(2, 1).unwrap();
        assert!(!m.gives_intervals());
        let timings = m.measure_rounds(2, drifting(&[1.0, 2.0]), |_| {}).unwrap();
        assert!(timings[0].median().is_finite());
        assert_eq!(timings[0].estimate(), None);
        assert_eq!(timings[1].paired_difference(&timings[0]), None);
        assert_eq!(Interleaved::fixed(0, 1), Err(ProtocolError::NoRounds));
        assert!(ProtocolError::NoRounds.to_string().contains("use 1 or more"));
        assert!(Interleaved::adaptive(1, 5, 10, 0.1, 1).is_err(), "adaptive rounds need intervals");
    }

    #[test]
    fn the_rounds_and_seed_are_recorded_as_inputs() {
        let fixed = Interleaved::fixed(6, 42).unwrap().recorded_in(RunInfo::default());
        assert_eq!(fixed.inputs, [("rounds".into(), "6 (after 1 warm-up)".into()), ("seed".into(), "42".into())]);
        let adaptive = Interleaved::adaptive(1, 6, 20, 0.05, 7).unwrap().recorded_in(RunInfo::default());
        assert!(adaptive.inputs[0].1.starts_with("6..=20 until"), "{:?}", adaptive.inputs);
    }

    #[test]
    fn left_out_runs_are_not_paired() {
        let m = Interleaved::fixed(6, 1).unwrap();
        let mut n = 0;
        let timings = m
            .measure_rounds(
                2,
                |c, phase| {
                    // Configuration 1's second and fourth timed runs do not count.
                    if c == 1 && phase == Phase::Timed {
                        n += 1;
                        if n % 2 == 0 && n <= 4 {
                            return Ok::<_, Failure>(Sample::left_out(()));
                        }
                    }
                    Ok(Sample::timed(1.0, ()))
                },
                |_| {},
            )
            .unwrap();
        assert_eq!((timings[1].samples().len(), timings[1].left_out()), (4, 2));
        assert_eq!(timings[1].rounds[1], None);
        assert_eq!(timings[1].paired_difference(&timings[0]), None, "fewer than six rounds counted by both");
    }

    #[test]
    fn a_time_budget_stops_the_rounds_it_would_overrun_but_never_before_the_fewest() {
        // Every run takes a second on the fake clock; two configurations, so a round is 2 s.
        let run = |budget_minutes: f64, min: u32, max: u32| {
            let m = Interleaved::adaptive(1, min, max, 1e-9, 5).unwrap().within_minutes(budget_minutes).unwrap();
            let clock = std::cell::Cell::new(0.0);
            let timings = m
                .measure_rounds_timed(
                    2,
                    |c, _| {
                        clock.set(clock.get() + 1.0);
                        Ok::<_, Failure>(Sample::timed(1.0 + c as f64 + clock.get() * 1e-3, ()))
                    },
                    |_| {},
                    || clock.get(),
                )
                .unwrap();
            timings[0].rounds.len()
        };
        // 30 s: warm-up 2 s, then rounds end at 4, 6, ..., 28 s; after the one at 28 s the
        // next would end at 30 s (not past it), after the one at 30 s it would end past.
        assert_eq!(run(0.5, 6, 100), 14);
        assert_eq!(run(0.01, 6, 100), 6, "never before the fewest rounds");
        assert_eq!(run(10.0, 6, 20), 20, "a budget that does not bind leaves the most rounds");
        // Without a budget the same (never precise) rounds go to the most.
        let m = Interleaved::adaptive(1, 6, 20, 1e-9, 5).unwrap();
        assert_eq!(m.max_seconds, None);
        assert!(m.within_minutes(0.0).is_err() && m.within_minutes(f64::NAN).is_err());
        let recorded = m.within_minutes(2.0).unwrap().recorded_in(RunInfo::default());
        assert_eq!(recorded.inputs[2], ("time_budget".into(), "2.0 min (never before 6 rounds)".into()));
    }

    #[test]
    fn adaptive_rounds_stop_once_every_interval_is_narrow() {
        let m = Interleaved::adaptive(0, 6, 40, 0.05, 2).unwrap();
        let mut rounds = 0;
        let timings = m.measure_rounds(2, |_, _| Ok::<_, Failure>(Sample::timed(5.0, ())), |r| rounds = r).unwrap();
        assert_eq!((rounds, timings[0].rounds.len()), (6, 6), "identical times are precise at the fewest rounds");
        let wide = m.measure_rounds(2, drifting(&[1.0, 1.0]), |_| {}).unwrap();
        assert_eq!(wide[0].rounds.len(), 40, "a steady drift never gets within 5 %");
    }
}
