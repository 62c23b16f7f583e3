//! Validated contexts on one thread at a time (`src/vk/validated_thread.rs`):
//! the validation layer's process-wide map is written when a validated
//! instance or device is created or destroyed, and read without a lock by
//! every call, so a second thread's validated context waits for the first
//! thread's to be gone, while contexts without validation never wait.

use crate::common::*;
use std::sync::mpsc;
use std::time::{Duration, Instant};

/// How long the first thread holds its validated contexts after the others
/// start: many times what creating a validated context takes here (about
/// 0.1-0.3 s on lavapipe), so a second validated context that did not wait
/// would be created well inside it.
const HOLD: Duration = Duration::from_millis(1500);

#[test]
fn a_second_threads_validated_context_waits_and_an_unvalidated_one_does_not() {
    let (held_tx, held_rx) = mpsc::channel::<()>();
    let (release_tx, release_rx) = mpsc::channel::<Instant>();
    std::thread::scope(|s| {
        let first = s.spawn(move || {
            // Two at once on one thread: a thread never waits for itself.
            let contexts = [validated_context(), validated_context()];
            held_tx.send(()).unwrap();
            std::thread::sleep(HOLD);
            for ctx in &contexts {
                assert_validation_clean(ctx);
            }
            let released = Instant::now();
            drop(contexts);
            release_tx.send(released).unwrap();
        });
        held_rx.recv().unwrap();
        let validated = s.spawn(|| {
            let ctx = validated_context();
            let created = Instant::now();
            assert_validation_clean(&ctx);
            created
        });
        let unvalidated = s.spawn(|| {
            let _ctx = unvalidated_context();
            Instant::now()
        });
        let unvalidated_created = unvalidated.join().unwrap();
        let validated_created = validated.join().unwrap();
        first.join().unwrap();
        let released = release_rx.recv().unwrap();
        assert!(unvalidated_created < released, "a context without validation waited for the validated ones");
        assert!(
            validated_created > released,
            "a validated context was created on a second thread {:?} before the first thread's were gone",
            released - validated_created
        );
    });
}
