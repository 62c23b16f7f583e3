//! `tools/test.sh` ends with one line summed over cargo test's `test result:`
//! lines (tools/test_summary.sh), which CI reads.

use std::io::Write;
use std::process::{Command, Stdio};

fn summary(log: &str) -> String {
    let script = concat!(env!("CARGO_MANIFEST_DIR"), "/tools/test_summary.sh");
    let mut child = Command::new("bash").arg(script).stdin(Stdio::piped()).stdout(Stdio::piped()).spawn().unwrap();
    child.stdin.take().unwrap().write_all(log.as_bytes()).unwrap();
    let out = child.wait_with_output().unwrap();
    assert!(out.status.success());
    String::from_utf8(out.stdout).unwrap()
}

#[test]
fn the_summary_sums_every_test_result_line() {
    let log = "running 15 tests\n\
               test a ... ok\n\
               test result: ok. 15 passed; 0 failed; 2 ignored; 0 measured; 0 filtered out; finished in 9.19s\n\
               test result: FAILED. 3 passed; 1 failed; 0 ignored; 0 measured; 0 filtered out; finished in 1.00s\n\
               test b ... 7 passed (not a result line)\n";
    assert_eq!(summary(log), "18 passed, 1 failed, 2 ignored\n");
    assert_eq!(summary(""), "0 passed, 0 failed, 0 ignored\n");
}
