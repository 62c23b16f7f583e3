//! Running the `sweeplab` binary as a user does, for the command-line tests.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// `sweeplab ARGS` with validation and synchronization validation on.
pub fn sweeplab(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_sweeplab"))
        .args(args)
        .env("SWEEPLAB_VALIDATE", "1")
        .output()
        .expect("run sweeplab")
}

/// The Cornell box of `tests/scenes/` at a 16-voxel volume and a 16-texel
/// IPSVI cache, written into `dir`: the benches run the same code as on the
/// full scene, in a fraction of the time (the benches' IPSVI frame at 32x32
/// takes 1.3 s on lavapipe with the scene's own volume and cache, 20 ms with
/// these).
pub fn small_cornell_box(dir: &Path) -> PathBuf {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(root.join("tests/scenes/cornell-box.toml")).unwrap();
    assert!(text.contains("\nsize = 64\n") && !text.contains("[ipsvi]"), "the scene this test shrinks changed");
    let small = text.replace("\nsize = 64\n", "\nsize = 16\n") + "\n[ipsvi]\ncache_size = 16\n";
    std::fs::create_dir_all(dir).unwrap();
    let path = dir.join("small-cornell-box.toml");
    std::fs::write(&path, small).unwrap();
    path
}

/// The image side and the arguments of `bench ipsvi --breakdown` as
/// tests/gpu_check.rs runs tools/gpu_check.sh's breakdown part on
/// [`small_cornell_box`]. tests/bench_breakdown_line_widths.rs runs the same
/// bench on the same scene: its pipelines (the segmented kernel's modes and
/// breakdown steps, which lavapipe compiles in about 10 s) are then compiled
/// once per run and found in Mesa's shader cache by the other test.
pub const GPU_CHECK_BENCH_SIZE: &str = "32";
/// One kernel per IPSVI part: each kernel's modes are pipelines lavapipe compiles.
pub const GPU_CHECK_IPSVI_ARGS: &str = "--line-widths 1,4 --repeat 1 --kernels segmented";

/// A fresh folder for one test's files.
pub fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("sweeplab-cli-{name}-{}", std::process::id()));
    // Empty: a folder of an earlier run whose process had the same id may remain.
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// A failure with a message that mentions `must_mention`, not a panic.
pub fn assert_user_error(o: &Output, must_mention: &str) {
    let err = stderr(o);
    assert!(!o.status.success(), "should fail: {err}");
    assert!(!err.contains("panicked"), "panicked: {err}");
    assert!(err.contains(must_mention), "error does not mention {must_mention:?}: {err}");
}

/// The rows of a bench's JSON table, after checking that the file names the
/// run that produced it (device, driver, host, build, date, command).
pub fn bench_rows(path: &std::path::Path) -> Vec<serde_json::Value> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let table: serde_json::Value = serde_json::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let run = &table["run"];
    for key in [
        "device",
        "vendor_id",
        "device_id",
        "driver_name",
        "driver_version",
        "api_version",
        "host_cpu",
        "git_commit",
        "date",
        "command",
    ] {
        assert!(run[key].as_str().is_some_and(|v| !v.is_empty()), "{}: run.{key} missing in {run}", path.display());
    }
    assert!(run["timestamp_period_ns"].as_f64().is_some(), "{}: {run}", path.display());
    let rows = table["rows"].as_array().unwrap_or_else(|| panic!("{}: no rows", path.display()));
    rows.clone()
}

/// Checks that a bench's CSV and Markdown files name the run, as its JSON does.
pub fn assert_names_its_run(csv: &std::path::Path, md: &std::path::Path) {
    let csv = std::fs::read_to_string(csv).unwrap();
    let md = std::fs::read_to_string(md).unwrap();
    for key in RUN_KEYS {
        assert!(csv.contains(&format!("# {key}: ")), "CSV lacks {key}");
        assert!(md.contains(&format!("- {key}: ")), "Markdown lacks {key}");
    }
}

/// What every bench output names (`RunInfo::lines`).
pub const RUN_KEYS: [&str; 14] = [
    "device",
    "device_type",
    "vendor_id",
    "device_id",
    "driver",
    "driver_version",
    "api_version",
    "timestamp_period_ns",
    "timestamp_valid_bits",
    "host_cpu",
    "host_load",
    "sweeplab",
    "date",
    "command",
];

/// Every file a bench wrote into `dir` (and its sub-folders) names the run
/// that produced it: CSV in `#` lines, Markdown in its header, JSON in a
/// `run` object, each chart in its caption (read from the SVG written beside
/// every PNG). A file of another kind fails: the check must see all outputs.
pub fn assert_every_output_names_its_run(dir: &std::path::Path) {
    fn files(dir: &std::path::Path, out: &mut Vec<std::path::PathBuf>) {
        for entry in std::fs::read_dir(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display())) {
            let path = entry.unwrap().path();
            if path.is_dir() {
                files(&path, out);
            } else {
                out.push(path);
            }
        }
    }
    fn run_object(v: &serde_json::Value) -> Option<&serde_json::Value> {
        match v {
            serde_json::Value::Object(m) => m.get("run").or_else(|| m.values().find_map(run_object)),
            serde_json::Value::Array(a) => a.iter().find_map(run_object),
            _ => None,
        }
    }
    let mut all = Vec::new();
    files(dir, &mut all);
    assert!(!all.is_empty(), "{} holds no output", dir.display());
    // The marker that makes the folder a bench's own (`OutFolder`).
    all.retain(|p| p.file_name().is_some_and(|n| n != ".sweeplab-bench"));
    // A partial run's marker names the command that made it.
    for marker in all.iter().filter(|p| p.file_name().is_some_and(|n| n == "PARTIAL")) {
        let text = std::fs::read_to_string(marker).unwrap();
        assert!(text.contains("command: "), "{}: {text}", marker.display());
    }
    all.retain(|p| p.file_name().is_some_and(|n| n != "PARTIAL"));
    for path in &all {
        let name = path.display();
        let text = || std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{name}: {e}"));
        match path.extension().and_then(|e| e.to_str()).unwrap_or("") {
            "csv" => {
                let t = text();
                for key in RUN_KEYS {
                    assert!(t.contains(&format!("# {key}: ")), "{name} lacks {key}");
                }
            }
            "md" => {
                let t = text();
                for key in RUN_KEYS {
                    assert!(t.contains(&format!("- {key}: ")), "{name} lacks {key}");
                }
            }
            "json" => {
                let v: serde_json::Value = serde_json::from_str(&text()).unwrap_or_else(|e| panic!("{name}: {e}"));
                let run = run_object(&v).unwrap_or_else(|| panic!("{name} has no run object"));
                for key in ["device", "vendor_id", "device_id", "driver_name", "api_version", "git_commit", "date"] {
                    assert!(run[key].as_str().is_some_and(|s| !s.is_empty()), "{name}: run.{key} in {run}");
                }
            }
            "svg" => {
                let t = text();
                assert!(
                    t.contains(&format!("sweeplab {} at ", env!("CARGO_PKG_VERSION"))),
                    "{name} has no run caption"
                );
            }
            "png" => assert!(path.with_extension("svg").is_file(), "{name} has no SVG twin to read its caption from"),
            other => panic!("{name}: an output of kind {other:?} the check does not know"),
        }
    }
}
