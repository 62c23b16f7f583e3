#!/bin/bash
# Issue 23's goal for the paper's write rule at 512x512 on engine.vti: every-sample
# (texel write pass, the default pass) with the visible box, against DVR and the
# default frame, 3 alternating rounds: the line dispatches' GPU ms (DVR: its
# one pass), process CPU seconds. Then the RMSE of the every-sample frame.
# Output: ipsvi_every_sample_goal_512_alternating.txt. From the repository root
# after `cargo build --release`.
set -eu
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}
vol=${VOLUME:-../shared/data/engine.vti}
bin=./target/release/sweeplab
echo "commit $(git rev-parse --short HEAD), $(date -u +%FT%TZ), volume $vol, load $(cut -d' ' -f1-3 /proc/loadavg)"
every=(--technique ipsvi --set 'ipsvi.write_rule="every-sample"' --set ipsvi.fit_to_visible=true)
for r in 1 2 3; do
  for cfg in dvr default every; do
    case $cfg in
      dvr) args=(--technique dvr) ;;
      default) args=(--technique ipsvi) ;;
      every) args=("${every[@]}") ;;
    esac
    log=$(mktemp)
    /usr/bin/time -f "%U %S" -o "$log.time" $bin render --volume "$vol" --size 512x512 "${args[@]}" \
      --out /tmp/every_goal_$cfg.png > "$log" 2>&1
    [ "$r" = 1 ] && [ "$cfg" = dvr ] && grep -m1 '^device:' "$log"
    echo "round $r, $cfg: cpu_user_s cpu_sys_s $(cat "$log.time"), gpu_ms $(awk '$1 == "total" {print $2; exit}' "$log")"
    rm -f "$log" "$log.time"
  done
done
$bin compare --volume "$vol" --size 512x512 "${every[@]}" 2>&1 | grep -E '^(rmse|gpu_ms|reference_gpu_ms) '
