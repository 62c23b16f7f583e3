//! `tools/suite_processes.sh`, which runs the suite one module per process in
//! two processes at a time, on a stand-in binary: every module and the
//! top-level tests run, each exactly once, and a process that dies of a signal
//! is reported as cargo reports it (tools/crash_backtrace.sh reads that line),
//! with its unfinished tests counted as failed and a failing exit status.

use std::process::Command;

/// A stand-in for the suite binary: lists four tests in two modules and one
/// top-level test; running `alpha::two` kills its own process (SIGKILL: no
/// core file), every other test passes.
const STAND_IN: &str = r#"#!/usr/bin/env bash
if [ "$1" = "--list" ]; then
    printf 'alpha::one: test\nalpha::two: test\nalpha::nested::three: test\nbeta::four: test\ntop: test\n'
    exit 0
fi
shift 2  # --test-threads=1 --exact
for t in "$@"; do
    [ "$t" = alpha::two ] && kill -KILL $$
    echo "test $t ... ok"
done
echo "test result: ok. $# passed; 0 failed; 0 ignored; 0 measured; 0 filtered out; finished in 0.00s"
"#;

#[test]
fn every_module_runs_once_and_a_killed_process_counts_its_unfinished_tests_as_failed() {
    let dir = std::env::temp_dir().join(format!("sweeplab-suite-processes-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let bin = dir.join("stand-in-suite");
    std::fs::write(&bin, STAND_IN).unwrap();
    std::fs::set_permissions(&bin, std::os::unix::fs::PermissionsExt::from_mode(0o755)).unwrap();
    let root = env!("CARGO_MANIFEST_DIR");
    let out = Command::new("bash")
        .arg(format!("{root}/tools/suite_processes.sh"))
        .arg(&bin)
        .env("PATH", std::env::var_os("PATH").unwrap_or_default())
        .output()
        .unwrap();
    let log = String::from_utf8_lossy(&out.stdout);
    assert!(!out.status.success(), "a killed module must fail the run:\n{log}");
    for test in ["alpha::one", "beta::four", "top"] {
        assert_eq!(log.matches(&format!("test {test} ... ok")).count(), 1, "{test} once:\n{log}");
    }
    assert!(!log.contains("alpha::nested::three ... ok"), "ran after the kill:\n{log}");
    let crash = format!("process didn't exit successfully: `{}` (signal: 9)", bin.display());
    assert!(log.contains(&crash), "cargo's line for the killed process:\n{log}");
    let summary = Command::new("bash")
        .arg("-c")
        .arg(format!("bash {root}/tools/test_summary.sh"))
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .spawn()
        .and_then(|mut child| {
            use std::io::Write;
            child.stdin.take().unwrap().write_all(log.as_bytes())?;
            child.wait_with_output()
        })
        .unwrap();
    // alpha::one, beta::four and top passed; alpha::two and
    // alpha::nested::three never finished.
    assert_eq!(String::from_utf8_lossy(&summary.stdout), "3 passed, 2 failed, 0 ignored\n");
    std::fs::remove_dir_all(&dir).unwrap();
}
