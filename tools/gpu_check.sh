#!/usr/bin/env bash
# One command for a machine with a GPU driver and nothing else (no compiler,
# no network): lists the devices, renders every technique against its ground
# truth with validation on, runs the IPSVI paper's Table 1 on the CT engine with
# both line kernels (`bench table1`), `bench sync`, `bench ipsvi --breakdown`,
# IPSVI's error against time per mode (`bench ipsvi`) and a short `bench lights`,
# and writes one report (report.json + report.md) into OUT. A part that fails is
# recorded (exit status, time, log tail) and the next one runs. See
# docs/bench-on-your-gpu.md.
#
#   tools/gpu_check.sh OUT            (from a bundle made by tools/gpu_check_prepare.sh,
#                                      or from a checkout with a release build)
#
# Sizes and choices (environment):
#   GPU_CHECK_BIN          sweeplab binary (default: bundle's bin/, else target/release/)
#   GPU_CHECK_DEVICE       device index or name substring (default: the engine's choice)
#   GPU_CHECK_SCENE        scene file (default: tests/scenes/cornell-box.toml)
#   GPU_CHECK_HALF_ANGLE_SCENE  half-angle's scene (one light outside the volume; default
#                          tests/scenes/slab-under-sphere.toml: the Cornell box's light is inside)
#   GPU_CHECK_SIZE         image side of the comparisons (default 256)
#   GPU_CHECK_BENCH_SIZE   image side of bench sync and bench ipsvi --breakdown (default 512)
#   GPU_CHECK_TECHNIQUES   comma-separated (default: every technique)
#   GPU_CHECK_SYNC_ARGS    extra arguments of bench sync (default: every workload, the chain
#                          calibration included, line widths 1,4,16,32, 6 to 12 rounds within 2 minutes)
#   GPU_CHECK_IPSVI_ARGS   extra arguments of bench ipsvi --breakdown (default: 6 to 30 rounds
#                          within 2 minutes, never fewer than 6)
#   GPU_CHECK_MODES_ARGS   arguments of bench ipsvi's error against time (default: every mode at
#                          caches 256 and 512, line width 1, one factor at a time, 6 to 12
#                          rounds within a minute)
#   GPU_CHECK_TABLE1_ARGS  arguments of bench table1 (default: the CT engine at 256 and 512,
#                          line widths 1, 2, 4, the serial line kernel and the segmented one
#                          at 32, 64 and 128 segments with their default texel lanes and at 128
#                          with 8 texel lanes, 6 rounds; needs engine.vti in the data folder)
#   SWEEPLAB_DATA          the data folder (default: data/ beside tools/, the bundle's copy or
#                          the checkout's: the binary's own default is the folder it was built in)
#   GPU_CHECK_LIGHTS_ARGS  arguments of bench lights (default: a short run)
#   GPU_CHECK_AO_SET       --set value for the ao comparison (default: none)
#   GPU_CHECK_BENCHES      0: the comparisons only (default 1)
#   GPU_CHECK_MAX_SECONDS  the whole check's time limit (default: none): each part runs
#                          under `timeout` with the time left, a part cut there is recorded
#                          as cut, the parts after it as skipped, and the report is written
#                          (tools/gpu_check_on_device.sh sets it for a lent machine)
set -u

out=${1:?usage: tools/gpu_check.sh OUT_DIR}
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/.." && pwd)
mkdir -p "$out/logs" "$out/compare" || exit 1
out=$(cd "$out" && pwd)

# The carried Vulkan loader and validation layer (tools/gpu_check_prepare.sh
# unpacks them into vulkan/ beside tools/): used in place of the system's.
carried="$root/vulkan"
if [ -d "$carried/usr/lib/x86_64-linux-gnu" ]; then
    export LD_LIBRARY_PATH="$carried/usr/lib/x86_64-linux-gnu${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
    export VK_LAYER_PATH="$carried/usr/share/vulkan/explicit_layer.d"
    export VK_ADD_LAYER_PATH="$VK_LAYER_PATH"
    vulkan_from="carried ($carried)"
else
    vulkan_from="system"
fi

# The data sets (Table 1's engine.vti) beside the script, wherever the bundle was unpacked.
export SWEEPLAB_DATA=${SWEEPLAB_DATA:-$root/data}

bin=${GPU_CHECK_BIN:-}
if [ -z "$bin" ]; then
    if [ -x "$root/bin/sweeplab" ]; then bin="$root/bin/sweeplab"; else bin="$root/target/release/sweeplab"; fi
fi
scene=${GPU_CHECK_SCENE:-$root/tests/scenes/cornell-box.toml}
half_angle_scene=${GPU_CHECK_HALF_ANGLE_SCENE:-$root/tests/scenes/slab-under-sphere.toml}
ipsvi_args=${GPU_CHECK_IPSVI_ARGS:---repeat 6 --max-rounds 30 --max-minutes 2}
size=${GPU_CHECK_SIZE:-256}
bench_size=${GPU_CHECK_BENCH_SIZE:-512}
techniques=${GPU_CHECK_TECHNIQUES:-dvr,phong,reference,ipsvi,half-angle,lightvolume,ao}
sync_args=${GPU_CHECK_SYNC_ARGS:---line-widths 1,4,16,32 --max-rounds 12 --max-minutes 2}
modes_args=${GPU_CHECK_MODES_ARGS:---one-at-a-time --line-widths 1 --cache-sizes 256,512 --half-angle-slices --repeat 6 --max-rounds 12 --max-minutes 1}
table1_args=${GPU_CHECK_TABLE1_ARGS:---data-sets engine.vti --sizes 256,512 --kernels serial,segmented --segments 32,64,128,128/8 --repeat 6}
lights_args=${GPU_CHECK_LIGHTS_ARGS:---scales 4 --light-counts 2 --scaling-counts 1,4 --error-scales 4 --incremental-passes 1 --repeat 1}
device_args=()
[ -n "${GPU_CHECK_DEVICE:-}" ] && device_args=(--device "$GPU_CHECK_DEVICE")
# The AO preprocessing's cache stays with the report.
export XDG_CACHE_HOME="$out/cache"

parts_json="$out/.parts.jsonl"
: > "$parts_json"
started_all=$(date +%s.%N)

json_string() {
    # A JSON string literal of $1 (backslash, quote, control characters).
    # (Empty: sed and awk below would print no line at all.)
    [ -z "$1" ] && { printf '""'; return; }
    printf '%s' "$1" | sed -e 's/\\/\\\\/g' -e 's/"/\\"/g' -e 's/\t/\\t/g' -e 's/\r//g' | awk 'BEGIN{ORS="\\n"} {print}' |
        sed -e 's/\\n$//' -e 's/^/"/' -e 's/$/"/'
}

# part NAME COMMAND...: runs it with its log in logs/NAME.log, records the result.
# Under GPU_CHECK_MAX_SECONDS it runs with the time left, or not at all.
max_seconds=${GPU_CHECK_MAX_SECONDS:-}
if [ -n "$max_seconds" ] && ! [[ "$max_seconds" =~ ^[0-9]+$ ]]; then
    echo "GPU_CHECK_MAX_SECONDS=$max_seconds is not a whole number of seconds" >&2
    exit 2
fi
part() {
    local name=$1
    shift
    local log="$out/logs/$name.log"
    local t0 t1 rc outcome limit=()
    t0=$(date +%s.%N)
    if [ -n "$max_seconds" ]; then
        local left
        left=$(awk -v a="$started_all" -v b="$t0" -v m="$max_seconds" 'BEGIN{printf "%d", m - (b - a)}')
        if [ "$left" -le 0 ]; then
            echo "== $name: skipped (the check's time limit, ${max_seconds} s, was reached)" >&2
            echo "skipped: the check's time limit (GPU_CHECK_MAX_SECONDS=$max_seconds) was reached before it began" > "$log"
            record_part "$name" "$*" 124 "skipped" 0.0 "$log"
            return
        fi
        # TERM first (a bench writes nothing more), KILL 10 s later.
        limit=(timeout --kill-after=10 "$left")
    fi
    echo "== $name: $*" >&2
    "${limit[@]}" "$@" > "$log" 2>&1
    rc=$?
    t1=$(date +%s.%N)
    local seconds
    seconds=$(awk -v a="$t0" -v b="$t1" 'BEGIN{printf "%.1f", b - a}')
    outcome=passed
    [ "$rc" -ne 0 ] && outcome=failed
    if [ ${#limit[@]} -gt 0 ] && { [ "$rc" -eq 124 ] || [ "$rc" -eq 137 ]; }; then
        outcome="cut at the time limit"
        echo "cut: the check's time limit (GPU_CHECK_MAX_SECONDS=$max_seconds) ended it" >> "$log"
    fi
    echo "   rc $rc, ${seconds} s, $outcome" >&2
    record_part "$name" "$*" "$rc" "$outcome" "$seconds" "$log"
}

# record_part NAME COMMAND RC OUTCOME SECONDS LOG: one line of the report's parts.
record_part() {
    local name=$1 command=$2 rc=$3 outcome=$4 seconds=$5 log=$6
    local validation="not run"
    if grep -q "^validation: clean" "$log"; then validation="clean"; elif grep -qi "validation:" "$log"; then
        validation="messages"
    fi
    printf '{"name": %s, "command": %s, "rc": %d, "outcome": %s, "seconds": %s, "validation": %s, "log": %s, "tail": %s}\n' \
        "$(json_string "$name")" "$(json_string "$command")" "$rc" "$(json_string "$outcome")" "$seconds" \
        "$(json_string "$validation")" "$(json_string "logs/$name.log")" "$(json_string "$(tail -n 8 "$log")")" >> "$parts_json"
}

part devices "$bin" devices
IFS=',' read -r -a list <<< "$techniques"
for t in "${list[@]}"; do
    extra=()
    [ "$t" = ao ] && [ -n "${GPU_CHECK_AO_SET:-}" ] && extra=(--set "$GPU_CHECK_AO_SET")
    s=$scene
    [ "$t" = half-angle ] && s=$half_angle_scene
    # The ground truths are kept in cache/ground-truth: a technique approximating the model
    # (and scene) of one before it reuses that one's instead of rendering it again.
    part "compare-$t" "$bin" compare --scene "$s" --technique "$t" --size "${size}x${size}" --validate \
        "${device_args[@]}" "${extra[@]}" --json "$out/compare/$t.json" --out "$out/compare/$t.png" \
        --reference-out "$out/compare/$t-reference.png" --reference-cache "$out/cache/ground-truth"
done
if [ "${GPU_CHECK_BENCHES:-1}" = 1 ]; then
    # --force: a second check into the same OUT replaces its bench results (as it does the rest).
    # The paper's Table 1 first (both line kernels, frames per second beside the GTX 580's):
    # under a time limit, the bench a GPU run needs most.
    # shellcheck disable=SC2086 # the argument strings are word lists
    part bench-table1 "$bin" bench table1 "${device_args[@]}" --out-dir "$out/bench-table1" --force $table1_args
    # shellcheck disable=SC2086
    part bench-sync "$bin" bench sync --scene "$scene" --size "${bench_size}x${bench_size}" "${device_args[@]}" \
        --out-dir "$out/bench-sync" --force $sync_args
    # shellcheck disable=SC2086
    part bench-ipsvi-breakdown "$bin" bench ipsvi --breakdown --scene "$scene" --sizes "$bench_size" "${device_args[@]}" \
        --out-dir "$out/bench-ipsvi" --force $ipsvi_args
    # shellcheck disable=SC2086
    part bench-ipsvi-modes "$bin" bench ipsvi --scene "$scene" --sizes "$bench_size" "${device_args[@]}" \
        --out-dir "$out/bench-ipsvi-modes" --force $modes_args
    # shellcheck disable=SC2086
    part bench-lights "$bin" bench lights --scene "$scene" "${device_args[@]}" --out-dir "$out/bench-lights" --force $lights_args
fi

total=$(awk -v a="$started_all" -v b="$(date +%s.%N)" 'BEGIN{printf "%.1f", b - a}')
# The binary's version and commit (`sweeplab --version`).
build=$("$bin" --version 2>/dev/null | head -n 1)
device=$(grep -m1 -E '^\s*(\*|0)' "$out/logs/devices.log" 2>/dev/null | sed 's/^[ *]*//')
# The layer's version beside the driver's API version: a layer older than the
# driver does not know its newest extensions. `sweeplab devices` names the
# layer; a validated part's first line names the device, its API version and
# the layer it ran with (and any extension left out for it).
layer=$(grep -m1 '^validation layer:' "$out/logs/devices.log" 2>/dev/null | sed 's/^validation layer: //')
validated=$(grep -h -m1 '^device: .*validation on' "$out"/logs/compare-*.log 2>/dev/null | head -n 1)
failed=$(grep -c -v '"rc": 0,' "$parts_json")
cut=$(grep -c -E '"outcome": "(cut|skipped)' "$parts_json")
{
    printf '{\n  "tool": "tools/gpu_check.sh",\n  "date": %s,\n  "host": %s,\n  "device": %s,\n' \
        "$(json_string "$(date -u +%Y-%m-%dT%H:%M:%SZ)")" "$(json_string "$(uname -srm)")" "$(json_string "$device")"
    printf '  "build": %s,\n' "$(json_string "${build:-unknown}")"
    printf '  "vulkan": %s,\n  "validation_layer": %s,\n  "validated_device": %s,\n' \
        "$(json_string "$vulkan_from")" "$(json_string "${layer:-unknown}")" "$(json_string "${validated:-none}")"
    printf '  "sizes": {"compare": %d, "bench": %d},\n  "total_seconds": %s,\n  "max_seconds": %s,\n' \
        "$size" "$bench_size" "$total" "${max_seconds:-null}"
    printf '  "failed_parts": %d,\n  "cut_or_skipped_parts": %d,\n' "$failed" "$cut"
    printf '  "parts": [\n'
    sed -e 's/^/    /' -e '$!s/$/,/' "$parts_json"
    printf '  ]\n}\n'
} > "$out/report.json"
{
    echo "# GPU check"
    echo
    echo "- build: ${build:-unknown}"
    echo "- device: ${device:-unknown} (Vulkan loader and layer: $vulkan_from)"
    echo "- validation layer: ${layer:-unknown}; validated runs: ${validated:-none}"
    echo "- host: $(uname -srm); $(date -u +%Y-%m-%dT%H:%M:%SZ)"
    echo "- comparisons at ${size}x${size}, benches at ${bench_size}; data sets from $SWEEPLAB_DATA; total ${total} s${max_seconds:+ (limit $max_seconds s)}; failed parts: $failed${max_seconds:+ (of them cut or skipped at the limit: $cut)}"
    echo
    echo "| part | exit | outcome | seconds | validation | log |"
    echo "|---|---|---|---|---|---|"
    while IFS= read -r line; do
        name=$(sed -E 's/.*"name": "([^"]*)".*/\1/' <<< "$line")
        rc=$(sed -E 's/.*"rc": ([0-9]+).*/\1/' <<< "$line")
        secs=$(sed -E 's/.*"seconds": ([0-9.]+).*/\1/' <<< "$line")
        outcome=$(sed -E 's/.*"outcome": "([^"]*)".*/\1/' <<< "$line")
        val=$(sed -E 's/.*"validation": "([^"]*)".*/\1/' <<< "$line")
        echo "| $name | $rc | $outcome | $secs | $val | logs/$name.log |"
    done < "$parts_json"
    echo
    echo "Errors against the ground truth: compare/*.json; benches: bench-sync/, bench-ipsvi/, bench-ipsvi-modes/, bench-table1/, bench-lights/."
    if [ -f "$out/bench-table1/table1.md" ]; then
        echo
        echo "### The IPSVI paper's Table 1 (CT engine; fps, the paper's GTX 580 beside)"
        echo
        echo '```'
        grep -E ' lw=' "$out/logs/bench-table1.log"
        echo '```'
    fi
    for f in "$out"/compare/*.json; do
        [ -e "$f" ] || continue
        echo
        echo "### $(basename "$f" .json)"
        echo
        echo '```'
        head -c 1500 "$f"
        echo
        echo '```'
    done
} > "$out/report.md"
rm -f "$parts_json"
echo "report: $out/report.md ($failed failed parts, ${total} s)" >&2
[ "$failed" -eq 0 ]
