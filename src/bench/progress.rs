//! A progress line on stderr for long sweeps:
//! `[ 3/40] line_width=4 cache=256 ... 1.2 s (eta 45 s)`.
//!
//! Steps may differ in size (a 512x512 frame costs four 256x256 ones): each
//! step has a weight, and the time left is the time per unit of weight so far
//! times the weight left, so a sweep whose large steps come last is not
//! promised an early end.
//!
//! On a terminal the line is redrawn in place; otherwise (logs, CI, pipes)
//! every step gets its own line, so the log shows every run and its time.
//! Own code rather than `indicatif`: one line of text and an average is all a
//! sweep needs, and it keeps the dependency tree and compile time small.

use std::io::{self, IsTerminal, Write};
use std::time::{Duration, Instant};

/// Labels longer than this are cut on terminals, so the line never wraps
/// (a wrapped line cannot be redrawn in place).
const MAX_LABEL_ON_TERMINAL: usize = 60;

/// Reports progress through a sweep of `total` steps. Output errors are
/// ignored: a closed stderr must not abort a benchmark.
pub struct Progress<W: Write = io::Stderr> {
    out: W,
    redraw: bool,
    total: usize,
    /// One weight per step, in the order the steps run.
    weights: Vec<f64>,
    finished_steps: usize,
    sweep_started: Instant,
    time_in_steps: Duration,
    current: Option<CurrentStep>,
    line_open: bool,
}

struct CurrentStep {
    prefix: String,
    started: Instant,
}

impl Progress<io::Stderr> {
    /// Progress on stderr, redrawn in place only when stderr is a terminal.
    pub fn new(total: usize) -> Self {
        Progress::weighted(vec![1.0; total])
    }

    /// Progress on stderr through steps of the given weights (e.g. pixels x
    /// repeats), one per step in the order they run.
    pub fn weighted(weights: Vec<f64>) -> Self {
        let out = io::stderr();
        let redraw = out.is_terminal();
        Progress::weighted_with_writer(weights, out, redraw)
    }
}

impl<W: Write> Progress<W> {
    /// Progress on any writer; `redraw` chooses one line redrawn in place
    /// (terminals) over one line per step.
    pub fn with_writer(total: usize, out: W, redraw: bool) -> Self {
        Progress::weighted_with_writer(vec![1.0; total], out, redraw)
    }

    /// [`Progress::weighted`] on any writer. A weight that is not a positive
    /// number counts as 1, so a bad estimate cannot stop the time left.
    pub fn weighted_with_writer(weights: Vec<f64>, out: W, redraw: bool) -> Self {
        let weights: Vec<f64> = weights.into_iter().map(|w| if w.is_finite() && w > 0.0 { w } else { 1.0 }).collect();
        Progress {
            out,
            redraw,
            total: weights.len(),
            weights,
            finished_steps: 0,
            sweep_started: Instant::now(),
            time_in_steps: Duration::ZERO,
            current: None,
            line_open: false,
        }
    }

    /// Announces the next step, e.g. `start_step("line_width=4 cache=256")`.
    /// A step still open is finished first.
    pub fn start_step(&mut self, label: &str) {
        if self.current.is_some() {
            self.finish_step();
        }
        let label = if self.redraw { shorten(label, MAX_LABEL_ON_TERMINAL) } else { label.to_owned() };
        let prefix = format!("{} {label} ...", step_counter(self.finished_steps + 1, self.total));
        self.begin_line();
        self.write(&prefix);
        self.line_open = true;
        self.current = Some(CurrentStep { prefix, started: Instant::now() });
    }

    /// Ends the current step successfully and returns how long it took.
    pub fn finish_step(&mut self) -> Duration {
        self.end_step(None)
    }

    /// Ends the current step as failed; the sweep goes on.
    pub fn fail_step(&mut self, reason: &str) -> Duration {
        self.end_step(Some(reason))
    }

    /// Prints a line of its own without breaking the progress line.
    pub fn message(&mut self, text: &str) {
        self.begin_line();
        self.write(text);
        self.write("\n");
        self.line_open = false;
        if let Some(prefix) = self.current.as_ref().map(|c| c.prefix.clone()) {
            self.write(&prefix);
            self.line_open = true;
        }
    }

    /// Ends the sweep with a summary line.
    pub fn finish(&mut self) {
        if self.current.is_some() {
            self.finish_step();
        }
        self.close_line();
        let summary = format!(
            "{}/{} steps in {}\n",
            self.finished_steps,
            self.total,
            format_duration(self.sweep_started.elapsed())
        );
        self.write(&summary);
    }

    fn end_step(&mut self, failure: Option<&str>) -> Duration {
        let Some(step) = self.current.take() else {
            return Duration::ZERO;
        };
        let took = step.started.elapsed();
        self.finished_steps += 1;
        self.time_in_steps += took;
        let mut outcome = match failure {
            None => format_duration(took),
            Some(reason) => format!("failed after {}: {reason}", format_duration(took)),
        };
        if let Some(eta) = remaining_time(self.time_in_steps, &self.weights, self.finished_steps) {
            outcome.push_str(&format!(" (eta {})", format_duration(eta)));
        }
        if self.redraw {
            self.write("\r\x1b[2K");
            self.write(&format!("{} {outcome}", step.prefix));
            // Stays visible until the next step redraws the line.
            self.line_open = true;
        } else {
            // Complete the step's line when nothing was printed since it began.
            if !self.line_open {
                self.write(&step.prefix);
            }
            self.write(&format!(" {outcome}\n"));
            self.line_open = false;
        }
        took
    }

    /// Gets ready to write a line from its start: clears the line on a
    /// terminal, or ends an open line elsewhere.
    fn begin_line(&mut self) {
        if self.redraw {
            self.write("\r\x1b[2K");
        } else {
            self.close_line();
        }
    }

    fn close_line(&mut self) {
        if self.line_open {
            self.write("\n");
            self.line_open = false;
        }
    }

    fn write(&mut self, text: &str) {
        let _ = self.out.write_all(text.as_bytes());
        let _ = self.out.flush();
    }
}

impl<W: Write> Drop for Progress<W> {
    /// Leaves the cursor on a fresh line, e.g. when a sweep ends by an error.
    fn drop(&mut self) {
        self.close_line();
    }
}

/// `[ 3/40]`: the step number padded to the width of the total.
fn step_counter(step: usize, total: usize) -> String {
    let width = total.to_string().len();
    format!("[{step:>width$}/{total}]")
}

/// The time per unit of weight so far times the weight of the steps left;
/// `None` when nothing was measured yet or nothing is left. Steps run past the
/// planned count weigh nothing.
fn remaining_time(time_in_steps: Duration, weights: &[f64], finished: usize) -> Option<Duration> {
    if finished == 0 || finished >= weights.len() {
        return None;
    }
    let (done, left) = weights.split_at(finished);
    let per_weight = time_in_steps.as_secs_f64() / done.iter().sum::<f64>();
    Duration::try_from_secs_f64(per_weight * left.iter().sum::<f64>()).ok()
}

/// Durations as a person reads them: "340 ms", "1.2 s", "45 s", "3 m 05 s", "1 h 02 m".
pub fn format_duration(duration: Duration) -> String {
    let seconds = duration.as_secs_f64();
    if seconds < 1.0 {
        return format!("{} ms", duration.as_millis());
    }
    if seconds < 10.0 {
        return format!("{seconds:.1} s");
    }
    let whole = seconds.round() as u64;
    if whole < 60 {
        format!("{whole} s")
    } else if whole < 3600 {
        format!("{} m {:02} s", whole / 60, whole % 60)
    } else {
        format!("{} h {:02} m", whole / 3600, (whole % 3600) / 60)
    }
}

fn shorten(text: &str, max_chars: usize) -> String {
    if text.chars().count() <= max_chars {
        return text.to_owned();
    }
    let mut short: String = text.chars().take(max_chars.saturating_sub(2)).collect();
    short.push_str("..");
    short
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counter_pads_the_step_to_the_width_of_the_total() {
        assert_eq!(step_counter(3, 40), "[ 3/40]");
        assert_eq!(step_counter(12, 40), "[12/40]");
        assert_eq!(step_counter(1, 5), "[1/5]");
    }

    #[test]
    fn eta_is_the_mean_step_time_times_the_steps_left() {
        let equal = [1.0; 6];
        let eta = remaining_time(Duration::from_secs(10), &equal, 2);
        assert_eq!(eta, Some(Duration::from_secs(20)));
        assert_eq!(remaining_time(Duration::from_secs(10), &equal, 6), None);
        assert_eq!(remaining_time(Duration::ZERO, &equal, 0), None);
        assert_eq!(remaining_time(Duration::from_secs(1), &equal, 7), None);
    }

    #[test]
    fn eta_weighs_the_steps_left_by_their_size() {
        // Two 256x256 steps took 2 s; two 512x512 steps (four times the
        // pixels) are left: 8 s, not the 2 s a per-step mean would say.
        let weights = [1.0, 1.0, 4.0, 4.0];
        assert_eq!(remaining_time(Duration::from_secs(2), &weights, 2), Some(Duration::from_secs(8)));
        // Large steps first: the small ones left are quick.
        let weights = [4.0, 4.0, 1.0, 1.0];
        assert_eq!(remaining_time(Duration::from_secs(8), &weights, 2), Some(Duration::from_secs(2)));
    }

    #[test]
    fn a_weighted_sweep_prints_the_weighted_eta() {
        let mut out = Vec::new();
        {
            let mut progress = Progress::weighted_with_writer(vec![1.0, 3.0, f64::NAN], &mut out, false);
            progress.start_step("small");
            std::thread::sleep(Duration::from_millis(20));
            progress.finish_step();
            progress.finish();
        }
        let text = String::from_utf8(out).unwrap();
        let first = text.lines().next().unwrap();
        // Weight 1 done; weight 3 + 1 (NaN counts as 1) left: four times the step.
        let ms = |text: &str| -> f64 { text.trim().trim_end_matches(" ms").parse().unwrap() };
        let (took, eta) = first.split_once("... ").unwrap().1.split_once(" (eta ").unwrap();
        let (took, eta) = (ms(took), ms(eta.trim_end_matches(')')));
        assert!(took >= 20.0 && (eta - 4.0 * took).abs() <= 4.0, "{first}");
        assert!(text.contains("1/3 steps"), "{text}");
    }

    #[test]
    fn durations_read_naturally() {
        assert_eq!(format_duration(Duration::from_millis(340)), "340 ms");
        assert_eq!(format_duration(Duration::from_millis(1234)), "1.2 s");
        assert_eq!(format_duration(Duration::from_secs(45)), "45 s");
        assert_eq!(format_duration(Duration::from_secs(185)), "3 m 05 s");
        assert_eq!(format_duration(Duration::from_secs(3720)), "1 h 02 m");
    }

    #[test]
    fn long_labels_are_cut() {
        assert_eq!(shorten("abcdef", 4), "ab..");
        assert_eq!(shorten("abc", 4), "abc");
    }
}
