#!/bin/bash
# The line shape (invocations per line dispatch, longest serial chain) of the
# CT engine's IPSVI frame for the serial kernel and the segmented one at 8
# segments (lavapipe's own 8-lane subgroup) and at 16 to 128 (a pixel's
# segments across 2 to 16 subgroups of its workgroup), at 256 and 512 (SIZES),
# for each build given as name=path:
#   docs/bench/lavapipe-engine/ipsvi_segment_chains.sh now=target/release/sweeplab
# The scene defaults of `render --volume data/engine.vti` (one light), or with
# SCENE a scene file, and SET extra settings, e.g. the paper's Table 1 scene:
#   SCENE=tests/scenes/engine.toml SET=ipsvi.cache_size=256 \
#     CONFIGS="serial-0 segmented-32 segmented-64 segmented-128" ... now=...
# A config kernel-segments-rounds sets ipsvi.segment_rounds as well, which
# only builds before the view-stops pass know (they marched in rounds), and
# kernel-segments-rounds-texels ipsvi.texel_segments (rounds may be empty:
# segmented-128--16). Texel lanes above lavapipe's 8-lane subgroup need
# LP_NATIVE_VECTOR_WIDTH=512 (16 lanes), which gets a Mesa shader cache of its
# own ($TMPDIR/sweeplab-mesa-shader-cache-lp512: docs/testing.md).
# Output: one "build size kernel: line shape ..." line per frame
# (ipsvi_segment_chains*.txt). The chain counts samples, not time: it is the
# same on any device that runs the same settings.
set -eu
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}
if [ -n "${LP_NATIVE_VECTOR_WIDTH:-}" ] && [ -z "${MESA_SHADER_CACHE_DIR:-}" ]; then
  export MESA_SHADER_CACHE_DIR="${TMPDIR:-/tmp}/sweeplab-mesa-shader-cache-lp$LP_NATIVE_VECTOR_WIDTH"
fi
if [ -n "${SCENE:-}" ]; then input=(--scene "$SCENE"); else input=(--volume "${VOLUME:-data/engine.vti}"); fi
extra=()
for s in ${SET:-}; do extra+=(--set "$s"); done
configs=${CONFIGS:-serial-0 segmented-8 segmented-16 segmented-32 segmented-64 segmented-128}
echo "# $(date -u +%FT%TZ), ${input[*]} ${extra[*]}, builds: $*"
for a in "$@"; do
  name=${a%%=*}; path=${a#*=}
  for size in ${SIZES:-256 512}; do
    for cfg in $configs; do
      IFS=- read -r kernel segments rounds texels <<<"$cfg"
      k=(--set "ipsvi.line_kernel=\"$kernel\"")
      [ "$kernel" = serial ] || k+=(--set "ipsvi.segments=$segments")
      [ -z "$rounds" ] || k+=(--set "ipsvi.segment_rounds=$rounds")
      [ -z "$texels" ] || k+=(--set "ipsvi.texel_segments=$texels")
      shape=$("$path" render "${input[@]}" --size ${size}x${size} --technique ipsvi "${extra[@]}" "${k[@]}" \
        --out /tmp/segment_chains.png 2>&1 | grep -E '^line shape|^error')
      echo "$name $size $kernel x$segments${rounds:+ rounds $rounds}${texels:+ texels $texels}: $shape"
    done
  done
done
