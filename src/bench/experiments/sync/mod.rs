//! The synchronization study (`sweeplab bench sync`): what a line boundary of
//! the IPSVI sweep costs under each way of synchronizing it, told apart into
//! quantities that each answer one question and are never joined into one
//! interval:
//!
//! - **(a) the fixed cost** of a boundary: what the primitive adds with
//!   nothing in flight, from the `empty` workload (shaders that return at
//!   once): the slope of frame time over the number of line blocks (the line
//!   width varies, the work does not), minus the no-barriers slope;
//! - **(b) the serialization** a strategy imposes on the sweep: frame time with
//!   it minus frame time without it, per line boundary, from the `sweep`
//!   workload's frames without per-line timestamps (on a GPU the lines of a
//!   frame without barriers overlap, with one they cannot);
//! - **(c) the per-line timestamps' own effect**: the baseline's frame with a
//!   timestamp around every line minus without, and whether the timestamps
//!   serialize the lines on this device (then per-line timings show lines one
//!   after another, never their overlap);
//! - **the calibration** (`chain` workload): per line a dependent chain of a
//!   known number of steps, its latency measured alone; per strategy a fitted
//!   line, time per boundary = fixed cost + serialized fraction x chain latency.
//!
//! Every workload runs in shuffled rounds (A B C, C A B), every estimate is a
//! median or a paired shift with its 95 % interval, and the baseline runs
//! twice (`no-barriers`, `no-barriers-again`): an A/A control whose difference
//! must read within noise. Each strategy's timeline is written once per
//! workload as a Perfetto trace (`trace_<workload>_<strategy>.json`).
//!
//! The files: [`plan`] (what to measure), [`run`] (the rounds), [`lines`] and
//! [`chain`] (what a configuration renders), [`budget`] (fitting the fewest
//! rounds into the time), [`report`] (what is kept), [`estimates`] and
//! [`calibration`] (the quantities), [`verdict`] (the answer in words),
//! [`files`], [`traces`], [`compare`] and [`progress`] (the outputs).

pub mod budget;
pub mod calibration;
pub mod chain;
pub mod chain_plan;
pub mod compare;
pub mod estimates;
mod experiment;
pub mod files;
mod lines;
pub mod options;
pub mod plan;
pub mod progress;
pub mod report;
mod run;
pub mod traces;
pub mod verdict;

pub use budget::LeftOut;
pub use experiment::SyncExperiment;
pub use options::SyncOptions;
pub use plan::{check, configurations, Precision, SyncPlan, MIN_RUN};
pub use report::{ConfigRow, StrategyRow, SyncReport, WorkloadRounds};
pub use run::{run, Eta, SyncObserver};

use crate::techniques::ipsvi::{BreakdownStep, SyncStrategy};
use serde::{Deserialize, Serialize};

/// What each line dispatch does.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Workload {
    /// The scene's IPSVI frame.
    Sweep,
    /// Every invocation returns at once: dispatches and sync alone.
    Empty,
    /// The calibration: per line a dependent chain of known length.
    Chain,
}

impl Workload {
    /// Every workload, in the order reports list them.
    pub const ALL: [Workload; 3] = [Workload::Empty, Workload::Sweep, Workload::Chain];

    pub fn name(self) -> &'static str {
        match self {
            Workload::Sweep => "sweep",
            Workload::Empty => "empty",
            Workload::Chain => "chain",
        }
    }

    /// The IPSVI line shader's step of the workload (the chain has its own shader).
    pub(crate) fn breakdown_step(self) -> BreakdownStep {
        match self {
            Workload::Sweep | Workload::Chain => BreakdownStep::Full,
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
            .ok_or_else(|| format!("unknown workload {s:?}; known: empty, sweep, chain"))
    }
}

/// One arm of the study: the baseline, its A/A copy, a strategy, or (in the
/// chain workload) one line alone, which measures the chain's own latency.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Arm {
    NoBarriers,
    NoBarriersAgain,
    Strategy(SyncStrategy),
    Alone,
}

/// The baseline's name in every output.
pub const BASELINE: &str = "no-barriers";
/// The A/A control's name.
pub const CONTROL: &str = "no-barriers-again";
/// The chain workload's frames of one line.
pub const ALONE: &str = "alone";
/// The run input naming the IPSVI line kernel of the sweep's and the empty
/// workload's lines as it ran (`serial`, `segmented x32`); absent from
/// older records, every one of which ran the serial kernel.
pub const LINE_KERNEL_INPUT: &str = "line_kernel";

impl Arm {
    pub fn name(self) -> &'static str {
        match self {
            Arm::NoBarriers => BASELINE,
            Arm::NoBarriersAgain => CONTROL,
            Arm::Strategy(s) => s.name(),
            Arm::Alone => ALONE,
        }
    }

    /// The arm a report's row names.
    pub fn from_name(name: &str) -> Option<Arm> {
        match name {
            BASELINE => Some(Arm::NoBarriers),
            CONTROL => Some(Arm::NoBarriersAgain),
            ALONE => Some(Arm::Alone),
            other => other.parse::<SyncStrategy>().ok().filter(|s| !s.is_racy()).map(Arm::Strategy),
        }
    }

    pub(crate) fn sync(self) -> SyncStrategy {
        match self {
            Arm::NoBarriers | Arm::NoBarriersAgain | Arm::Alone => SyncStrategy::Racy,
            Arm::Strategy(s) => s,
        }
    }

    /// Whether consecutive lines run unsynchronized (one line alone has no
    /// boundary to race across).
    pub fn racy(self) -> bool {
        self != Arm::Alone && self.sync().is_racy()
    }
}

/// A configuration: workload, arm, line width, whether its frames carry
/// per-line timestamps, and (chain workload) each line's chain length.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ConfigKey {
    pub workload: Workload,
    pub arm: Arm,
    pub line_width: u32,
    pub line_timestamps: bool,
    /// Loop trips of each line's chain (chain workload; 0 elsewhere).
    pub chain_trips: u32,
}

impl ConfigKey {
    /// A frame of the sweep or empty workload.
    pub fn lines(workload: Workload, arm: Arm, line_width: u32, line_timestamps: bool) -> ConfigKey {
        ConfigKey { workload, arm, line_width, line_timestamps, chain_trips: 0 }
    }

    /// Whether its frames leave lines unsynchronized (hazards expected,
    /// images undefined).
    pub fn racy(&self) -> bool {
        self.arm.racy()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arms_and_workloads_read_back_from_their_names() {
        for arm in [Arm::NoBarriers, Arm::NoBarriersAgain, Arm::Alone, Arm::Strategy(SyncStrategy::Events)] {
            assert_eq!(Arm::from_name(arm.name()), Some(arm));
        }
        assert_eq!(Arm::from_name("racy"), None, "the baseline is named no-barriers");
        for w in Workload::ALL {
            assert_eq!(w.name().parse::<Workload>(), Ok(w));
        }
        assert!(!Arm::Alone.racy() && Arm::NoBarriers.racy() && !Arm::Strategy(SyncStrategy::Submits).racy());
    }
}
