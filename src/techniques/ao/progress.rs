//! Progress of the long preprocessing steps, with a time estimate, handed to a
//! caller-supplied callback (the CLI prints it on the terminal).

use std::time::{Duration, Instant};

/// One report: `fraction` of `step` done after `elapsed`.
#[derive(Clone, Debug, PartialEq)]
pub struct Progress<'a> {
    pub step: &'a str,
    pub fraction: f64,
    pub elapsed: Duration,
    /// Linear extrapolation of the time left; None before any progress.
    pub remaining: Option<Duration>,
}

impl Progress<'_> {
    /// `ao training  42.0 %  3.1 s (about 4.3 s left)`
    pub fn line(&self) -> String {
        let left = match self.remaining {
            Some(r) if self.fraction < 1.0 => format!(" (about {:.1} s left)", r.as_secs_f64()),
            _ => String::new(),
        };
        format!("{}  {:5.1} %  {:.1} s{left}", self.step, 100.0 * self.fraction, self.elapsed.as_secs_f64())
    }
}

/// Times one step and turns fractions into [`Progress`] reports.
pub struct StepClock {
    pub step: &'static str,
    started: Instant,
}

impl StepClock {
    pub fn start(step: &'static str) -> StepClock {
        StepClock { step, started: Instant::now() }
    }

    pub fn elapsed(&self) -> Duration {
        self.started.elapsed()
    }

    pub fn report(&self, fraction: f64) -> Progress<'static> {
        let fraction = fraction.clamp(0.0, 1.0);
        let elapsed = self.elapsed();
        let remaining = (fraction > 0.0).then(|| elapsed.mul_f64((1.0 - fraction) / fraction));
        Progress { step: self.step, fraction, elapsed, remaining }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn remaining_time_extrapolates_linearly() {
        let p = Progress { step: "x", fraction: 0.25, elapsed: Duration::from_secs(3), remaining: None };
        assert_eq!(p.line(), "x   25.0 %  3.0 s");
        let clock = StepClock::start("ao test");
        std::thread::sleep(Duration::from_millis(20));
        let r = clock.report(0.5);
        let (e, left) = (r.elapsed.as_secs_f64(), r.remaining.unwrap().as_secs_f64());
        assert!((left - e).abs() < 1e-9 && e >= 0.02, "{e} {left}");
        assert_eq!(clock.report(0.0).remaining, None);
    }
}
