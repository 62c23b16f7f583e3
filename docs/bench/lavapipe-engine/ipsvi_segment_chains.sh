#!/bin/bash
# The line shape (invocations per line dispatch, longest serial chain) of the
# CT engine's IPSVI frame, scene defaults, for the serial kernel and the
# segmented one at 2, 4 and 8 segments (lavapipe's own 8-lane subgroups)
# and 16 (LP_NATIVE_VECTOR_WIDTH=512: 16-lane subgroups, the widest lavapipe
# compiles), at 256 and 512, for each build given as name=path:
#   docs/bench/lavapipe-engine/ipsvi_segment_chains.sh before=/tmp/before/sweeplab now=target/release/sweeplab
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
    for cfg in "256 serial 0" "256 segmented 2" "256 segmented 4" "256 segmented 8" "512 segmented 16"; do
      set -- $cfg
      # A shader cache per vector width: Mesa 22.3's does not key on it, and a
      # shader compiled at one width runs silently wrong at another.
      shape=$(LP_NATIVE_VECTOR_WIDTH=$1 MESA_SHADER_CACHE_DIR="${TMPDIR:-/tmp}/sweeplab-mesa-shader-cache-lp$1" "$path" render --volume "$vol" --size ${size}x${size} --technique ipsvi \
        --set "ipsvi.line_kernel=\"$2\"" --set "ipsvi.segments=$3" --out /tmp/segment_chains.png 2>&1 |
        grep -E '^line shape|^error')
      echo "$name $size $2 x$3 ($1-bit vectors): $shape"
    done
  done
done
