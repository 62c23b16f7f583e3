//! Work over all cores with std::thread::scope: chunks handed out from a shared
//! counter, results sent back to the calling thread, which consumes them (and
//! reports progress) while the workers go on.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::mpsc;

/// Worker threads: one per core the process may use.
pub fn worker_count() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// Runs `work(state, i)` for every chunk `i` in `0..chunks` on
/// [`worker_count`] threads, each with its own `init()` state, and calls
/// `consume(i, result, done)` on the calling thread as results arrive (in
/// completion order, `done` counting them). Returns the workers' final states.
pub fn for_each_chunk<S: Send, R: Send>(
    chunks: usize,
    init: impl Fn() -> S + Sync,
    work: impl Fn(&mut S, usize) -> R + Sync,
    mut consume: impl FnMut(usize, R, usize),
) -> Vec<S> {
    let next = AtomicUsize::new(0);
    let workers = worker_count().min(chunks.max(1));
    let (send, receive) = mpsc::channel();
    std::thread::scope(|scope| {
        let handles: Vec<_> = (0..workers)
            .map(|_| {
                let send = send.clone();
                let (next, init, work) = (&next, &init, &work);
                scope.spawn(move || {
                    let mut state = init();
                    loop {
                        let i = next.fetch_add(1, Ordering::Relaxed);
                        if i >= chunks {
                            break;
                        }
                        let result = work(&mut state, i);
                        // The receiver lives until every chunk is in.
                        if send.send((i, result)).is_err() {
                            break;
                        }
                    }
                    state
                })
            })
            .collect();
        drop(send);
        for done in 1..=chunks {
            // A worker that panicked drops its sender; the join below re-raises it.
            let Ok((i, result)) = receive.recv() else { break };
            consume(i, result, done);
        }
        handles.into_iter().map(|h| h.join().unwrap_or_else(|p| std::panic::resume_unwind(p))).collect()
    })
}
