#!/bin/bash
# IPSVI line kernels on lavapipe, engine.vti at 256x256 with the scene's
# defaults (every-sample, texel pass, cache 256, plain termination), in
# alternating rounds: the build before the segmented kernel (BEFORE, default
# the main checkout's release binary), this build's default (auto: serial on
# a CPU device), and the segmented kernel at 8 segments (lavapipe's subgroup)
# and 4 (segmented-S; segmented-S-R sets ipsvi.segment_rounds = R too, which
# only builds before the view-stops pass know). Per render: process CPU seconds (user,
# sys), wall seconds, the line dispatches' GPU ms, and the frame's line shape.
# Output: ipsvi_line_kernels_256_alternating.txt. Run from the repository root
# after `cargo build --release`.
set -eu
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}
vol=${VOLUME:-data/engine.vti}
before=${BEFORE:-../../main/target/release/sweeplab}
rounds=${ROUNDS:-6}
# CONFIGS: a subset of the configurations below, in this order within a round.
echo "commit $(git rev-parse --short HEAD), before: $before ($(git -C "$(dirname "$before")/../.." rev-parse --short HEAD 2>/dev/null || echo ?)), $(date -u +%FT%TZ), volume $vol, load $(cut -d' ' -f1-3 /proc/loadavg)"
./target/release/sweeplab render --volume "$vol" --size 8x8 --technique dvr --out /tmp/line_kernels_device.png 2>&1 | grep -m1 '^device:' || true
for r in $(seq 1 "$rounds"); do
  for cfg in ${CONFIGS:-before auto segmented-8 segmented-4}; do
    bin=./target/release/sweeplab
    extra=()
    case $cfg in
      before) bin=$before ;;
      auto) ;;
      segmented-*)
        s=$(echo "$cfg" | cut -d- -f2); n=$(echo "$cfg" | cut -s -d- -f3)
        extra=(--set 'ipsvi.line_kernel="segmented"' --set "ipsvi.segments=$s")
        [ -z "$n" ] || extra+=(--set "ipsvi.segment_rounds=$n") ;;
    esac
    log=$(mktemp)
    /usr/bin/time -f "%U %S %e" -o "$log.time" "$bin" render --volume "$vol" --size 256x256 \
      --technique ipsvi "${extra[@]}" --out "/tmp/line_kernels_$cfg.png" > "$log" 2>&1
    echo "round $r, $cfg: cpu_user_s cpu_sys_s wall_s $(cat "$log.time"), line gpu_ms $(awk '$1 == "ipsvi_line" {print $3}' "$log"); $(grep -m1 '^line shape' "$log" || echo 'line shape: not reported')"
    rm -f "$log" "$log.time"
  done
done
