//! The measuring loop every bench shares: untimed warm-up runs (llvmpipe
//! compiles shader variants on first use), then `repeat` timed runs, reported
//! as their median, minimum and maximum with the output of the last timed run
//! (its image and profile).

use super::estimate::{median_estimate, Estimate};
use super::progress::Progress;
use super::stats::median;
use std::io::Write;

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
    /// Median of the samples (upper median for an even count); NaN for none.
    pub fn median(&self) -> f64 {
        median(&self.samples)
    }

    /// The median with its 95 % interval; `None` below
    /// [`MIN_SAMPLES`](super::estimate::MIN_SAMPLES) samples.
    pub fn estimate(&self) -> Option<Estimate> {
        median_estimate(&self.samples).ok()
    }

    /// NaN for no samples.
    pub fn min(&self) -> f64 {
        self.samples.iter().copied().fold(f64::NAN, f64::min)
    }

    /// NaN for no samples.
    pub fn max(&self) -> f64 {
        self.samples.iter().copied().fold(f64::NAN, f64::max)
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

    /// The same repeats after `warm_up` untimed runs.
    pub fn with_warm_up(self, warm_up: u32) -> Harness {
        Harness { warm_up, ..self }
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

    /// [`Harness::measure`] as one step of `progress`, labelled `label`.
    pub fn measure_step<T, E, W: Write>(
        &self,
        progress: &mut Progress<W>,
        label: &str,
        run: impl FnMut() -> Result<Sample<T>, E>,
    ) -> Result<Measurement<T>, E> {
        progress.start_step(label);
        let measured = self.measure(run);
        match &measured {
            Ok(_) => progress.finish_step(),
            Err(_) => progress.fail_step("error"),
        };
        measured
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
        assert_eq!(even.median(), 3.0, "upper median, as every bench reported it");
    }

    #[test]
    fn warm_up_runs_are_not_counted() {
        // Two warm-up runs of 100 ms, then 1, 2, 3.
        let m = Harness::new(2, 3).unwrap().measure(from(&[100.0, 100.0, 1.0, 2.0, 3.0])).unwrap();
        assert_eq!(m.samples, [1.0, 2.0, 3.0]);
        assert_eq!(m.last, 5, "the last output is the fifth call's");
        assert_eq!((m.min(), m.max()), (1.0, 3.0));
    }

    #[test]
    fn min_and_max_of_the_samples() {
        let m = Harness::new(0, 5).unwrap().measure(from(&[7.0, 2.5, 9.0, 4.0, 3.0])).unwrap();
        assert_eq!((m.min(), m.median(), m.max()), (2.5, 4.0, 9.0));
        assert_eq!(m.estimate(), None, "five samples give no 95 % interval");
        let six = Harness::new(0, 6).unwrap().measure(from(&[7.0, 2.5, 9.0, 4.0, 3.0, 5.0])).unwrap();
        let e = six.estimate().unwrap();
        assert!(e.lo <= six.median() && six.median() <= e.hi, "{e:?}");
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
        assert!(none.median().is_nan() && none.min().is_nan() && none.max().is_nan());
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

    #[test]
    fn a_measured_step_is_reported_as_done_or_failed() {
        let mut out = Vec::new();
        {
            let mut progress = Progress::with_writer(2, &mut out, false);
            let harness = Harness::new(0, 2).unwrap();
            harness.measure_step(&mut progress, "first", from(&[1.0])).unwrap();
            let failed = harness.measure_step(&mut progress, "second", || Err::<Sample<()>, _>("broken"));
            assert!(failed.is_err());
        }
        let text = String::from_utf8(out).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert!(lines[0].starts_with("[1/2] first ..."), "{text}");
        assert!(lines[1].starts_with("[2/2] second ... failed"), "{text}");
    }
}
