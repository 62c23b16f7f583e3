#!/usr/bin/env bash
# The README's gallery and sample output, regenerated from the current build:
# the one way to change them. Renders every technique's image at 256x256 and
# the image at the top at 512x512 (docs/images/), writes what each render
# reported (dispatches and barriers per frame) to docs/images/gallery.json,
# runs `sweeplab bench sync --quick` for the sample verdicts, and rewrites the
# README's blocks between `<!-- gallery:NAME -->` and `<!-- end gallery:NAME -->`
# from them, naming the build, the device and the date. The suite's test
# `readme_gallery` fails when the README's counts and the build disagree.
#
#   tools/gallery.sh              everything (about 5 min on 2 cores with lavapipe)
#   tools/gallery.sh --no-bench   the images and counts, not the bench sample
set -euo pipefail
cd "$(dirname "$0")/.."
bench=1
case "${1:-}" in
  "") ;;
  --no-bench) bench=0 ;;
  *) echo "usage: tools/gallery.sh [--no-bench]" >&2; exit 2 ;;
esac
source tools/setup.sh
cd "$(dirname "${BASH_SOURCE[0]}")/.."
cargo build --release --quiet --bin sweeplab
bin=target/release/sweeplab
images=docs/images
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

slab=tests/scenes/slab-under-sphere.toml
cornell=tests/scenes/cornell-box.toml
# technique | scene | what the README says it is
rows=(
  "dvr|$slab|unshaded"
  "phong|$slab|gradient Blinn-Phong"
  "reference|$slab|ground truth, brute-force shadow rays"
  "ipsvi|$slab|image plane sweep, a dispatch and a barrier per line"
  "half-angle|$slab|half-angle slicing, a dispatch and a barrier per slice"
  "lightvolume|$slab|illumination volume, selective light updates"
  "ao|$cornell|ambient occlusion and colour bleeding"
)

# render OUT SIZE TECHNIQUE SCENE: renders with the scene's defaults and
# prints "DISPATCHES BARRIERS SECONDS" from what sweeplab reports.
render() {
  local out=$1 size=$2 technique=$3 scene=$4 log="$work/render.log" t0 t1
  t0=$(date +%s.%N)
  if ! "$bin" render --scene "$scene" --technique "$technique" --size "$size" --out "$out" >"$log" 2>&1; then
    cat "$log" >&2
    echo "gallery: sweeplab render --technique $technique failed" >&2
    exit 1
  fi
  t1=$(date +%s.%N)
  local counts
  counts=$(sed -nE 's/.*\(([0-9]+) dispatch(es)?, ([0-9]+) barriers?\)$/\1 \3/p' "$log" | tail -n 1)
  [ -n "$counts" ] || { cat "$log" >&2; echo "gallery: no dispatch count in the output" >&2; exit 1; }
  echo "$counts $(awk -v a="$t0" -v b="$t1" 'BEGIN{printf "%.1f", b - a}')"
}

# The first device's name: the second line of the devices table, up to the column gap.
device=$("$bin" devices 2>/dev/null | sed -n 2p | sed -E 's/^[ *]*[0-9]+ +//; s/ {2,}.*//')
device=${device:-unknown device}
# The build's commit, `-dirty` where what it is built from differs (build.rs's
# rule): the README and the images this script rewrites do not make it dirty.
commit=$(git rev-parse --short=12 HEAD)$( [ -z "$(git status --porcelain --untracked-files=no -- src glsl build.rs Cargo.toml Cargo.lock)" ] || echo "-dirty")
date=$(date -u +%Y-%m-%d)
cpu=$(sed -nE 's/^model name\s*:\s*//p' /proc/cpuinfo | head -n 1)
cores=$(nproc)

json_rows=()
table="| technique | image | dispatches / barriers per frame | command |
| --- | --- | ---: | --- |"
first=1
for row in "${rows[@]}"; do
  IFS='|' read -r technique scene what <<<"$row"
  echo "gallery: $technique" >&2
  read -r dispatches barriers seconds < <(render "$images/$technique.png" 256x256 "$technique" "$scene")
  json_rows+=("    {\"technique\": \"$technique\", \"scene\": \"$scene\", \"size\": \"256x256\", \"dispatches\": $dispatches, \"barriers\": $barriers, \"seconds\": $seconds}")
  counts="$dispatches / $barriers"
  [ "$technique" = ao ] && counts="$counts (+ preprocessing, cached)"
  if [ "$first" = 1 ] || [ "$scene" != "$slab" ]; then
    command="\`sweeplab render --scene $scene --technique $technique --size 256x256\`"
  else
    command="\`... --technique $technique\`"
  fi
  first=0
  table+="
| \`$technique\`: $what | ![$technique]($images/$technique.png) | $counts | $command |"
done

echo "gallery: the image at the top (ipsvi, 512x512)" >&2
read -r top_dispatches top_barriers top_seconds < <(render "$images/render.png" 512x512 ipsvi "$slab")
top_command="sweeplab render --scene $slab --technique ipsvi --size 512x512 --out $images/render.png"

{
  echo "{"
  echo "  \"tool\": \"tools/gallery.sh\", \"build\": \"$commit\", \"device\": \"$device\", \"date\": \"$date\","
  echo "  \"host\": \"$cpu, $cores cores\","
  echo "  \"rows\": ["
  for i in "${!json_rows[@]}"; do
    sep=","
    [ "$i" -eq $((${#json_rows[@]} - 1)) ] && sep=""
    echo "${json_rows[$i]}$sep"
  done
  echo "  ],"
  echo "  \"top\": {\"technique\": \"ipsvi\", \"scene\": \"$slab\", \"size\": \"512x512\", \"dispatches\": $top_dispatches, \"barriers\": $top_barriers, \"seconds\": $top_seconds}"
  echo "}"
} >"$images/gallery.json"

cat >"$work/gallery.md" <<EOF
The slab-under-sphere scene (\`$slab\`; AO on the Cornell box), 256x256, each technique with
the scene's defaults (nothing set), on $device. Dispatches and barriers per frame as
\`sweeplab render\` reports them. Made by \`tools/gallery.sh\` from build $commit on $date.

$table

The image at the top: \`$top_command\` ($top_dispatches dispatches, $top_barriers barriers).
EOF

# replace_block NAME FILE: the README's lines between the block's markers become FILE.
replace_block() {
  local name=$1 file=$2
  grep -q "^<!-- gallery:$name -->\$" README.md && grep -q "^<!-- end gallery:$name -->\$" README.md || {
    echo "gallery: README.md has no <!-- gallery:$name --> block" >&2
    exit 1
  }
  awk -v start="<!-- gallery:$name -->" -v end="<!-- end gallery:$name -->" -v file="$file" '
    $0 == start { print; while ((getline line < file) > 0) print line; skip = 1; next }
    $0 == end { skip = 0 }
    !skip { print }' README.md >"$work/README.md"
  mv "$work/README.md" README.md
}
replace_block table "$work/gallery.md"

if [ "$bench" = 1 ]; then
  echo "gallery: sweeplab bench sync --quick (about 90 s)" >&2
  t0=$(date +%s)
  "$bin" bench sync --quick --out-dir "$work/bench-sync" >"$work/bench.out" 2>"$work/bench.err" || {
    cat "$work/bench.err" >&2
    exit 1
  }
  seconds=$(($(date +%s) - t0))
  {
    echo "On $device, on this $cores-core machine ($cpu; \`sweeplab bench sync --quick\`, build"
    echo "$commit, $date, $seconds s):"
    echo
    echo '```'
    grep -v -e '^\s*$' -e '^wrote into ' "$work/bench.out"
    echo '```'
  } >"$work/bench.md"
  replace_block bench-sync "$work/bench.md"
fi
echo "gallery: wrote $images/*.png, $images/gallery.json and README.md's gallery blocks" >&2
