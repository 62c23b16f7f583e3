//! Long renders show progress: a submission still running when the
//! context's reporter is due is reported with its name and what it holds, and
//! nothing is reported without a reporter or for a submission that ends first.

use crate::common;

use common::*;
use glam::Vec3;
use std::sync::{Arc, Mutex};
use std::time::Duration;
use sweeplab::render::GpuScene;
use sweeplab::techniques::{render, Technique};
use sweeplab::vk::{Profiler, WaitReporter};

type Reports = Arc<Mutex<Vec<(String, Duration, u32)>>>;

fn reporter(after: Duration, reports: &Reports) -> WaitReporter {
    let reports = reports.clone();
    WaitReporter {
        after,
        every: Duration::from_millis(1),
        report: Box::new(move |r| reports.lock().unwrap().push((r.name.to_string(), r.elapsed, r.dispatches))),
    }
}

#[test]
fn a_frame_still_running_is_reported_with_its_name_and_dispatches() {
    let ctx = validated_context();
    let scene = scene_with(sphere_volume(32, 10.0), vec![directional(Vec3::new(-1.0, -1.0, -0.5), 2.0)], 128, 128);
    let gpu = GpuScene::upload(&ctx, &scene).unwrap();
    let mut profiler = Profiler::new(&ctx, 256).unwrap();
    let reports: Reports = Arc::default();

    // Due at once: a 128x128 reference frame runs for milliseconds at least.
    ctx.set_wait_reporter(Some(reporter(Duration::ZERO, &reports)));
    let out = render(&gpu, Technique::Reference, 128, 128, &mut profiler).unwrap();
    let seen = reports.lock().unwrap().clone();
    assert!(!seen.is_empty(), "a running frame was not reported");
    assert!(seen.iter().all(|(name, _, dispatches)| name == "frame" && *dispatches == out.dispatches), "{seen:?}");
    assert!(seen.windows(2).all(|w| w[0].1 <= w[1].1), "elapsed times go forward: {seen:?}");

    // Due after an hour, or no reporter: nothing.
    reports.lock().unwrap().clear();
    ctx.set_wait_reporter(Some(reporter(Duration::from_secs(3600), &reports)));
    render(&gpu, Technique::Reference, 128, 128, &mut profiler).unwrap();
    ctx.set_wait_reporter(None);
    render(&gpu, Technique::Reference, 128, 128, &mut profiler).unwrap();
    assert!(reports.lock().unwrap().is_empty());
    assert_validation_clean(&ctx);
}
