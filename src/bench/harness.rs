//! One configuration's repeats in a block: untimed warm-up runs (llvmpipe
//! compiles shader variants on first use), then `repeat` timed runs, reported
//! as their median with the output of the last timed run (its image and
//! profile). Only for what is not compared with anything else measured (`bench
//! stability`'s cells); configurations that are compared share the shuffled
//! rounds of [`Interleaved`](super::Interleaved). [`Sample`] is what one run
//! gives either way.

use super::estimate::median;
use super::estimate::{median_estimate, Estimate};

/// Why a harness cannot be made.
#[derive(Debug, PartialEq, Eq, thiserror::Error)]
pub enum HarnessError {
    #[error("0 timed runs measure nothing; use 1 or more")]
    NoRepeats,
}

/// What one run gives: its time (GPU ms from the profiler report), or none
/// where the run does not count (e.g. an update that came out as another kind),
/// and its output.
#[derive(Clone, Debug)]
pub struct Sample<T> {
    pub ms: Option<f64>,
    pub output: T,
}

impl<T> Sample<T> {
    pub fn timed(ms: f64, output: T) -> Self {
        Sample { ms: Some(ms), output }
    }

    /// A run that was not what was meant to be measured: left out of the statistics.
    pub fn left_out(output: T) -> Self {
        Sample { ms: None, output }
    }
}

/// The timed runs of one configuration.
#[derive(Clone, Debug)]
pub struct Measurement<T> {
    /// Times of the runs that counted, in run order.
    pub samples: Vec<f64>,
    /// Timed runs left out of `samples` (see [`Sample::left_out`]).
    pub left_out: usize,
    /// The output of the last timed run (counted or not).
    pub last: T,
}

impl<T> Measurement<T> {
    /// Median of the samples ([`median`]: for an even count the mean of the
    /// two middle values, the value of [`Self::estimate`]); NaN for none.
    pub fn median(&self) -> f64 {
        median(&self.samples)
    }

    /// The median with its 95 % interval; `None` below
    /// [`MIN_SAMPLES`](super::estimate::MIN_SAMPLES) samples.
    pub fn estimate(&self) -> Option<Estimate> {
        median_estimate(&self.samples).ok()
    }
}

/// Warm-up runs and timed repeats; at least one timed run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Harness {
    warm_up: u32,
    repeat: u32,
}

impl Harness {
    pub fn new(warm_up: u32, repeat: u32) -> Result<Harness, HarnessError> {
        if repeat == 0 {
            return Err(HarnessError::NoRepeats);
        }
        Ok(Harness { warm_up, repeat })
    }

    /// One timed run after `warm_up` untimed ones.
    pub fn once_after(warm_up: u32) -> Harness {
        Harness { warm_up, repeat: 1 }
    }

    pub fn repeat(&self) -> u32 {
        self.repeat
    }

    /// Runs `run` `warm_up` times untimed, then `repeat` times timed. The first
    /// error ends the measurement and is returned.
    pub fn measure<T, E>(&self, mut run: impl FnMut() -> Result<Sample<T>, E>) -> Result<Measurement<T>, E> {
        for _ in 0..self.warm_up {
            run()?;
        }
        let mut samples = Vec::with_capacity(self.repeat as usize);
        let mut left_out = 0;
        let mut last = None;
        for _ in 0..self.repeat {
            let sample = run()?;
            match sample.ms {
                Some(ms) => samples.push(ms),
                None => left_out += 1,
            }
            last = Some(sample.output);
        }
        let last = last.expect("Harness::new refuses 0 repeats");
        Ok(Measurement { samples, left_out, last })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Runs that give `times` in order (then keep giving the last one), counting calls.
    fn from(times: &[f64]) -> impl FnMut() -> Result<Sample<usize>, String> + '_ {
        let mut calls = 0;
        move || {
            let ms = times[calls.min(times.len() - 1)];
            calls += 1;
            Ok(Sample::timed(ms, calls))
        }
    }

    #[test]
    fn repeat_zero_is_refused() {
        assert_eq!(Harness::new(1, 0), Err(HarnessError::NoRepeats));
        assert!(Harness::new(0, 1).is_ok());
    }

    #[test]
    fn median_of_odd_and_even_counts() {
        let odd = Harness::new(0, 3).unwrap().measure(from(&[5.0, 1.0, 3.0])).unwrap();
        assert_eq!(odd.median(), 3.0);
        let even = Harness::new(0, 4).unwrap().measure(from(&[4.0, 1.0, 3.0, 2.0])).unwrap();
        assert_eq!(even.median(), 2.5, "the mean of the two middle values");
    }

    #[test]
    fn warm_up_runs_are_not_counted() {
        // Two warm-up runs of 100 ms, then 1, 2, 3.
        let m = Harness::new(2, 3).unwrap().measure(from(&[100.0, 100.0, 1.0, 2.0, 3.0])).unwrap();
        assert_eq!(m.samples, [1.0, 2.0, 3.0]);
        assert_eq!(m.last, 5, "the last output is the fifth call's");
    }

    #[test]
    fn six_samples_give_an_interval_five_do_not() {
        let five = Harness::new(0, 5).unwrap().measure(from(&[7.0, 2.5, 9.0, 4.0, 3.0])).unwrap();
        assert_eq!((five.median(), five.estimate()), (4.0, None));
        let six = Harness::new(0, 6).unwrap().measure(from(&[7.0, 2.5, 9.0, 4.0, 3.0, 5.0])).unwrap();
        let e = six.estimate().unwrap();
        assert!(e.lo <= six.median() && six.median() <= e.hi, "{e:?}");
        // The published estimate is the same median, on even counts too.
        assert_eq!(e.value, six.median());
        assert_eq!(six.median(), 4.5);
    }

    #[test]
    fn left_out_runs_are_counted_apart_and_the_last_output_is_kept() {
        let mut call = 0;
        let m = Harness::new(1, 4)
            .unwrap()
            .measure(|| {
                call += 1;
                Ok::<_, String>(if call % 2 == 0 { Sample::left_out(call) } else { Sample::timed(call as f64, call) })
            })
            .unwrap();
        assert_eq!(m.samples, [3.0, 5.0]);
        assert_eq!(m.left_out, 2);
        assert_eq!(m.last, 5);
        let none = Harness::new(0, 2).unwrap().measure(|| Ok::<_, String>(Sample::left_out(()))).unwrap();
        assert!(none.median().is_nan());
    }

    #[test]
    fn an_error_ends_the_measurement_and_is_returned() {
        let mut calls = 0;
        let result = Harness::new(1, 5).unwrap().measure(|| {
            calls += 1;
            if calls == 3 {
                Err(format!("device lost in run {calls}"))
            } else {
                Ok(Sample::timed(1.0, ()))
            }
        });
        assert_eq!(result.unwrap_err(), "device lost in run 3");
        assert_eq!(calls, 3, "no run after the failing one");
        let warm_up_fails = Harness::new(1, 5).unwrap().measure(|| Err::<Sample<()>, _>("warm-up"));
        assert_eq!(warm_up_fails.unwrap_err(), "warm-up");
    }
}
