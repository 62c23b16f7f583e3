//! Validated contexts live on one thread at a time.
//!
//! Why: the Khronos validation layer (1.3.239, Debian 12's) finds its data for
//! every call in one process-wide map keyed by instance and device
//! (`layer_data_map`, read by `GetLayerDataPtr` without a lock: the layer's own
//! "TODO: We probably should lock here"; Vulkan-ValidationLayers issue 4391).
//! Creating or destroying a validated instance or device writes that map, and
//! a call on another thread that reads it at that moment can corrupt the heap.
//! Measured here: labelled submissions in a loop on validated contexts of
//! three threads aborted the process within 1.5-6.3 s in five of five runs
//! (SIGSEGV, or glibc's `malloc(): unaligned fastbin chunk detected`: the
//! suite's intermittent abort); one thread alone made 251,143 and 268,414 of
//! them in 30 s without one (docs/testing.md, "The suite's heap abort").
//!
//! So a context with validation claims the process for its thread: a validated
//! context created on another thread waits until every validated context of
//! the claiming thread is gone. Contexts without validation never pass through
//! the layer and never wait. A thread may hold several validated contexts.

use std::sync::{Condvar, Mutex, MutexGuard};
use std::thread::ThreadId;

/// The thread whose validated contexts are alive, and how many there are.
struct Claim {
    owner: Option<ThreadId>,
    contexts: usize,
}

static CLAIM: Mutex<Claim> = Mutex::new(Claim { owner: None, contexts: 0 });
static RELEASED: Condvar = Condvar::new();

fn claim_state() -> MutexGuard<'static, Claim> {
    // The counts are updated in single statements: a panic elsewhere leaves them whole.
    CLAIM.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// Held by a validated context from before its instance is created until after
/// it is destroyed.
pub(crate) struct ValidatedThreadClaim(());

impl ValidatedThreadClaim {
    /// Waits until no other thread holds a validated context, then claims the
    /// process for this one.
    pub(crate) fn acquire() -> ValidatedThreadClaim {
        let me = std::thread::current().id();
        let mut claim = claim_state();
        while claim.owner.is_some_and(|owner| owner != me) {
            claim = RELEASED.wait(claim).unwrap_or_else(|poisoned| poisoned.into_inner());
        }
        claim.owner = Some(me);
        claim.contexts += 1;
        ValidatedThreadClaim(())
    }
}

impl Drop for ValidatedThreadClaim {
    fn drop(&mut self) {
        let mut claim = claim_state();
        claim.contexts -= 1;
        if claim.contexts == 0 {
            claim.owner = None;
            RELEASED.notify_all();
        }
    }
}
