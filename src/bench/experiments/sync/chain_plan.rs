//! How long the chain workload's chains are, and how many lines a frame holds:
//! chain latencies from zero to several times a sweep line's latency (what
//! the sweep workload measured just before), in loop trips from the time one
//! trip takes (probed on the device before the rounds), reduced where the
//! fewest rounds would not fit the time the budget leaves.

use super::{Arm, ConfigKey, Workload};
use serde::{Deserialize, Serialize};

/// Chain latencies, as multiples of a sweep line's latency.
pub const LATENCY_MULTIPLES: [f64; 5] = [0.0, 0.5, 1.0, 2.0, 4.0];
/// Lines per frame: enough that a frame's first line and its set-up are a
/// small part of it, few enough that lavapipe's frames stay short.
pub const LINES: u32 = 16;
/// A sweep line's latency where no sweep ran before the chain, us.
pub const DEFAULT_LINE_LATENCY_US: f64 = 200.0;
/// lavapipe ends an invocation after 65,535 loop iterations; a trip is one.
pub const MAX_TRIPS: u32 = 65_535;

/// What the chain workload measured with, recorded in the report.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ChainSetup {
    /// Lines per frame (one boundary fewer).
    pub lines: u32,
    /// Invocations per line (the image width, rounded up to the workgroup).
    pub invocations: u32,
    /// Dependent fused multiply-adds per loop trip.
    pub steps_per_trip: u32,
    /// Each configuration's loop trips per line, ascending (0 first).
    pub trips: Vec<u32>,
    /// The sweep line latency the lengths were planned from, us, and where it came from.
    pub line_latency_us: f64,
    pub line_latency_from: String,
    /// One trip's time, as probed before the rounds, ns.
    pub trip_ns: f64,
    /// The largest chain latency planned, as a multiple of the line latency.
    pub max_multiple: f64,
    /// What was cut to fit the time budget, if anything.
    pub reduced: Option<String>,
}

/// The trips of each latency multiple up to `max_multiple`, distinct,
/// ascending. Where the longest would pass [`MAX_TRIPS`], every length keeps
/// its share of the longest and the longest is the cap (the verdict names the
/// line latencies reached).
pub fn trips_for(line_latency_us: f64, trip_ns: f64, max_multiple: f64) -> Vec<u32> {
    let longest = (max_multiple * line_latency_us * 1e3 / trip_ns.max(1e-3)).min(MAX_TRIPS as f64);
    let mut trips: Vec<u32> = LATENCY_MULTIPLES
        .iter()
        .filter(|&&m| m <= max_multiple + 1e-9)
        .map(|&m| if m == 0.0 { 0 } else { ((m / max_multiple * longest).round() as u32).clamp(1, MAX_TRIPS) })
        .collect();
    trips.dedup();
    trips
}

/// The predicted time of one round: every arm's frame of `lines` lines and
/// one line alone, at each trip count; `dispatch_us` is one line with no chain.
pub fn round_seconds(trips: &[u32], trip_ns: f64, dispatch_us: f64, arms: usize, lines: u32) -> f64 {
    trips
        .iter()
        .map(|&t| {
            let line_s = (t as f64 * trip_ns * 1e-9) + dispatch_us * 1e-6;
            line_s * (arms as f64 * lines as f64 + 1.0)
        })
        .sum()
}

/// The lines and largest multiple to measure with: the first of a list of
/// ever cheaper choices whose warm-up and fewest rounds fit `time_left_s`
/// (the cheapest where none does), and what was cut.
pub fn fit(
    line_latency_us: f64,
    trip_ns: f64,
    dispatch_us: f64,
    arms: usize,
    rounds: u32,
    time_left_s: f64,
) -> (u32, f64, Option<String>) {
    let choices = [(LINES, 4.0), (8, 4.0), (8, 2.0), (4, 2.0), (4, 1.0)];
    let cost = |&(lines, multiple): &(u32, f64)| {
        let trips = trips_for(line_latency_us, trip_ns, multiple);
        (rounds as f64 + 1.0) * round_seconds(&trips, trip_ns, dispatch_us, arms, lines)
    };
    let chosen = choices.iter().find(|c| cost(c) <= time_left_s).unwrap_or(&choices[choices.len() - 1]);
    let reduced = (*chosen != choices[0]).then(|| {
        format!(
            "{} lines per frame and chains up to {} line latencies (planned: {} and {}) to fit the time budget: \
             {rounds} rounds of the planned chains take about {:.1} min, {:.1} min were left",
            chosen.0,
            chosen.1,
            choices[0].0,
            choices[0].1,
            cost(&choices[0]) / 60.0,
            time_left_s / 60.0
        )
    });
    (chosen.0, chosen.1, reduced)
}

/// The chain workload's configurations: the baseline, each strategy and one
/// line alone, at every trip count.
pub fn configurations(arms: &[Arm], trips: &[u32]) -> Vec<ConfigKey> {
    let mut keys = Vec::new();
    for arm in arms.iter().copied().filter(|a| *a != Arm::NoBarriersAgain).chain([Arm::Alone]) {
        for &chain_trips in trips {
            keys.push(ConfigKey { workload: Workload::Chain, arm, line_width: 1, line_timestamps: false, chain_trips });
        }
    }
    keys
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::techniques::ipsvi::SyncStrategy;

    #[test]
    fn chains_reach_four_line_latencies_within_lavapipes_loop_cap() {
        // A 140 us line (the H200's sweep) and 130 ns a trip.
        let trips = trips_for(140.0, 130.0, 4.0);
        assert_eq!(trips.len(), LATENCY_MULTIPLES.len());
        assert_eq!(trips[0], 0);
        assert!((trips[4] as f64 * 130e-3 - 560.0).abs() < 1.0, "{trips:?}");
        // lavapipe's 15 ms lines at 1.4 us a trip would need 43,000 trips: under the cap.
        assert!(trips_for(15_000.0, 1_400.0, 4.0).iter().all(|&t| t <= MAX_TRIPS));
        // Past the cap, the lengths keep their shares of the longest.
        let capped = trips_for(1e6, 1.0, 4.0);
        assert_eq!(capped, [0, 8192, 16384, 32768, MAX_TRIPS], "{capped:?}");
        assert_eq!(trips_for(0.001, 1e6, 4.0), [0, 1], "lengths that coincide are measured once");
    }

    #[test]
    fn the_chain_shrinks_to_fit_the_time_left() {
        let (lines, multiple, reduced) = fit(140.0, 130.0, 3.0, 6, 6, 60.0);
        assert_eq!((lines, multiple, reduced), (LINES, 4.0, None), "a GPU's chains take a second");
        let full = 7.0 * round_seconds(&trips_for(15_000.0, 1_400.0, 4.0), 1_400.0, 40.0, 6, LINES);
        let (lines, multiple, reduced) = fit(15_000.0, 1_400.0, 40.0, 6, 6, full / 2.0);
        assert!(lines < LINES || multiple < 4.0, "{lines} {multiple}");
        assert!(reduced.unwrap().contains("to fit the time budget"));
        let (lines, multiple, _) = fit(15_000.0, 1_400.0, 40.0, 6, 6, 0.0);
        assert_eq!((lines, multiple), (4, 1.0), "the cheapest where nothing fits");
    }

    #[test]
    fn every_arm_and_one_line_alone_at_every_length() {
        let arms = [Arm::NoBarriers, Arm::NoBarriersAgain, Arm::Strategy(SyncStrategy::BarrierGlobal)];
        let keys = configurations(&arms, &[0, 10, 20]);
        assert_eq!(keys.len(), 3 * 3, "no control in the chain: baseline, strategy, alone");
        assert!(keys.iter().any(|k| k.arm == Arm::Alone && k.chain_trips == 20));
        assert!(keys.iter().all(|k| k.workload == Workload::Chain && !k.line_timestamps));
    }
}
