#!/usr/bin/env bash
# The main job: set up, build, and render the known-shadow scene (a sphere over a
# slab, light from above) with image plane sweep volume illumination, one
# dispatch and one barrier per line, timed per line: prints the per-pass GPU
# profile (the `ipsvi_line` row: lines, total and mean per line) and writes the
# image, the profile with every line's time, and a Perfetto trace.
# Arguments replace the defaults and go to `sweeplab render`
# (e.g. --technique reference, or --volume data/engine.vti).
set -euo pipefail
cd "$(dirname "$0")/.."
source tools/setup.sh
cargo build --release --quiet
# `sweeplab` on PATH, as the README writes every command: a link to this
# build in /usr/local/bin (root, as the README runs it), else ~/.local/bin.
link_dir=/usr/local/bin
[ -w "$link_dir" ] || link_dir="$HOME/.local/bin"
mkdir -p "$link_dir" && ln -sf "$(pwd)/target/release/sweeplab" "$link_dir/sweeplab"
case ":$PATH:" in
  *":$link_dir:"*) ;;
  *) echo "note: $link_dir is not on PATH; add it to run \`sweeplab\` by name" ;;
esac
mkdir -p out
# `sweeplab render` alone renders this scene with IPSVI's defaults (the paper's
# view-sample cache), timed per line.
./target/release/sweeplab render --out out/render.png --profile-json out/profile.json --trace out/trace.json "$@"
echo "wrote out/render.png (the sphere's shadow on the slab), out/profile.json (per-pass and per-line GPU times) and out/trace.json (open in Perfetto); \`sweeplab\` is $link_dir/sweeplab"
