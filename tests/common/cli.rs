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
