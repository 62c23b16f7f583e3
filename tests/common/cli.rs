//! Running the `sweeplab` binary as a user does, for the command-line tests.

use std::path::PathBuf;
use std::process::{Command, Output};

/// `sweeplab ARGS` with validation and synchronization validation on.
pub fn sweeplab(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_sweeplab"))
        .args(args)
        .env("SWEEPLAB_VALIDATE", "1")
        .output()
        .expect("run sweeplab")
}

/// A fresh folder for one test's files.
pub fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("sweeplab-cli-{name}-{}", std::process::id()));
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
    for key in ["device", "driver", "host_cpu", "sweeplab", "date", "command"] {
        assert!(csv.contains(&format!("# {key}: ")), "CSV lacks {key}");
        assert!(md.contains(&format!("- {key}: ")), "Markdown lacks {key}");
    }
}
