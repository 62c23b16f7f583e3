#!/usr/bin/env bash
# What tools/test.sh costs in a fresh clone with cold caches, phase by phase:
# the repository cloned at HEAD into a temporary folder (its own target/, so
# every crate is compiled), XDG_CACHE_HOME an empty folder (no Mesa shader
# cache: lavapipe compiles every shader variant in full, as on a new CI
# machine; the pipeline and ground-truth caches live in the clone's target/).
# Crates are fetched first from the local registry and not timed (a new
# machine downloads them too; that depends on its network). Then test.sh's
# steps, each under /usr/bin/time: fmt, the test build (clippy lints it), the
# tests (with validation). Prints a Markdown table (wall and CPU seconds) and the
# machine; docs/testing.md quotes it. Takes about as long as it measures.
#
#   tools/clean_clone_costs.sh            (KEEP=1 keeps the clone and its logs)
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
cd "$repo"
source tools/setup.sh
commit=$(git -C "$repo" rev-parse --short HEAD)
dir=$(mktemp -d "${TMPDIR:-/tmp}/sweeplab-clean-clone.XXXXXX")
[ "${KEEP:-0}" = 1 ] || trap 'rm -rf "$dir"' EXIT
git clone --quiet "$repo" "$dir/repo"
cd "$dir/repo"
export XDG_CACHE_HOME="$dir/xdg-cache"
mkdir -p "$XDG_CACHE_HOME"
cargo fetch --quiet

rows=()
total_wall=0
total_cpu=0
# phase NAME COMMAND...: runs it, keeps its log, adds a row; stops on failure.
phase() {
  local name=$1
  shift
  local log="$dir/$name.log"
  if ! /usr/bin/time -f "%e %U %S" -o "$dir/$name.time" "$@" >"$log" 2>&1; then
    echo "clean_clone_costs: $name failed; its failures, then the last lines of its log ($log):" >&2
    grep -E "\.\.\. FAILED|panicked at|process didn't exit|did not build|lists no tests" "$log" | head -n 30 >&2
    tail -n 30 "$log" >&2
    # A failure keeps the clone and its logs, to be read.
    trap - EXIT
    echo "clean_clone_costs: kept $dir" >&2
    exit 1
  fi
  local wall user sys cpu
  read -r wall user sys <"$dir/$name.time"
  cpu=$(awk -v u="$user" -v s="$sys" 'BEGIN{printf "%.0f", u + s}')
  rows+=("| $name | \`$*\` | $(printf '%.0f' "$wall") | $cpu |")
  total_wall=$(awk -v a="$total_wall" -v b="$wall" 'BEGIN{printf "%.0f", a + b}')
  total_cpu=$(awk -v a="$total_cpu" -v b="$cpu" 'BEGIN{printf "%.0f", a + b}')
  echo "clean_clone_costs: $name: $(printf '%.0f' "$wall") s wall, $cpu CPU s" >&2
}

phase fmt cargo fmt --all -- --check
source tools/clippy_in_build.sh
phase build+clippy cargo test --release --no-run
phase tests env SWEEPLAB_VALIDATE=1 bash tools/run_built_tests.sh

summary=$(bash tools/test_summary.sh <"$dir/tests.log" | tail -n 1)
mesa=$(vulkaninfo --summary 2>/dev/null | sed -nE 's/^[[:space:]]*driverInfo[[:space:]]*=[[:space:]]*//p' | head -n 1)
echo "Clean clone of $commit, $(date -u +%Y-%m-%d), $(nproc) cores ($(sed -nE 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1)), driver ${mesa:-unknown}: $summary"
echo
echo "| phase | command | wall s | CPU s |"
echo "| --- | --- | ---: | ---: |"
printf '%s\n' "${rows[@]}"
echo "| all | tools/test.sh's steps | $total_wall | $total_cpu |"
[ "${KEEP:-0}" = 1 ] && echo "kept: $dir"
exit 0
