//! `bench ipsvi --breakdown` also times the whole frame at each of
//! --line-widths, for the LW4/LW1 speed-up.
use crate::common;

use common::cli::*;
use std::process::Command;

#[test]
fn breakdown_times_the_frame_at_every_line_width_against_line_width_1() {
    let dir = temp_dir("breakdown-widths");
    let scene = small_cornell_box(&dir.join("scene"));
    // Without validation: the breakdown's step b has no barriers by design.
    let o = Command::new(env!("CARGO_BIN_EXE_sweeplab"))
        .args(["bench", "ipsvi", "--breakdown", "--scene", scene.to_str().unwrap()])
        // tools/gpu_check.sh's breakdown part as tests/gpu_check.rs runs it: the
        // segmented kernel's modes at line widths 1 and 4 (the serial kernel's:
        // tests/bench_ipsvi_experiment.rs), on the same scene and size, so that
        // lavapipe compiles their pipelines once per run.
        .args(["--sizes", GPU_CHECK_BENCH_SIZE])
        .args(GPU_CHECK_IPSVI_ARGS.split_whitespace())
        .args(["--out-dir", dir.join("bench").to_str().unwrap()])
        .env_remove("SWEEPLAB_VALIDATE")
        .output()
        .expect("run sweeplab");
    assert!(o.status.success(), "{}", stderr(&o));
    let out = dir.join("bench");
    let rows = bench_rows(&out.join("ipsvi_line_widths.json"));
    assert_names_its_run(&out.join("ipsvi_line_widths.csv"), &out.join("ipsvi_line_widths.md"));
    assert_every_output_names_its_run(&out);
    for mode in ["view-samples", "light-rays"] {
        let row = |lw: u32| {
            rows.iter()
                .find(|r| r["cache_update"] == mode && r["line_width"] == lw)
                .unwrap_or_else(|| panic!("{mode} line width {lw} missing: {rows:?}"))
        };
        let (one, four) = (row(1), row(4));
        assert_eq!(one["speedup_over_lw1"].as_f64(), Some(1.0), "{one}");
        let expected = one["gpu_ms"].as_f64().unwrap() / four["gpu_ms"].as_f64().unwrap();
        assert!((four["speedup_over_lw1"].as_f64().unwrap() - expected).abs() < 1e-9 * expected, "{four}");
        // Four lines per dispatch: fewer dispatches for the same frame.
        assert!(four["dispatches"].as_u64() < one["dispatches"].as_u64(), "{one} {four}");
        assert_eq!(one["line_kernel"], "segmented x8", "the kernel as it ran, its segments named: {one}");
        assert!(one["longest_chain"].as_u64().is_some_and(|c| c > 0), "the frame's shape: {one}");
    }
}
