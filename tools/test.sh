#!/usr/bin/env bash
# The test suite: set up, then every test with the Khronos validation layer and
# synchronization validation on (any message fails the test), after fmt; clippy
# lints our crate as the test build compiles it.
set -euo pipefail
cd "$(dirname "$0")/.."
source tools/setup.sh
export SWEEPLAB_VALIDATE=1
cargo fmt --all -- --check
# Clippy lints our crate as the test build compiles it.
source tools/clippy_in_build.sh
# The whole output stays on the terminal; the last line sums the `test result:`
# lines (CI reads it). The exit status is non-zero when a step failed.
log="$(mktemp)"
status=0
# A test binary that dies of a signal leaves a core file here, and
# tools/crash_backtrace.sh prints its threads' backtraces.
ulimit -c unlimited 2>/dev/null || true
# Every test target built at once, then run (tools/run_built_tests.sh).
cargo test --release --no-run 2>&1 | tee "$log" || status=$?
bash tools/run_built_tests.sh 2>&1 | tee -a "$log" || status=$?
bash tools/crash_backtrace.sh <"$log"
bash tools/test_summary.sh <"$log"
rm -f "$log"
exit "$status"
