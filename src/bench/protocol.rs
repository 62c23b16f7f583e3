//! The measurement protocol of every bench that reports a cost: warm-up, then
//! rounds in which every configuration runs once, in an order shuffled anew
//! each round (A B C, C A B, ... never A A A B B B), until every estimate is
//! as precise as asked or the rounds run out.
//!
//! Why: on a shared machine the time of a run moves 20-50 % with whatever
//! else runs. Blocks of one configuration after another turn that drift into
//! differences between configurations; shuffled rounds spread it over all of
//! them alike, and a difference taken round by round
//! ([`paired_difference`](super::estimate::paired_difference)) cancels what
//! one round did to all of its runs.

use super::estimate::MIN_SAMPLES;
use serde::Serialize;

/// Why a protocol cannot be made.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ProtocolError {
    #[error("0 timed rounds measure nothing; use 1 or more")]
    NoRounds,
    #[error("{} cannot give a 95 % interval of a median: use at least {needed}", crate::plural::count(*.min, "round", "rounds"))]
    TooFewRounds { min: u32, needed: usize },
    #[error("the most rounds ({max}) is below the fewest ({min})")]
    MaxBelowMin { min: u32, max: u32 },
    #[error("no configuration to measure")]
    NoConfigurations,
    #[error("a time budget must be a number of minutes above 0")]
    NoTime,
}

/// Warm-up, the fewest and most timed rounds, and the seed of the shuffles.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct Protocol {
    pub warm_up_rounds: u32,
    pub min_rounds: u32,
    pub max_rounds: u32,
    pub seed: u64,
}

/// Whether a run counts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Phase {
    /// Untimed: compiles shaders, fills caches; its result is dropped.
    WarmUp,
    Timed,
}

/// After a round: go on, or stop (the estimates are precise enough).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Next {
    Continue,
    Stop,
}

/// What the rounds measured: `runs[configuration][round]`, and each round's
/// order of configurations (recorded so a run can be inspected and repeated).
#[derive(Clone, Debug)]
pub struct Rounds<T> {
    pub runs: Vec<Vec<T>>,
    pub orders: Vec<Vec<usize>>,
}

impl<T> Rounds<T> {
    /// Timed rounds done.
    pub fn count(&self) -> usize {
        self.orders.len()
    }

    /// One number per round of `configuration`, in round order (paired with
    /// every other configuration's series by index).
    pub fn series(&self, configuration: usize, value: impl Fn(&T) -> f64) -> Vec<f64> {
        self.runs[configuration].iter().map(value).collect()
    }
}

impl Protocol {
    pub fn new(warm_up_rounds: u32, min_rounds: u32, max_rounds: u32, seed: u64) -> Result<Protocol, ProtocolError> {
        if (min_rounds as usize) < MIN_SAMPLES {
            return Err(ProtocolError::TooFewRounds { min: min_rounds, needed: MIN_SAMPLES });
        }
        if max_rounds < min_rounds {
            return Err(ProtocolError::MaxBelowMin { min: min_rounds, max: max_rounds });
        }
        Ok(Protocol { warm_up_rounds, min_rounds, max_rounds, seed })
    }

    /// A seed that differs from run to run (the time), for when none is given.
    pub fn seed_from_clock() -> u64 {
        std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map(|d| d.as_nanos() as u64).unwrap_or(1)
    }

    /// The warm-up rounds alone, each in its own shuffled order (from the
    /// seed, apart from the timed rounds' orders), for a caller that decides
    /// after them what its timed rounds hold; its timed rounds then run with
    /// `warm_up_rounds: 0`.
    pub fn warm_up<E>(&self, configurations: usize, mut measure: impl FnMut(usize) -> Result<(), E>) -> Result<(), E> {
        let mut shuffle = Shuffle::new(!self.seed);
        for _ in 0..self.warm_up_rounds {
            for c in shuffle.order(configurations) {
                measure(c)?;
            }
        }
        Ok(())
    }

    /// Runs `configurations` configurations: `warm_up_rounds` untimed rounds,
    /// then timed rounds until `after_round` says [`Next::Stop`] (asked from
    /// `min_rounds` on, and after every round so partial results can be
    /// written) or `max_rounds` are done. `measure(c, phase)` runs
    /// configuration `c` once. The first error ends the measurement.
    pub fn run<T, E>(
        &self,
        configurations: usize,
        mut measure: impl FnMut(usize, Phase) -> Result<T, E>,
        mut after_round: impl FnMut(&Rounds<T>) -> Result<Next, E>,
    ) -> Result<Rounds<T>, E>
    where
        E: From<ProtocolError>,
    {
        if configurations == 0 {
            return Err(ProtocolError::NoConfigurations.into());
        }
        let mut shuffle = Shuffle::new(self.seed);
        for _ in 0..self.warm_up_rounds {
            for c in shuffle.order(configurations) {
                measure(c, Phase::WarmUp)?;
            }
        }
        let mut rounds = Rounds { runs: (0..configurations).map(|_| Vec::new()).collect(), orders: Vec::new() };
        while rounds.count() < self.max_rounds as usize {
            let order = shuffle.order(configurations);
            for &c in &order {
                let run = measure(c, Phase::Timed)?;
                rounds.runs[c].push(run);
            }
            rounds.orders.push(order);
            let next = after_round(&rounds)?;
            if rounds.count() >= self.min_rounds as usize && next == Next::Stop {
                break;
            }
        }
        Ok(rounds)
    }
}

/// Fisher-Yates shuffles from splitmix64: small, seeded, the same order for the
/// same seed on every platform.
struct Shuffle {
    state: u64,
}

impl Shuffle {
    fn new(seed: u64) -> Shuffle {
        Shuffle { state: seed }
    }

    fn next(&mut self) -> u64 {
        self.state = self.state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    fn order(&mut self, n: usize) -> Vec<usize> {
        let mut order: Vec<usize> = (0..n).collect();
        for i in (1..n).rev() {
            let j = (self.next() % (i as u64 + 1)) as usize;
            order.swap(i, j);
        }
        order
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bench::estimate::{median_estimate, paired_difference, Verdict};

    #[derive(Debug, PartialEq)]
    enum Failure {
        Protocol(ProtocolError),
        Broken,
    }
    impl From<ProtocolError> for Failure {
        fn from(e: ProtocolError) -> Self {
            Failure::Protocol(e)
        }
    }

    #[test]
    fn too_few_rounds_are_refused() {
        assert_eq!(Protocol::new(1, 5, 10, 0), Err(ProtocolError::TooFewRounds { min: 5, needed: 6 }));
        assert_eq!(Protocol::new(1, 8, 7, 0), Err(ProtocolError::MaxBelowMin { min: 8, max: 7 }));
        let p = Protocol::new(0, 6, 6, 0).unwrap();
        let none = p.run(0, |_, _| Ok::<_, Failure>(()), |_| Ok(Next::Continue));
        assert_eq!(none.unwrap_err(), Failure::Protocol(ProtocolError::NoConfigurations));
    }

    #[test]
    fn rounds_are_shuffled_recorded_and_repeatable() {
        let p = Protocol::new(1, 8, 8, 42).unwrap();
        let mut calls = Vec::new();
        let rounds = p
            .run(
                4,
                |c, phase| {
                    calls.push((c, phase));
                    Ok::<_, Failure>(c)
                },
                |_| Ok(Next::Continue),
            )
            .unwrap();
        assert_eq!(rounds.count(), 8);
        assert_eq!(calls.len(), 4 * 9, "one warm-up round, then eight timed ones");
        assert!(
            calls[..4].iter().all(|&(_, p)| p == Phase::WarmUp) && calls[4..].iter().all(|&(_, p)| p == Phase::Timed)
        );
        for (r, order) in rounds.orders.iter().enumerate() {
            let mut sorted = order.clone();
            sorted.sort();
            assert_eq!(sorted, [0, 1, 2, 3], "round {r} runs every configuration once");
            let run: Vec<usize> = calls[4 * (r + 1)..4 * (r + 2)].iter().map(|&(c, _)| c).collect();
            assert_eq!(run, *order, "the recorded order is the order run");
        }
        let distinct: std::collections::BTreeSet<_> = rounds.orders.iter().collect();
        assert!(distinct.len() >= 4, "orders vary from round to round: {:?}", rounds.orders);
        assert!(rounds.runs.iter().enumerate().all(|(c, runs)| runs.iter().all(|&r| r == c)));
        let again = p.run(4, |c, _| Ok::<_, Failure>(c), |_| Ok(Next::Continue)).unwrap();
        assert_eq!(again.orders, rounds.orders, "the same seed gives the same orders");
        let other = Protocol { seed: 43, ..p }.run(4, |c, _| Ok::<_, Failure>(c), |_| Ok(Next::Continue)).unwrap();
        assert_ne!(other.orders, rounds.orders);
    }

    #[test]
    fn stops_when_asked_but_not_before_the_fewest_rounds() {
        let p = Protocol::new(0, 6, 50, 1).unwrap();
        let mut asked = 0;
        let rounds = p
            .run(
                2,
                |_, _| Ok::<_, Failure>(1.0),
                |r| {
                    asked += 1;
                    Ok(if r.count() >= 3 { Next::Stop } else { Next::Continue })
                },
            )
            .unwrap();
        assert_eq!((rounds.count(), asked), (6, 6), "asked after every round, stopped at the fewest");
        let capped = p.run(2, |_, _| Ok::<_, Failure>(1.0), |_| Ok(Next::Continue)).unwrap();
        assert_eq!(capped.count(), 50);
        let mut n = 0;
        let broken = p.run(
            2,
            |_, _| {
                n += 1;
                if n == 5 {
                    Err(Failure::Broken)
                } else {
                    Ok(1.0)
                }
            },
            |_| Ok(Next::Continue),
        );
        assert_eq!(broken.unwrap_err(), Failure::Broken);
    }

    /// A machine whose load drifts slowly over the whole measurement (up to
    /// +60 %) and jitters run to run: configuration 0 and 1 do the same work
    /// (an A/A control), 2 costs 3 % more.
    fn drifting_machine(seed: u64) -> impl FnMut(usize, Phase) -> Result<f64, Failure> {
        let mut t = 0.0f64;
        let mut shuffle = Shuffle::new(seed);
        move |c, _| {
            t += 1.0;
            let jitter = 1.0 + 0.01 * ((shuffle.next() >> 11) as f64 / (1u64 << 53) as f64 - 0.5);
            let load = 1.0 + 0.6 * (t / 120.0).min(1.0);
            let work = if c == 2 { 103.0 } else { 100.0 };
            Ok(work * load * jitter)
        }
    }

    #[test]
    fn interleaved_rounds_flag_the_a_a_control_within_noise_and_find_a_real_difference() {
        let p = Protocol::new(0, 30, 30, 9).unwrap();
        let rounds = p.run(3, drifting_machine(5), |_| Ok(Next::Continue)).unwrap();
        let series = |c| rounds.series(c, |&v| v);
        let control = paired_difference(&series(0), &series(1)).unwrap();
        assert_eq!(control.verdict(), Verdict::WithinNoise, "{control:?}");
        let real = paired_difference(&series(0), &series(2)).unwrap();
        assert_eq!(real.verdict(), Verdict::Cost, "{real:?}");
        // The same machine measured in blocks (A A A ... then B B B ...) makes
        // the drift a difference: the A/A control comes out as a cost.
        let mut machine = drifting_machine(5);
        let blocks: Vec<Vec<f64>> =
            (0..3).map(|c| (0..30).map(|_| machine(c, Phase::Timed).unwrap()).collect()).collect();
        let blocked = paired_difference(&blocks[0], &blocks[1]).unwrap();
        assert_eq!(blocked.verdict(), Verdict::Cost, "blocks turn drift into cost: {blocked:?}");
        assert!(median_estimate(&series(0)).is_ok());
    }
}
