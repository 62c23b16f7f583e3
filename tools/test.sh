#!/usr/bin/env bash
# The test suite: set up, then every test with the Khronos validation layer and
# synchronization validation on (any message fails the test), then fmt and clippy.
set -euo pipefail
cd "$(dirname "$0")/.."
source tools/setup.sh
export SWEEPLAB_VALIDATE=1
export SWEEPLAB_DATA="${SWEEPLAB_DATA:-$(pwd)/../shared/data}"
cargo fmt --all -- --check
cargo clippy --all-targets --quiet -- -D warnings
cargo test --release --no-fail-fast 2>&1
