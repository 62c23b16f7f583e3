#!/usr/bin/env bash
# The main job: set up, build, render the embedded default scene (3D Shepp-Logan
# phantom, one directional light) and print its per-pass GPU profile.
# Extra arguments go to `sweeplab render` (e.g. --technique reference --size 256x256).
set -euo pipefail
cd "$(dirname "$0")/.."
source tools/setup.sh
cargo build --release --quiet
mkdir -p out
./target/release/sweeplab render --out out/render.png --profile-json out/profile.json --trace out/trace.json "$@"
echo "wrote out/render.png, out/profile.json (per-pass GPU times) and out/trace.json (open in Perfetto)"
