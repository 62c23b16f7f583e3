//! A `submit_and_wait` frame's command pool outlives the frame until the next
//! one has finished (`src/vk/finished_frame.rs`): the validation layer's
//! retire thread may still hold the frame's command buffer when the fence
//! wakes us, and a buffer freed then dies on that thread, racing our next
//! debug label (docs/testing.md, "The validation layer's retire thread").

use crate::common::*;
use std::time::Instant;
use sweeplab::vk::commands::submit_and_wait;
use sweeplab::vk::VkError;

#[test]
fn the_last_frames_pool_is_kept_until_the_next_frame_has_finished() {
    let ctx = validated_context();
    assert_eq!(ctx.finished_frame.kept_pool(), None, "nothing kept before the first frame");
    submit_and_wait(&ctx, "first frame", |rec| {
        rec.begin_label("first pass");
        rec.end_label();
        Ok(())
    })
    .unwrap();
    let first = ctx.finished_frame.kept_pool().expect("the first frame's pool is kept after its fence");
    submit_and_wait(&ctx, "second frame", |_| Ok(())).unwrap();
    let second = ctx.finished_frame.kept_pool().expect("the second frame's pool is kept");
    assert_ne!(first, second, "the second frame keeps its own pool in place of the first's");

    // A frame that fails while recording submits nothing: what is kept stays.
    let failed = submit_and_wait(&ctx, "failing frame", |_| -> Result<(), VkError> {
        Err(VkError::Profiler("a recording error".into()))
    });
    assert!(failed.is_err());
    assert_eq!(ctx.finished_frame.kept_pool(), Some(second), "a failed frame replaces nothing");
    assert_validation_clean(&ctx);
}

/// The race itself, by hand: frames of a debug label and nothing else, as
/// fast as one thread submits them, validated, for `STRESS_SECS` (default
/// 10). It needs the layer's thread preempted between waking us and dropping
/// its references, so run it in several processes at once on a loaded
/// machine (docs/testing.md gives the loop and what it found):
/// `STRESS_SECS=60 SUITE --ignored --exact finished_frames::label_frames_stress --nocapture`.
#[test]
#[ignore]
fn label_frames_stress() {
    let secs: u64 = match std::env::var("STRESS_SECS") {
        Ok(s) => s.parse().unwrap_or_else(|e| panic!("STRESS_SECS={s:?}: whole seconds expected ({e})")),
        Err(_) => 10,
    };
    let ctx = validated_context();
    let start = Instant::now();
    let mut frames = 0u64;
    while start.elapsed().as_secs() < secs {
        submit_and_wait(&ctx, "stress frame", |rec| {
            rec.begin_label("stress pass");
            rec.end_label();
            Ok(())
        })
        .unwrap();
        frames += 1;
    }
    eprintln!("stress: {frames} frames in {secs} s");
    assert_validation_clean(&ctx);
}
