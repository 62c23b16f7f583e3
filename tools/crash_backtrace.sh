#!/usr/bin/env bash
# After a test run whose log (stdin) says a test binary died of a signal: the
# backtrace of every thread from its core file, so a crash that happens once
# in many runs (CI) leaves more than "signal: 11". tools/test.sh allows core
# files for the run; where the kernel writes them elsewhere (core_pattern) or
# gdb is missing, this says so and stops.
set -uo pipefail
cd "$(dirname "$0")/.."
crashed=$(sed -n 's/.*process didn.t exit successfully: `\([^`]*\)` (signal: \([0-9]*\).*/\1 \2/p' | head -1)
[ -z "$crashed" ] && exit 0
bin=${crashed% *}
echo "crash: $bin died of signal ${crashed##* } (kernel core_pattern: $(cat /proc/sys/kernel/core_pattern 2>/dev/null))" >&2
core=$(ls -t core core.* 2>/dev/null | head -1)
if [ -z "$core" ] || ! command -v gdb >/dev/null 2>&1; then
    echo "crash: no core file in $(pwd) or no gdb: no backtrace" >&2
    exit 0
fi
gdb -q -batch -ex 'info threads' -ex 'thread apply all bt 25' "$bin" "$core" 2>&1 | tail -n 400 >&2
rm -f "$core"
