#!/bin/bash
# The line shape (invocations per line dispatch, longest serial chain) of the
# CT engine's IPSVI frame, scene defaults, for the serial kernel and the
# segmented one at 8 segments (lavapipe's own 8-lane subgroup) and at 16 to
# 128 (a pixel's segments across 2 to 16 subgroups of its workgroup), in the
# default 4 rounds and in 1 round, at 256 and 512, for each build given as
# name=path:
#   docs/bench/lavapipe-engine/ipsvi_segment_chains.sh now=target/release/sweeplab
# Output: one "build size kernel: line shape ..." line per frame
# (ipsvi_segment_chains.txt). The chain counts samples, not time: it is the
# same on any device that runs the same settings.
set -eu
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}
vol=${VOLUME:-data/engine.vti}
echo "# $(date -u +%FT%TZ), volume $vol, builds: $*"
for a in "$@"; do
  name=${a%%=*}; path=${a#*=}
  for size in 256 512; do
    for cfg in "serial 0 4" "segmented 8 4" "segmented 16 4" "segmented 32 4" "segmented 64 4" "segmented 128 4" \
               "segmented 32 1" "segmented 128 1"; do
      set -- $cfg
      kernel=(--set "ipsvi.line_kernel=\"$1\"")
      [ "$1" = serial ] || kernel+=(--set "ipsvi.segments=$2" --set "ipsvi.segment_rounds=$3")
      shape=$("$path" render --volume "$vol" --size ${size}x${size} --technique ipsvi "${kernel[@]}" \
        --out /tmp/segment_chains.png 2>&1 | grep -E '^line shape|^error')
      echo "$name $size $1 x$2 rounds $3: $shape"
    done
  done
done
