#!/bin/bash
# 3 alternating rounds at 512x512, engine.vti: process CPU seconds (user+sys) and GPU ms per frame.
B=/tmp/wta-sweeplab3; V=/work/shared/data/engine.vti
export XDG_RUNTIME_DIR=/tmp
for round in 1 2 3; do
 for cfg in dvr non-empty every-sample light-rays; do
  case $cfg in
   dvr) args=(--technique dvr);;
   light-rays) args=(--technique ipsvi --set 'ipsvi.cache_update="light-rays"');;
   *) args=(--technique ipsvi --set "ipsvi.write_rule=\"$cfg\"");;
  esac
  out=$( /usr/bin/time -f "CPU %U %S" $B render --volume $V --size 512x512 "${args[@]}" --out /tmp/wta-alt.png 2>&1 )
  cpu=$(echo "$out" | grep "^CPU" | awk '{print $2+$3}')
  gpu=$(echo "$out" | grep "^total" | head -1)
  echo "round $round $cfg cpu_s $cpu | $gpu"
 done
done
