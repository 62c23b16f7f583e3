//! Word from a long wait for the device: a submission that runs for seconds
//! (a tiny step, a big image on a CPU device) reports, while the host waits on
//! its fence, how long it has run and what it holds, so a long render shows
//! that it is alive. Off unless a caller (the command line) sets a reporter:
//! the wait is then sliced, which costs the device nothing.

use super::context::Context;
use super::error::{VkError, VkResultExt};
use crate::plural::count;
use ash::vk;
use std::time::{Duration, Instant};

/// One report on a submission still running.
#[derive(Clone, Copy, Debug)]
pub struct WaitReport<'a> {
    /// The submission's name (its debug label).
    pub name: &'a str,
    /// Since the host began to wait for it.
    pub elapsed: Duration,
    /// Dispatches and barriers recorded in it.
    pub dispatches: u32,
    pub barriers: u32,
}

impl WaitReport<'_> {
    /// A running submission as progress: "frame: 2 s on the device so far (402
    /// dispatches, 417 barriers)". How far it has got is not known (that would
    /// need timestamps inside the frame), so it says how long and how big.
    pub fn progress_line(&self) -> String {
        format!(
            "{}: {:.0} s on the device so far ({}, {})",
            self.name,
            self.elapsed.as_secs_f64(),
            count(self.dispatches, "dispatch", "dispatches"),
            count(self.barriers, "barrier", "barriers")
        )
    }
}

/// Reports after `after` of waiting, then every `every`.
pub struct WaitReporter {
    pub after: Duration,
    pub every: Duration,
    pub report: Box<dyn Fn(&WaitReport) + Send + Sync>,
}

/// Waits for `fence`, reporting through the context's reporter if it has one.
pub(super) fn wait_for_fence(ctx: &Context, fence: vk::Fence, report: WaitReport) -> Result<(), VkError> {
    let device = &ctx.device;
    let Some(reporter) = ctx.wait_reporter() else {
        // SAFETY: fence belongs to device and was submitted with work.
        return unsafe { device.wait_for_fences(&[fence], true, u64::MAX) }.call("vkWaitForFences");
    };
    let start = Instant::now();
    let slice = reporter.every.clamp(Duration::from_millis(1), Duration::from_millis(250));
    let mut next = reporter.after;
    loop {
        // SAFETY: as above; a timeout leaves the fence and the work untouched.
        match unsafe { device.wait_for_fences(&[fence], true, slice.as_nanos() as u64) } {
            Ok(()) => return Ok(()),
            Err(vk::Result::TIMEOUT) => {
                let elapsed = start.elapsed();
                if elapsed >= next {
                    (reporter.report)(&WaitReport { elapsed, ..report });
                    next = elapsed + reporter.every;
                }
            }
            Err(e) => return Err(e).call("vkWaitForFences"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_long_wait_reads_as_progress() {
        let r = WaitReport { name: "frame", elapsed: Duration::from_millis(2040), dispatches: 402, barriers: 417 };
        assert_eq!(r.progress_line(), "frame: 2 s on the device so far (402 dispatches, 417 barriers)");
        let one = WaitReport { dispatches: 1, barriers: 1, ..r };
        assert_eq!(one.progress_line(), "frame: 2 s on the device so far (1 dispatch, 1 barrier)");
    }
}
