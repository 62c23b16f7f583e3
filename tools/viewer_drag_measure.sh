#!/usr/bin/env bash
# How long an interactive `sweeplab view` takes to answer a mouse drag: the
# viewer runs as a user runs it (no --frames: previews while dragging, idle
# once the full frame is shown), xdotool drags the camera once the first full
# frame is on screen, and the frames' present times in the log are lined up
# with the drag's start. Needs xdotool (apt-get install xdotool) and an X
# server on $DISPLAY (e.g. Xvfb :99 -screen 0 1280x1024x24 &).
#   DISPLAY=:99 tools/viewer_drag_measure.sh [TECHNIQUE] [SIZE] [SETTLE_S]
# SETTLE_S: seconds to wait for the first full frame (default 90).
set -euo pipefail
technique=${1:-ipsvi}
size=${2:-256x256}
settle=${3:-90}
command -v xdotool >/dev/null || { echo "needs xdotool: apt-get install xdotool" >&2; exit 1; }
bin=$(cd "$(dirname "$0")/.." && pwd)/target/release/sweeplab
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
now_ms() { date +%s%3N; }
"$bin" view --technique "$technique" --size "$size" --log-json "$dir/log.json" >"$dir/out.txt" 2>&1 &
viewer=$!
window=""
for _ in $(seq 100); do
    window=$(xdotool search --name "sweeplab view" 2>/dev/null | head -n1) && [ -n "$window" ] && break
    sleep 0.1
done
[ -n "$window" ] || { echo "no viewer window" >&2; kill "$viewer"; exit 1; }
# The first full frame: the viewer goes idle after it.
sleep "$settle"
eval "$(xdotool getwindowgeometry --shell "$window")"
x=$((X + WIDTH - 128)); y=$((Y + 128))
xdotool mousemove "$x" "$y"
start=$(now_ms)
xdotool mousedown 1
for i in $(seq 1 10); do
    xdotool mousemove "$((x + 4 * i))" "$y"
    sleep 0.05
done
xdotool mouseup 1
sleep 5
# Q quits (the log is written at the end).
xdotool windowfocus "$window" 2>/dev/null || true
xdotool key q
wait "$viewer" || { cat "$dir/out.txt" >&2; exit 1; }
python3 - "$dir/log.json" "$start" <<'PY'
import json, sys
frames = json.load(open(sys.argv[1]))["frames"]
start = float(sys.argv[2])
after = [f for f in frames if f["presented_unix_ms"] > start]
full_before = [f for f in frames if f["presented_unix_ms"] <= start and f["preview_scale"] == 1]
print(f"{len(full_before)} frames before the drag; the last full one took {full_before[-1]['gpu_ms']:.0f} ms GPU" if full_before else "no full frame before the drag")
for f in after[:12]:
    print(f"+{f['presented_unix_ms'] - start:7.0f} ms  {f['image_width']}x{f['image_height']} (1/{f['preview_scale']})"
          f"{'  reshown' if f['reshown'] else ''}  frame {f['frame_ms']:.0f} ms, GPU {f['gpu_ms']:.0f} ms")
first = next((f for f in after if not f["reshown"]), None)
if first:
    print(f"the drag was answered {first['presented_unix_ms'] - start:.0f} ms after it began (a {first['image_width']}x{first['image_height']} frame)")
PY
