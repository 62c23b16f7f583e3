//! The process's CPU time (all threads, user + system), to put beside GPU
//! time: on lavapipe the "GPU" is the host's cores, and CPU time moves less
//! than elapsed time when other processes share them.

use std::time::Duration;

/// CPU time used by this process so far, with nanosecond resolution where the
/// kernel keeps it (Linux does); `None` where the clock is unavailable.
pub fn process_cpu_time() -> Option<Duration> {
    let mut ts = libc::timespec { tv_sec: 0, tv_nsec: 0 };
    // SAFETY: `ts` is a valid, writable timespec; clock_gettime writes only it
    // and reports failure through its return value.
    let rc = unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut ts) };
    (rc == 0).then(|| Duration::new(ts.tv_sec as u64, ts.tv_nsec as u32))
}

/// Milliseconds of CPU time between two readings (NaN where either is missing).
pub fn cpu_ms_between(start: Option<Duration>, end: Option<Duration>) -> f64 {
    match (start, end) {
        (Some(a), Some(b)) => b.saturating_sub(a).as_secs_f64() * 1e3,
        _ => f64::NAN,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn thread_cpu_time() -> Duration {
        let mut ts = libc::timespec { tv_sec: 0, tv_nsec: 0 };
        // SAFETY: as in process_cpu_time.
        assert_eq!(unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut ts) }, 0);
        Duration::new(ts.tv_sec as u64, ts.tv_nsec as u32)
    }

    // The process's time holds this thread's: spinning until this thread has
    // used 20 ms of CPU (however long that takes on a loaded machine) moves
    // it by at least as much. Other tests run in this process at the same
    // time, so only a lower bound can be asserted.
    #[test]
    fn cpu_time_grows_with_work() {
        let start = process_cpu_time().expect("Linux keeps process CPU time");
        let thread_start = thread_cpu_time();
        let mut x = 0u64;
        while thread_cpu_time() - thread_start < Duration::from_millis(20) {
            x = x.wrapping_mul(6364136223846793005).wrapping_add(1);
        }
        std::hint::black_box(x);
        let busy = cpu_ms_between(Some(start), process_cpu_time());
        assert!(busy >= 20.0, "20 ms of this thread's CPU moved the process's by {busy} ms");
        assert!(cpu_ms_between(None, process_cpu_time()).is_nan());
    }
}
