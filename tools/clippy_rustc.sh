#!/usr/bin/env bash
# Cargo's RUSTC_WORKSPACE_WRAPPER in tools/test.sh (tools/clippy_in_build.sh):
# clippy-driver lints each target of this package and compiles it. Test
# harnesses (`--test`: the library's unit tests, the binary's, the suite)
# compile at opt-level 1: the library they test is the release build itself,
# they only call it, and the library's unit-test build (the whole library
# compiled a second time, beside the release build) took 62 s of a clean
# build's cores at opt-level 3, 44 s at 1. Opt-level 1 keeps debug assertions
# and overflow checks off, as in release; rustc takes the last -C opt-level.
for arg in "$@"; do
  if [ "$arg" = "--test" ]; then
    exec "$SWEEPLAB_CLIPPY_DRIVER" "$@" -C opt-level=1
  fi
done
exec "$SWEEPLAB_CLIPPY_DRIVER" "$@"
