//! The `sweeplab` binary as a user runs it: outputs, reports, and clear errors
//! with a non-zero exit for bad input (never a panic).

use std::path::PathBuf;
use std::process::{Command, Output};

fn sweeplab(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_sweeplab"))
        .args(args)
        .env("SWEEPLAB_VALIDATE", "1")
        .output()
        .expect("run sweeplab")
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("sweeplab-cli-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn assert_user_error(o: &Output, must_mention: &str) {
    let err = stderr(o);
    assert!(!o.status.success(), "should fail: {err}");
    assert!(!err.contains("panicked"), "panicked: {err}");
    assert!(err.contains(must_mention), "error does not mention {must_mention:?}: {err}");
}

#[test]
fn render_writes_png_profile_and_trace_validation_clean() {
    let dir = temp_dir("render");
    let (png, json, trace) = (dir.join("r.png"), dir.join("p.json"), dir.join("t.json"));
    let o = sweeplab(&[
        "render",
        "--size",
        "48x40",
        "--technique",
        "phong",
        "--out",
        png.to_str().unwrap(),
        "--profile-json",
        json.to_str().unwrap(),
        "--trace",
        trace.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("validation: clean"), "{}", stderr(&o));
    let img = image::open(&png).unwrap();
    assert_eq!((img.width(), img.height()), (48, 40));
    let p: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    for key in ["device", "gpu_ms_total", "gpu_memory_bytes", "passes"] {
        assert!(p.get(key).is_some(), "profile JSON lacks {key}: {p}");
    }
    let pass = &p["passes"][0];
    assert_eq!(pass["name"], "phong");
    assert!(pass["gpu_ms"].as_f64().unwrap() > 0.0 && pass["count"] == 1);
    assert!(p["gpu_memory_bytes"].as_u64().unwrap() > 0);
    let t: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&trace).unwrap()).unwrap();
    assert_eq!(t["traceEvents"][0]["ph"], "X");
}

#[test]
fn compare_reports_error_and_time_as_json() {
    let dir = temp_dir("compare");
    let json = dir.join("c.json");
    let heat = dir.join("h.png");
    let o = sweeplab(&[
        "compare",
        "--technique",
        "dvr",
        "--size",
        "32x32",
        "--json",
        json.to_str().unwrap(),
        "--heatmap",
        heat.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let c: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    for key in ["technique", "rmse", "max_abs", "psnr", "gpu_ms", "reference_gpu_ms"] {
        assert!(c.get(key).is_some(), "compare JSON lacks {key}: {c}");
    }
    assert_eq!(c["technique"], "dvr");
    assert!(c["rmse"].as_f64().unwrap() > 0.0, "unshaded DVR cannot equal the lit reference");
    assert!(image::open(&heat).is_ok());
}

#[test]
fn devices_lists_timestamp_properties() {
    let o = sweeplab(&["devices", "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let d: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let first = &d[0];
    for key in ["name", "api_version", "driver_name", "timestamp_period_ns", "timestamp_valid_bits"] {
        assert!(first.get(key).is_some(), "{key} missing: {first}");
    }
}

#[test]
fn bad_input_gives_clear_errors_not_panics() {
    let dir = temp_dir("errors");
    let missing = dir.join("missing-scene.toml");
    assert_user_error(&sweeplab(&["render", "--scene", missing.to_str().unwrap()]), "missing-scene.toml");
    let garbage = dir.join("garbage.vti");
    std::fs::write(&garbage, b"<VTKFile type=\"ImageData\"><ImageData WholeExtent=\"0 1").unwrap();
    assert_user_error(&sweeplab(&["render", "--volume", garbage.to_str().unwrap()]), "garbage.vti");
    let unknown = dir.join("volume.xyz");
    std::fs::write(&unknown, b"x").unwrap();
    assert_user_error(&sweeplab(&["render", "--volume", unknown.to_str().unwrap()]), "volume.xyz");
    assert_user_error(&sweeplab(&["render", "--size", "12"]), "--size");
    assert_user_error(&sweeplab(&["render", "--size", "0x5"]), "--size");
    assert_user_error(&sweeplab(&["render", "--technique", "raytrace"]), "raytrace");
    assert_user_error(&sweeplab(&["render", "--set", "camera.azimut=3"]), "azimut");
    assert_user_error(&sweeplab(&["render", "--set", "novalue"]), "novalue");
    assert_user_error(
        &sweeplab(&["render", "--set", "ipsvi.line_width=99", "--technique", "ipsvi", "--size", "8x8"]),
        "line_width",
    );
    assert_user_error(&sweeplab(&["render", "--device", "no-such-gpu"]), "no-such-gpu");
    let out = dir.join("bench");
    let out = out.to_str().unwrap();
    assert_user_error(&sweeplab(&["bench", "ipsvi", "--sizes", "0", "--out", out]), "empty");
    assert_user_error(
        &sweeplab(&["bench", "ipsvi", "--sizes", "8", "--line-widths", "99", "--repeat", "1", "--out", out]),
        "line_width",
    );
    assert_user_error(&sweeplab(&["bench", "sync", "--strategies", "fences", "--out", out]), "fences");
    let unwritable = dir.join("no-such-dir").join("out.png");
    assert_user_error(&sweeplab(&["render", "--size", "8x8", "--out", unwritable.to_str().unwrap()]), "out.png");
}
