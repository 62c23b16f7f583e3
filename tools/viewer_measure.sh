#!/usr/bin/env bash
# Viewer cost against headless rendering: the DVR frame time
# in `sweeplab view` (under the X server of $DISPLAY, e.g. Xvfb) beside the
# headless `render`'s GPU time at the same size, and the panel's own cost per
# frame (its `ui` profiler scope on the GPU, its layout on the host).
#   DISPLAY=:99 tools/viewer_measure.sh [SIZE] [FRAMES] [RENDERS]
# Medians; the viewer's first two frames (pipeline and swapchain warm-up) are
# left out. Prints a Markdown table.
set -euo pipefail
size=${1:-512x512}
frames=${2:-12}
renders=${3:-5}
bin=$(cd "$(dirname "$0")/.." && pwd)/target/release/sweeplab
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
cd "$dir"
for i in $(seq "$renders"); do
    "$bin" render --size "$size" --technique dvr --out r.png --profile-json "render-$i.json" >/dev/null 2>&1
done
"$bin" view --size "$size" --technique dvr --frames "$frames" --no-ui --log-json no-ui.json >/dev/null 2>&1
"$bin" view --size "$size" --technique dvr --frames "$frames" --log-json ui.json >/dev/null 2>&1
python3 - "$renders" "$size" <<'PY'
import json, statistics as st, sys
renders, size = int(sys.argv[1]), sys.argv[2]
headless = st.median(json.load(open(f"render-{i}.json"))["gpu_ms_total"] for i in range(1, renders + 1))
print(f"DVR {size}, headless render GPU time (median of {renders}): {headless:.1f} ms\n")
print("| viewer | frame ms | technique GPU ms | frame / headless GPU | frame / own GPU | present_blit GPU ms | ui GPU ms | ui host ms |")
print("|---|---|---|---|---|---|---|---|")
for name in ["no-ui", "ui"]:
    f = json.load(open(f"{name}.json"))["frames"][2:]
    m = lambda key: st.median((x[key] or 0.0) for x in f)
    print(f"| {name} | {m('frame_ms'):.1f} | {m('gpu_ms'):.1f} | {m('frame_ms') / headless:.2f}x | "
          f"{m('frame_ms') / m('gpu_ms'):.2f}x | {m('present_gpu_ms'):.2f} | {m('ui_gpu_ms'):.2f} | {m('ui_cpu_ms'):.2f} |")
PY
