#!/usr/bin/env bash
# What a lent GPU machine runs, in the repository root of the copy of the tree
# its call sent (docs/bench-on-your-gpu.md, "On a lent machine"): unpacks the
# packages tools/gpu_check_stage.sh put in .gl/ into / (the machine is bare and
# given back afterwards), unpacks the bundle beside them, runs its
# gpu_check.sh under a time limit that leaves room to pack, and packs its OUT
# into one tarball in RESULTS, whatever happened: a part cut at the limit
# still comes back with the parts before it. Prints the report's summary last
# (the call's reply keeps the output's tail).
#
#   tools/gpu_check_on_device.sh [RESULTS]     (default: $OUT, the device tool's folder)
#
# Environment:
#   GPU_CHECK_STAGE        the staged folder (default .gl)
#   GPU_CHECK_MAX_SECONDS  gpu_check.sh's own limit (default 480, its goal: with a machine's start,
#                          about 10 of a session's 15 device minutes, leaving a short rerun)
#   GPU_CHECK_*            passed on to gpu_check.sh (tools/gpu_check.sh lists them)
set -u

results=${1:-${OUT:-}}
[ -n "$results" ] || { echo "usage: tools/gpu_check_on_device.sh RESULTS (or OUT set)" >&2; exit 2; }
mkdir -p "$results" || exit 2
stage=${GPU_CHECK_STAGE:-.gl}
bundle="$stage/gpu-check.tar.gz"
[ -f "$bundle" ] || { echo "no bundle at $bundle: run tools/gpu_check_stage.sh here first" >&2; exit 2; }

debs=("$stage"/*.deb)
if [ -e "${debs[0]}" ]; then
    for f in "${debs[@]}"; do dpkg -x "$f" / || exit 2; done
    ldconfig
fi
# A machine whose NVIDIA driver registers its Vulkan ICD outside the loader's search path.
icd_dirs=(/etc/vulkan/icd.d /usr/local/share/vulkan/icd.d /usr/share/vulkan/icd.d)
nvidia_icd=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
if [ -z "${VK_DRIVER_FILES:-}${VK_ICD_FILENAMES:-}" ] && [ -f "$nvidia_icd" ] &&
    # shellcheck disable=SC2086 # the globs are to expand
    ! grep -qsl nvidia ${icd_dirs[@]/%//*.json}; then
    export VK_DRIVER_FILES=$nvidia_icd
fi

work=$(mktemp -d)
tar -xzf "$bundle" -C "$work" || exit 2
out="$work/gpu-check-out"
mkdir -p "$out"
{
    date -u +%Y-%m-%dT%H:%M:%SZ
    uname -srm
    echo "VK_DRIVER_FILES=${VK_DRIVER_FILES:-}"
    ls -l "${icd_dirs[@]}" "$(dirname "$nvidia_icd")"
    command -v nvidia-smi >/dev/null && nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv
} > "$out/machine.txt" 2>&1

GPU_CHECK_MAX_SECONDS=${GPU_CHECK_MAX_SECONDS:-480} bash "$work/gpu-check/tools/gpu_check.sh" "$out"
rc=$?
# Without the caches (ground truths and AO preprocessing: the images are in compare/). A
# file over 16 MiB does not come back from the device: then without images and traces.
packed="$results/gpu-check-out.tar.gz"
tar -czf "$packed" -C "$work" --exclude=gpu-check-out/cache gpu-check-out || rc=2
if [ "$(du -m "$packed" | cut -f1)" -ge 16 ]; then
    echo "the results are over 16 MiB packed: packed again without images and Perfetto traces" >&2
    tar -czf "$packed" -C "$work" --exclude=gpu-check-out/cache --exclude='*.png' --exclude='trace_*.json' \
        gpu-check-out || rc=2
fi

# The summary, least needed first: the reply keeps the last 12,000 characters.
if [ -f "$out/logs/bench-sync.log" ]; then
    echo "## bench sync (the log's last lines)"
    tail -n 30 "$out/logs/bench-sync.log"
fi
if [ -f "$out/report.md" ]; then
    # The header, the parts and Table 1; the comparisons' JSON stays in the tarball.
    awk '/^### [a-z-]+$/ { exit } { print }' "$out/report.md"
fi
echo "gpu_check: exit $rc; results: $packed ($(du -k "$packed" 2>/dev/null | cut -f1) KiB)"
rm -rf "$work"
exit "$rc"
