#!/usr/bin/env bash
# The suite binary (tests/main.rs) in two processes at a time, one test thread
# each: every file of tests/ (a module) runs in a process of its own, handed
# out heaviest first to whichever of the two is free.
#
# Why processes: a validated Vulkan context claims its process for its thread
# (src/vk/validated_thread.rs: the Khronos validation layer's process-wide map
# is not safe against a second thread creating or destroying a validated
# instance or device), so two test threads in one process would take turns on
# the GPU tests. Two processes keep both cores busy and never wait.
#
# Usage: tools/suite_processes.sh SUITE_BINARY
# Prints each module's output whole when it ends, then libtest's `test result:`
# line; a process that dies of a signal prints cargo's line for it (which
# tools/crash_backtrace.sh reads) and a result line counting its unfinished
# tests as failed. Exit status 0 only when every module passed.
set -uo pipefail
cd "$(dirname "$0")/.."
# The tests of tests/main.rs itself, outside any module.
TOP_LEVEL=main.rs
# What cargo test gives the binary from .cargo/config.toml's [env]: the
# driver's pipeline cache in target/, not in the user's ~/.cache.
export SWEEPLAB_PIPELINE_CACHE="${SWEEPLAB_PIPELINE_CACHE:-$(pwd)/target/pipeline-cache}"

run_module() {
    local bin=$1 module=$2 list=$3 log
    log=$(mktemp)
    if [ "$module" = "$TOP_LEVEL" ]; then
        mapfile -t tests < <(sed -n 's/^\([^:]*\): test$/\1/p' "$list")
    else
        mapfile -t tests < <(sed -n "s/^\(${module}::.*\): test\$/\1/p" "$list")
    fi
    local status=0 start=$EPOCHREALTIME
    "$bin" --test-threads=1 --exact "${tests[@]}" >"$log" 2>&1 || status=$?
    if [ "$status" -gt 128 ]; then
        local passed ignored
        passed=$(grep -cE '^test .* \.\.\. ok$' "$log")
        ignored=$(grep -cE '^test .* \.\.\. ignored' "$log")
        {
            echo "error: process didn't exit successfully: \`$bin\` (signal: $((status - 128)))"
            echo "test result: FAILED. $passed passed; $((${#tests[@]} - passed - ignored)) failed; $ignored ignored (${module}: its process died)"
        } >>"$log"
    fi
    echo "suite_processes: ${module} took $(awk -v a="$start" -v b="$EPOCHREALTIME" 'BEGIN{printf "%.1f", b - a}') s" >>"$log"
    # One module's output at a time on the terminal.
    flock "$list" cat "$log"
    rm -f "$log"
    return $((status == 0 ? 0 : 1))
}

if [ "${1:-}" = "--module" ]; then
    run_module "$2" "$3" "$4"
    exit $?
fi

bin=${1:?usage: tools/suite_processes.sh SUITE_BINARY}
list=$(mktemp)
trap 'rm -f "$list"' EXIT
if ! "$bin" --list --format terse >"$list" || ! grep -q ': test$' "$list"; then
    echo "suite_processes: $bin lists no tests"
    exit 1
fi
# Heaviest first, so that no long module starts last: their wall seconds in a
# clean clone's tools/test.sh, cold shader cache (2026-12-06: 160 s for
# ipsvi_view_samples down to 14 s for gpu_smoke; each module's time is printed
# with its output). Modules not named here follow in name order.
heavy="ipsvi_view_samples ipsvi_segmented ipsvi viewer stability bench_sync gpu_check cli
lightvolume_updates reference_convergence lightvolume_coarse_error clean_images best_practices
readme_gallery ipsvi_merged_sweeps gpu_smoke"
all=$(sed -n 's/^\([a-z0-9_]*\)::.*: test$/\1/p' "$list" | sort -u)
grep -q '^[^:]*: test$' "$list" && all+=$'\n'$TOP_LEVEL
ordered=$( (for m in $heavy; do grep -qx "$m" <<<"$all" && echo "$m"; done; grep -vxF -f <(tr ' ' '\n' <<<"$heavy" | sed '/^$/d') <<<"$all") )
xargs -P 2 -I{} bash "$0" --module "$bin" {} "$list" <<<"$ordered"
