#!/usr/bin/env bash
# What each file of tests/ costs: the suite binary run once per module (the
# file's tests alone, two test threads as in tools/test.sh), with validation,
# under /usr/bin/time. Prints a Markdown table, most expensive first: the
# module, its tests, CPU seconds (user + sys: every thread, lavapipe's
# included, and the sweeplab processes a test starts; what the module costs
# whatever else shares the machine) and wall seconds (only meaningful on a
# quiet machine). docs/testing.md quotes its output.
#
#   tools/test_costs.sh [MODULE...]      (default: every module of tests/main.rs)
set -euo pipefail
cd "$(dirname "$0")/.."
source tools/setup.sh
cd "$(dirname "${BASH_SOURCE[0]}")/.."
export SWEEPLAB_VALIDATE=1
cargo test --release --no-run --quiet --test suite 2>/dev/null
suite=$(cargo test --release --no-run --test suite --message-format=json 2>/dev/null |
  sed -nE 's/.*"executable":"([^"]+)".*/\1/p' | tail -n 1)
[ -x "$suite" ] || { echo "test_costs: no suite binary" >&2; exit 1; }
# The environment cargo test gives the binary (.cargo/config.toml's [env]).
export SWEEPLAB_PIPELINE_CACHE="${SWEEPLAB_PIPELINE_CACHE:-$(pwd)/target/pipeline-cache}"
modules=("$@")
if [ ${#modules[@]} -eq 0 ]; then
  mapfile -t modules < <(sed -nE 's/^mod ([a-z0-9_]+);$/\1/p' tests/main.rs | grep -vx common)
fi
rows=$(mktemp)
trap 'rm -f "$rows" "$rows.time" "$rows.log"' EXIT
total_cpu=0
for m in "${modules[@]}"; do
  /usr/bin/time -f "%U %S %e" -o "$rows.time" "$suite" "$m::" >"$rows.log" 2>&1 || {
    echo "test_costs: $m failed:" >&2
    tail -n 30 "$rows.log" >&2
  }
  read -r user sys wall <"$rows.time"
  tests=$(sed -nE 's/^test result: .*\. ([0-9]+) passed; ([0-9]+) failed; ([0-9]+) ignored.*/\1 \2 \3/p' "$rows.log")
  read -r passed failed ignored <<<"${tests:-0 0 0}"
  cpu=$(awk -v u="$user" -v s="$sys" 'BEGIN{printf "%.1f", u + s}')
  total_cpu=$(awk -v a="$total_cpu" -v b="$cpu" 'BEGIN{printf "%.1f", a + b}')
  echo "$cpu|$wall|$m|$passed|$failed|$ignored" >>"$rows"
  echo "test_costs: $m: $cpu CPU s, $wall s wall" >&2
done
echo "| file of tests/ | tests (ignored) | CPU s | wall s |"
echo "| --- | ---: | ---: | ---: |"
sort -t'|' -k1,1 -rn "$rows" | while IFS='|' read -r cpu wall m passed failed ignored; do
  note=""
  [ "$failed" -gt 0 ] && note=" ($failed failed)"
  echo "| \`$m.rs\`$note | $passed ($ignored) | $cpu | $wall |"
done
echo "| all | | $total_cpu | |"
