#!/bin/bash
# IPSVI write passes (sample loop against per-texel invocations) at 256x256 on
# engine.vti, with light rays, in 4 alternating rounds: process CPU seconds
# (user, sys), wall seconds and the line dispatches' GPU ms of each render.
# Output: ipsvi_write_pass_256_alternating.txt. Run from the repository root
# after `cargo build --release`.
set -eu
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}
vol=${VOLUME:-../shared/data/engine.vti}
echo "commit $(git rev-parse --short HEAD), $(date -u +%FT%TZ), volume $vol, load $(cut -d' ' -f1-3 /proc/loadavg)"
./target/release/sweeplab render --volume "$vol" --size 8x8 --technique dvr --out /tmp/write_pass_device.png 2>&1 | grep -m1 '^device:'
for r in 1 2 3 4; do
  for cfg in "non-empty sample" "non-empty texel" "every-sample sample" "every-sample texel" "non-empty rays"; do
    set -- $cfg
    extra="--set ipsvi.write_pass=\"$2\""
    [ "$2" = rays ] && extra="--set ipsvi.cache_update=\"light-rays\""
    log=$(mktemp)
    /usr/bin/time -f "%U %S %e" -o "$log.time" ./target/release/sweeplab render --volume "$vol" --size 256x256 \
      --technique ipsvi --set ipsvi.write_rule=\"$1\" $extra --out "/tmp/write_pass_$1_$2.png" > "$log" 2>&1
    echo "round $r, $1 $2: cpu_user_s cpu_sys_s wall_s $(cat "$log.time"), line gpu_ms $(awk '$1 == "ipsvi_line" {print $3}' "$log")"
    rm -f "$log" "$log.time"
  done
done
cmp /tmp/write_pass_non-empty_sample.png /tmp/write_pass_non-empty_texel.png
cmp /tmp/write_pass_every-sample_sample.png /tmp/write_pass_every-sample_texel.png
echo "PNGs of both write passes identical under both write rules"
