#!/usr/bin/env bash
# The tests, once `cargo test --release --no-run` has built them: the library's
# and the binary's own tests, the doc tests, and the suite (tests/main.rs) in
# two processes of one test thread each (tools/suite_processes.sh says why).
# tools/test.sh and tools/clean_clone_costs.sh run this. Exit status non-zero
# when any step failed.
set -uo pipefail
cd "$(dirname "$0")/.."
status=0
cargo test --release --no-fail-fast --lib --bins 2>&1 || status=1
cargo test --release --no-fail-fast --doc 2>&1 || status=1
suite=$(cargo test --release --test suite --no-run 2>&1 | sed -n 's/.*Executable tests\/main.rs (\(.*\))$/\1/p')
if [ -z "$suite" ]; then
    echo "the suite (tests/main.rs) did not build"
    exit 1
fi
bash tools/suite_processes.sh "$suite" 2>&1 || status=1
exit "$status"
