#!/usr/bin/env bash
# The main job: set up, build, and render the known-shadow scene (a sphere over a
# slab, light from above) with image plane sweep volume illumination, one
# dispatch and one barrier per line, timed per line: prints the per-pass GPU
# profile (the `ipsvi_line` row: lines, total and mean per line) and writes the
# image, the profile with every line's time, and a Perfetto trace.
# Arguments replace the defaults and go to `sweeplab render`
# (e.g. --technique reference, or --volume ../shared/data/engine.vti).
set -euo pipefail
cd "$(dirname "$0")/.."
source tools/setup.sh
cargo build --release --quiet
mkdir -p out
# `sweeplab render` alone renders this scene with IPSVI's defaults (the paper's
# view-sample cache), timed per line.
./target/release/sweeplab render --out out/render.png --profile-json out/profile.json --trace out/trace.json "$@"
echo "wrote out/render.png (the sphere's shadow on the slab), out/profile.json (per-pass and per-line GPU times) and out/trace.json (open in Perfetto)"
