#!/bin/bash
# Several builds of sweeplab, each `sweeplab render --volume data/engine.vti
# --size 256x256 --technique ipsvi` (scene defaults), in rounds whose order
# rotates (round r starts with build r mod n): the line dispatches' GPU ms of
# each render. Builds are name=path pairs, e.g.
#   ROUNDS=8 docs/bench/lavapipe-engine/ipsvi_builds_rotated.sh \
#     before=/tmp/before/sweeplab now=target/release/sweeplab
# RENDER_ARGS adds arguments to every render (split at spaces), e.g.
#   RENDER_ARGS='--set ipsvi.line_kernel="segmented"'
# Output: "round R NAME MS" lines (ipsvi_line_main_256_rotated.txt).
set -eu
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}
vol=${VOLUME:-data/engine.vti}
names=(); paths=()
for a in "$@"; do names+=("${a%%=*}"); paths+=("${a#*=}"); done
n=${#names[@]}
read -ra extra <<< "${RENDER_ARGS:-}"
echo "# $(date -u +%FT%TZ), volume $vol, load $(cut -d' ' -f1-3 /proc/loadavg), render arguments: ${extra[*]:-none}, builds: $*"
"${paths[0]}" render --volume "$vol" --size 8x8 --technique dvr --out /tmp/builds_rotated_device.png 2>&1 | grep -m1 '^device:' | sed 's/^/# /' || true
for r in $(seq 1 "${ROUNDS:-5}"); do
  for j in $(seq 0 $((n - 1))); do
    i=$(((j + r) % n))
    ms=$("${paths[$i]}" render --volume "$vol" --size 256x256 --technique ipsvi "${extra[@]}" --out /tmp/builds_rotated.png 2>&1 |
      awk '$1 == "ipsvi_line" {print $3; exit}')
    echo "round $r ${names[$i]} $ms"
  done
done
