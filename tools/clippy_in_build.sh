# Sourced by tools/test.sh and tools/clean_clone_costs.sh: cargo then compiles
# this package (lib, bin, tests, example) with clippy-driver, which lints it as
# `cargo clippy -- -D warnings` does and then compiles it as rustc would (with
# MIR optimizations off, as clippy needs; LLVM's are unchanged). Dependencies
# stay plain rustc. A separate `cargo clippy` type-checked every dependency a
# second time: 70 s of a clean clone. A lint is a compile error, so no test
# runs then. Cargo's fingerprint includes the wrapper: a plain `cargo test`
# afterwards recompiles this package, not its dependencies.
if ! clippy_driver="$(command -v clippy-driver)" || ! "$clippy_driver" -V >/dev/null 2>&1; then
  echo "clippy-driver is missing (rustup component add clippy)" >&2
  exit 1
fi
export RUSTC_WORKSPACE_WRAPPER="$clippy_driver"
# cargo clippy's own encoding of the arguments after `--`.
export CLIPPY_ARGS="-D__CLIPPY_HACKERY__warnings__CLIPPY_HACKERY__"
