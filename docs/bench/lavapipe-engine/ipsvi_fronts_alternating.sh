#!/bin/bash
# IPSVI piecewise fronts (ipsvi.read_fronts: the blended depth of a read's
# four texels, the paper's, against each texel's own) under both write
# rules, with light rays beside them, on engine.vti at 256x256 and 512x512:
# 3 alternating rounds of process CPU seconds (user, sys), wall seconds and
# the line dispatches' GPU ms per render, then each configuration's error
# against the ground truth (`sweeplab compare`, deterministic: once).
# Output: ipsvi_fronts_alternating.txt. Run from the repository root after
# `cargo build --release`.
set -eu
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}
vol=${VOLUME:-../shared/data/engine.vti}
echo "commit $(git rev-parse --short HEAD), $(date -u +%FT%TZ), volume $vol, load $(cut -d' ' -f1-3 /proc/loadavg)"
./target/release/sweeplab render --volume "$vol" --size 8x8 --technique dvr --out /tmp/fronts_device.png 2>&1 | grep -m1 '^device:'
configs=("non-empty blended" "non-empty per-texel" "every-sample blended" "every-sample per-texel" "rays blended")
settings() {
  if [ "$1" = rays ]; then echo "--set ipsvi.cache_update=\"light-rays\" --set ipsvi.read_fronts=\"$2\""
  else echo "--set ipsvi.write_rule=\"$1\" --set ipsvi.read_fronts=\"$2\""; fi
}
for size in 256 512; do
  for r in 1 2 3; do
    for cfg in "${configs[@]}"; do
      set -- $cfg
      log=$(mktemp)
      /usr/bin/time -f "%U %S %e" -o "$log.time" ./target/release/sweeplab render --volume "$vol" --size ${size}x$size \
        --technique ipsvi $(settings $1 $2) --out "/tmp/fronts_$1_$2_$size.png" > "$log" 2>&1
      echo "$size round $r, $1 read_fronts=$2: cpu_user_s cpu_sys_s wall_s $(cat "$log.time"), line gpu_ms $(awk '$1 == "ipsvi_line" {print $3}' "$log")"
      rm -f "$log" "$log.time"
    done
  done
done
for size in 256 512; do
  for cfg in "${configs[@]}"; do
    set -- $cfg
    echo "$size $1 read_fronts=$2: $(./target/release/sweeplab compare --volume "$vol" --size ${size}x$size --technique ipsvi \
      $(settings $1 $2) 2>&1 | grep -E '^(rmse|max_abs)' | tr -s ' ' | tr '\n' ' ')"
  done
done
