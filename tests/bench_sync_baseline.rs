//! `bench sync` measures each strategy against an equal-work baseline: the
//! same line dispatches in the sweep's order with no barriers, one
//! per line width, not the single dispatch over all lines it used to be.
mod common;

use common::cli::*;

#[test]
fn sync_overhead_is_computed_against_the_no_barrier_frame_of_each_line_width() {
    let dir = temp_dir("sync-baseline");
    let o = sweeplab(&[
        "bench",
        "sync",
        "--sizes",
        "12",
        "--line-widths",
        "1,2",
        "--strategies",
        "barrier-global,events",
        "--repeat",
        "1",
        "--out",
        dir.to_str().unwrap(),
    ]);
    // With validation on (sweeplab() sets it): the baseline's hazards are
    // expected and dropped, anything else would fail the run.
    assert!(o.status.success(), "{}", stderr(&o));
    let rows: Vec<serde_json::Value> =
        serde_json::from_str(&std::fs::read_to_string(dir.join("sync.json")).unwrap()).unwrap();
    assert!(rows.iter().all(|r| r["strategy"] != "single-dispatch"), "{rows:?}");
    for lw in [1, 2] {
        let row = |strategy: &str| {
            rows.iter()
                .find(|r| r["strategy"] == strategy && r["line_width"] == lw)
                .unwrap_or_else(|| panic!("no {strategy} row at line width {lw}: {rows:?}"))
        };
        let baseline = row("no-barriers");
        assert!(
            baseline["hazards_ignored"].as_u64().is_some_and(|n| n > 0),
            "the baseline has no barriers, validation must see hazards: {baseline}"
        );
        for strategy in ["barrier-global", "events"] {
            let r = row(strategy);
            // Equal work: the same dispatches as the strategy's frame.
            assert_eq!(r["dispatches"], baseline["dispatches"], "{strategy} lw {lw}");
            assert_eq!(r["lines"], baseline["lines"], "{strategy} lw {lw}");
            let lines = r["lines"].as_f64().unwrap();
            let expected = (r["gpu_ms"].as_f64().unwrap() - baseline["gpu_ms"].as_f64().unwrap()) * 1e3 / lines;
            let reported = r["per_line_overhead_us"].as_f64().unwrap();
            assert!(
                (reported - expected).abs() <= 1e-6 * expected.abs().max(1.0),
                "{strategy} lw {lw}: overhead {reported} us, against the baseline {expected} us"
            );
        }
    }
}
