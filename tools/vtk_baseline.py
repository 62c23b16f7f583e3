#!/usr/bin/env python3
"""VTK 9.7's GPU ray caster beside sweeplab, on the same machine, in one run.

What it measures
  VTK: `vtkGPUVolumeRayCastMapper` on a volume file (default data/engine.vti),
  composite blend, sample distance 0.5 voxel (AutoAdjustSampleDistances off, no
  LockSampleDistanceToInputSpacing, ImageSampleDistance 1, no jittering: VTK really
  steps 0.5 voxel), in a W x H offscreen window, in three configurations:
    unshaded  emission-absorption, shading off (what sweeplab's `dvr` computes);
    shaded    gradient shading on (`SetShade(1)`, sweeplab's Phong coefficients, no shadows);
    shadows   shading on plus VTK's volumetric scattering (VTK >= 9.2):
              `SetVolumetricScatteringBlending(2.0)` (volumetric model only) and
              `SetGlobalIlluminationReach(1.0)` (shadow rays through the whole volume):
              the "VTK with shadows" comparison for IPSVI's full shadows.
  Each configuration runs in its own process: the first frame (volume upload, shader
  compile) and then --frames further frames, each `renWin.Render()` followed by
  `renWin.WaitForCompletion()` (glFinish), so a frame's time is complete. Per frame:
  wall-clock seconds and the process CPU seconds (all of llvmpipe's threads).
  sweeplab: `target/release/sweeplab render --volume FILE --size WxH --technique T`
  for T = dvr, ipsvi (defaults: view samples, directional light, full shadows) and
  ipsvi with `--set ipsvi.cache_update="light-rays"`: its GPU ms (`gpu_ms_total` of
  `--profile-json`; on lavapipe the CPU time that executes the command buffers), the
  process wall time and CPU time (start-up, load, pipeline compile, one frame, PNG).
  VTK and sweeplab runs alternate --rounds times, so load changes hit both; medians over
  the rounds are reported, with the load average (/proc/loadavg) before each run.

The camera and the light are given to sweeplab explicitly (`--set camera.distance=...
--set lights.0.direction=...`): since commit 422681d its automatic camera frames the
visible voxels and its light comes from the side, which the VTK scene below does not.
The scene mirrors sweeplab's defaults for `--volume FILE` up to commit dd41002 (src/scene/default_scene.rs,
src/scene/presets.rs::transfer_from_histogram, src/scene/scene_spec.rs): the automatic
transfer function from the volume's histogram (recomputed here the same way), opacity
per voxel length (ScalarOpacityUnitDistance = smallest spacing), orbit camera at azimuth
30, elevation 20, 30 degree vertical field of view framing the bounding sphere with 5 %
margin, black background, one directional light travelling along (1, -1, -1).
What differs: VTK writes its composited colours straight into an 8-bit buffer, sweeplab
composites in linear RGB and encodes sRGB (VTK's image is darker where translucent);
VTK ends rays at its own opacity threshold; VTK's shadow model (its step, its blending
with the gradient model) is its own, not sweeplab's model (ii).

How to run (from the repository root; LP_NUM_THREADS is removed from the children's
environment, so llvmpipe and lavapipe use all cores):
    cargo build --release
    python3 tools/vtk_baseline.py --json out.json --markdown out.md --png vtk.png
Offscreen via EGL (the wheel's vtkEGLRenderWindow, no X server needed) by default;
`--window x` uses GLX instead, under Xvfb: `xvfb-run -a python3 tools/vtk_baseline.py --window x`.

Needs: Python 3.9+, `pip install vtk==9.7.1` (brings numpy), Mesa (llvmpipe for OpenGL,
lavapipe for Vulkan), the built sweeplab binary (`--no-sweeplab` skips it).
Not part of the tests or CI: the record is docs/bench/lavapipe-engine/vtk-baseline.*.
"""

import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
VTK_MODES = ("unshaded", "shaded", "shadows")
# (label, extra sweeplab arguments)
SWEEPLAB_RUNS = (
    ("dvr", ["--technique", "dvr"]),
    ("ipsvi view-samples", ["--technique", "ipsvi"]),
    ("ipsvi light-rays", ["--technique", "ipsvi", "--set", 'ipsvi.cache_update="light-rays"']),
)

# sweeplab's defaults for `--volume FILE` (see the module docstring for where they live).
SAMPLE_DISTANCE_VOXELS = 0.5
CAMERA_AZIMUTH_DEG = 30.0
CAMERA_ELEVATION_DEG = 20.0
CAMERA_FOV_Y_DEG = 30.0
FRAMING_MARGIN = 1.05
LIGHT_DIRECTION = (1.0, -1.0, -1.0)
PHONG = {"ambient": 0.2, "diffuse": 0.8, "specular": 0.3, "shininess": 32.0}
# presets.rs: automatic transfer function.
AUTO_BINS = 256
AUTO_SMOOTHING = 4
AUTO_TOP_PERCENTILE = 0.99
AUTO_MAX_ALPHA = 0.6
AUTO_DARK, AUTO_ORANGE, AUTO_PALE = (0.55, 0.12, 0.05), (0.95, 0.45, 0.15), (1.0, 0.92, 0.8)


def auto_ramp(h):
    """Start and top of the automatic opacity ramp: presets.rs::auto_ramp, line for line."""
    n = len(h)
    bin_width = 1.0 / n
    peak = 0
    for i in range(n // 2):
        if h[i] > h[peak]:
            peak = i
    smoothed = []
    for i in range(n):
        window = h[max(i - AUTO_SMOOTHING, 0) : min(i + AUTO_SMOOTHING + 1, n)]
        smoothed.append(sum(window) / len(window))
    valley = next((i for i in range(peak + 1, n - 1) if smoothed[i] <= smoothed[i + 1]), n - 1)

    def count_from(start):
        return sum(h[min(start, n) :])

    start = valley + 1 if count_from(valley + 1) > 0 else peak + 1
    foreground = count_from(start)
    if foreground == 0:
        return min((peak + 1) * bin_width, 1.0 - bin_width), 1.0

    def percentile_bin(fraction):
        target = -(-foreground * fraction // 1)  # ceil
        seen = 0
        for i in range(start, n):
            seen += h[i]
            if seen >= target:
                return i
        return n - 1

    top = percentile_bin(AUTO_TOP_PERCENTILE)
    first = min(percentile_bin(0.5), (start + top) // 2)
    hi = min((top + 1) * bin_width, 1.0)
    lo = min(first * bin_width, hi - bin_width)
    return lo, hi


def auto_transfer(h):
    """(s, (r, g, b), alpha per voxel) points of presets.rs::transfer_from_histogram."""
    lo, hi = auto_ramp(h)
    points = [(0.0, AUTO_DARK, 0.0), (lo, AUTO_DARK, 0.0)]
    points.append(((lo + hi) * 0.5, AUTO_ORANGE, AUTO_MAX_ALPHA * 0.25))
    points.append((hi, AUTO_PALE, AUTO_MAX_ALPHA))
    if hi < 1.0:
        points.append((1.0, AUTO_PALE, AUTO_MAX_ALPHA))
    return points


def measure_vtk(args):
    """One VTK configuration in this process; returns the record as a dict."""
    import numpy as np
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy

    mode = args.child
    width, height = args.size
    t_load = time.perf_counter()
    reader = vtk.vtkXMLImageDataReader()
    reader.SetFileName(str(args.volume))
    reader.Update()
    image = reader.GetOutput()
    scalars = image.GetPointData().GetScalars()
    if scalars is None or scalars.GetNumberOfComponents() != 1:
        raise SystemExit(f"{args.volume}: needs one scalar component per voxel")
    values = vtk_to_numpy(scalars).astype(np.float64)
    # volume.rs: 8-bit data is s = v / 255, wider types are rescaled from their [min, max].
    if scalars.GetDataType() == vtk.VTK_UNSIGNED_CHAR:
        to_scalar = lambda s: s * 255.0  # noqa: E731
    else:
        vmin, vmax = float(values.min()), float(values.max())
        to_scalar = lambda s: vmin + s * (vmax - vmin)  # noqa: E731
    normalized = (values - to_scalar(0.0)) / max(to_scalar(1.0) - to_scalar(0.0), 1e-30)
    bins = np.minimum((np.clip(normalized, 0.0, 1.0) * AUTO_BINS).astype(np.int64), AUTO_BINS - 1)
    histogram = [int(c) for c in np.bincount(bins, minlength=AUTO_BINS)]
    transfer = auto_transfer(histogram)
    load_s = time.perf_counter() - t_load

    color = vtk.vtkColorTransferFunction()
    opacity = vtk.vtkPiecewiseFunction()
    for s, rgb, alpha in transfer:
        color.AddRGBPoint(to_scalar(s), *rgb)
        opacity.AddPoint(to_scalar(s), alpha)
    spacing = image.GetSpacing()
    voxel = min(spacing)
    prop = vtk.vtkVolumeProperty()
    prop.SetColor(color)
    prop.SetScalarOpacity(opacity)
    # sweeplab's alphas are opacities of one voxel (its smallest spacing) of length.
    prop.SetScalarOpacityUnitDistance(voxel)
    prop.SetInterpolationTypeToLinear()
    prop.SetShade(mode != "unshaded")
    prop.SetAmbient(PHONG["ambient"])
    prop.SetDiffuse(PHONG["diffuse"])
    prop.SetSpecular(PHONG["specular"])
    prop.SetSpecularPower(PHONG["shininess"])

    mapper = vtk.vtkGPUVolumeRayCastMapper()
    mapper.SetInputConnection(reader.GetOutputPort())
    mapper.SetBlendModeToComposite()
    mapper.AutoAdjustSampleDistancesOff()
    mapper.LockSampleDistanceToInputSpacingOff()
    mapper.SetSampleDistance(SAMPLE_DISTANCE_VOXELS * voxel)
    mapper.SetImageSampleDistance(1.0)
    mapper.UseJitteringOff()
    if mode == "shadows":
        mapper.SetVolumetricScatteringBlending(2.0)
        mapper.SetGlobalIlluminationReach(1.0)

    volume = vtk.vtkVolume()
    volume.SetMapper(mapper)
    volume.SetProperty(prop)
    renderer = vtk.vtkRenderer()
    renderer.AddVolume(volume)
    renderer.SetBackground(0.0, 0.0, 0.0)
    window = vtk.vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(width, height)
    window.AddRenderer(renderer)

    # Camera and light as sweeplab's in world units scaled by the longest side.
    bounds = image.GetBounds()
    center = [(bounds[2 * a] + bounds[2 * a + 1]) * 0.5 for a in range(3)]
    extent = [bounds[2 * a + 1] - bounds[2 * a] + spacing[a] for a in range(3)]  # cell box, as sweeplab
    radius = 0.5 * sum(e * e for e in extent) ** 0.5 * FRAMING_MARGIN
    half_y = math.radians(CAMERA_FOV_Y_DEG * 0.5)
    half_x = math.atan(math.tan(half_y) * width / height)
    distance = radius / math.sin(min(half_y, half_x))
    az, el = math.radians(CAMERA_AZIMUTH_DEG), math.radians(CAMERA_ELEVATION_DEG)
    direction = (math.cos(el) * math.sin(az), math.sin(el), math.cos(el) * math.cos(az))
    camera = renderer.GetActiveCamera()
    camera.SetFocalPoint(*center)
    camera.SetPosition(*[c + d * distance for c, d in zip(center, direction)])
    camera.SetViewUp(0.0, 1.0, 0.0)
    camera.SetViewAngle(CAMERA_FOV_Y_DEG)
    renderer.ResetCameraClippingRange()
    light = vtk.vtkLight()
    light.SetLightTypeToSceneLight()
    light.SetPositional(False)
    light.SetFocalPoint(*center)
    light.SetPosition(*[c - d * distance for c, d in zip(center, LIGHT_DIRECTION)])
    light.SetIntensity(1.0)
    renderer.AutomaticLightCreationOff()
    renderer.RemoveAllLights()
    renderer.AddLight(light)

    def frame():
        wall, cpu = time.perf_counter(), time.process_time()
        window.Render()
        window.WaitForCompletion()
        return time.perf_counter() - wall, time.process_time() - cpu

    first_wall, first_cpu = frame()
    walls, cpus = [], []
    for _ in range(args.frames):
        w, c = frame()
        walls.append(w)
        cpus.append(c)

    capabilities = window.ReportCapabilities() or ""
    gl_renderer = next(
        (line.split(":", 1)[1].strip() for line in capabilities.splitlines() if "OpenGL renderer string" in line),
        "unknown",
    )
    gl_version = next(
        (line.split(":", 1)[1].strip() for line in capabilities.splitlines() if "OpenGL version string" in line),
        "unknown",
    )
    if args.png:
        grab = vtk.vtkWindowToImageFilter()
        grab.SetInput(window)
        grab.ReadFrontBufferOff()
        grab.Update()
        shrink = vtk.vtkImageResize()
        shrink.SetInputConnection(grab.GetOutputPort())
        shrink.SetOutputDimensions(args.png_size, args.png_size, 1)
        writer = vtk.vtkPNGWriter()
        writer.SetFileName(str(args.png))
        writer.SetInputConnection(shrink.GetOutputPort())
        writer.Write()
    return {
        "mode": mode,
        "vtk_version": vtk.vtkVersion.GetVTKVersionFull(),
        "window_class": window.GetClassName(),
        "gl_renderer": gl_renderer,
        "gl_version": gl_version,
        # The same camera in sweeplab's world units (the longest side of the
        # cell box is 1), passed to its runs: since sweeplab's automatic camera
        # frames the visible voxels instead, both would otherwise render
        # different pixel counts.
        "sweeplab_camera_distance": distance / max(extent),
        "sample_distance_used": mapper.GetSampleDistance(),
        "auto_adjust_sample_distances": mapper.GetAutoAdjustSampleDistances(),
        "transfer": [[to_scalar(s), list(rgb), a] for s, rgb, a in transfer],
        "load_s": load_s,
        "first_frame_s": first_wall,
        "first_frame_cpu_s": first_cpu,
        "frames_s": walls,
        "frames_cpu_s": cpus,
        "frame_median_s": statistics.median(walls),
        "frame_min_s": min(walls),
        "frame_max_s": max(walls),
        "frame_cpu_median_s": statistics.median(cpus),
    }


def child_env(args):
    env = dict(os.environ)
    # Default thread counts: llvmpipe and lavapipe use every core.
    env.pop("LP_NUM_THREADS", None)
    if args.window == "egl":
        env["VTK_DEFAULT_OPENGL_WINDOW"] = "vtkEGLRenderWindow"
    return env


def run_measured(cmd, env):
    """Runs `cmd`; returns (stdout, stderr, wall s, CPU s of the child and its threads)."""
    start = time.perf_counter()
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        proc = subprocess.Popen(cmd, stdout=out, stderr=err, env=env, cwd=REPO)
        _, status, usage = os.wait4(proc.pid, 0)
        wall = time.perf_counter() - start
        proc.returncode = os.waitstatus_to_exitcode(status)
        out.seek(0)
        err.seek(0)
        stdout, stderr = out.read().decode(), err.read().decode()
    if proc.returncode != 0:
        raise SystemExit(f"{' '.join(map(str, cmd))} failed ({proc.returncode}):\n{stderr[-3000:]}")
    return stdout, stderr, wall, usage.ru_utime + usage.ru_stime


def loadavg():
    return Path("/proc/loadavg").read_text().split()[0:3]


def run_vtk(args, mode, png):
    cmd = [sys.executable, __file__, "--child", mode, "--volume", str(args.volume), "--frames", str(args.frames)]
    cmd += ["--size", f"{args.size[0]}x{args.size[1]}", "--window", args.window]
    if png:
        cmd += ["--png", str(png), "--png-size", str(args.png_size)]
    load = loadavg()
    stdout, _, wall, cpu = run_measured(cmd, child_env(args))
    record = json.loads(stdout.strip().splitlines()[-1])
    record.update({"process_wall_s": wall, "process_cpu_s": cpu, "loadavg_before": load})
    return record


def sweeplab_scene(vtk_record):
    """sweeplab overrides that give it VTK's camera and light: sweeplab's
    `--volume` defaults now frame the visible voxels and light from the side,
    which this script's VTK scene (its defaults up to commit dd41002) does not."""
    light = "[" + ", ".join(f"{c:g}" for c in LIGHT_DIRECTION) + "]"
    return [
        "--set", f"camera.distance={vtk_record['sweeplab_camera_distance']:.6f}",
        "--set", f"lights.0.direction={light}",
    ]


def run_sweeplab(args, label, extra, scratch):
    profile = scratch / "profile.json"
    cmd = [str(args.sweeplab), "render", "--volume", str(args.volume), "--size", f"{args.size[0]}x{args.size[1]}"]
    cmd += extra + ["--out", str(scratch / "sweeplab.png"), "--profile-json", str(profile)]
    load = loadavg()
    stdout, stderr, wall, cpu = run_measured(cmd, child_env(args))
    gpu_ms = json.loads(profile.read_text())["gpu_ms_total"]
    # sweeplab names its Vulkan device on a line "device: NAME (DRIVER, Vulkan X.Y.Z)".
    lines = (stdout + stderr).splitlines()
    device = next((ln[len("device:") :].strip() for ln in lines if ln.startswith("device:")), "?")
    record = {"run": label, "gpu_s": gpu_ms / 1000.0, "process_wall_s": wall, "process_cpu_s": cpu}
    record["command"] = " ".join(map(str, cmd))
    record.update({"loadavg_before": load, "vulkan_device": device})
    return record


def median_of(records, key):
    return statistics.median(r[key] for r in records)


def summary_row(what, runs, frame_key, min_key, max_key, medians=()):
    """Medians over the rounds: the frame (`frame_key`), the process, and `medians` (name, key)."""
    row = {
        "what": what,
        "frame_s": median_of(runs, frame_key),
        "frame_min_s": min(r[min_key] for r in runs),
        "frame_max_s": max(r[max_key] for r in runs),
    }
    for name, key in (*medians, ("process_wall_s", "process_wall_s"), ("process_cpu_s", "process_cpu_s")):
        row[name] = median_of(runs, key)
    return row


def summarize(vtk_runs, sweeplab_runs):
    vtk_medians = (("frame_cpu_s", "frame_cpu_median_s"), ("first_frame_s", "first_frame_s"))
    rows = [
        summary_row(f"VTK {mode}", runs, "frame_median_s", "frame_min_s", "frame_max_s", vtk_medians)
        for mode, runs in vtk_runs.items()
    ]
    rows += [summary_row(f"sweeplab {label}", runs, "gpu_s", "gpu_s", "gpu_s") for label, runs in sweeplab_runs.items()]
    return rows


def host_cpu():
    """The host CPU's model name (lavapipe's speed is the host's), or "unknown"."""
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return "unknown"


def git_commit():
    """The checkout's commit (with -dirty for uncommitted changes): the build the
    sweeplab figures come from, if target/release/sweeplab was built from it."""
    try:
        out = subprocess.run(["git", "describe", "--always", "--dirty", "--abbrev=12"],
                             capture_output=True, text=True, check=True)
        return out.stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def markdown(rows, ratios, meta):
    def cell(row, key):
        return f"{row[key]:.3f}" if key in row else "-"

    lines = [
        f"{meta['size']} on {meta['volume']}, GL renderer `{meta['gl_renderer']}` ({meta['window_class']}),",
        f"Vulkan `{meta['vulkan_device']}`; medians of {meta['rounds']} alternating rounds, "
        f"VTK {meta['frames']} frames after the first; load average {meta['loadavg_range']}.",
        f"Host CPU `{meta['host_cpu']}` ({meta['cores']} cores); sweeplab at `{meta['sweeplab_commit']}`; "
        f"{meta['date']}; `{meta['command']}`.",
        "",
        "| run | frame s (median) | min | max | frame CPU s | first frame s | process wall s | process CPU s |",
        "| :-- | --: | --: | --: | --: | --: | --: | --: |",
    ]
    for r in rows:
        keys = ["frame_s", "frame_min_s", "frame_max_s", "frame_cpu_s", "first_frame_s"]
        keys += ["process_wall_s", "process_cpu_s"]
        lines.append(f"| {r['what']} | " + " | ".join(cell(r, k) for k in keys) + " |")
    lines += [
        "",
        "frame s: wall-clock seconds of one frame (VTK: `Render()` + `WaitForCompletion()`; sweeplab: its GPU",
        "timestamps, which on lavapipe time the CPU threads executing the frame); frame CPU s: VTK's process",
        "CPU time over the frame (all threads); process: the whole process (sweeplab: start-up, load, compile,",
        "one frame, PNG; VTK: import, load, first frame and the timed frames).",
        "",
        "| ratio | wall (frame s / frame s) | CPU (sweeplab process CPU s / VTK frame CPU s) |",
        "| :-- | --: | --: |",
    ]
    lines += [f"| {name} | {v['wall']:.2f} | {v['cpu']:.2f} |" for name, v in ratios.items()]
    return "\n".join(lines) + "\n"


def parse_size(text):
    try:
        w, h = (int(p) for p in text.lower().split("x"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"size {text!r}: expected WxH, e.g. 512x512") from None
    if not (1 <= w <= 8192 and 1 <= h <= 8192):
        raise argparse.ArgumentTypeError(f"size {text!r}: each side must be in [1, 8192]")
    return w, h


def parse_modes(text):
    modes = [m.strip() for m in text.split(",") if m.strip()]
    for m in modes:
        if m not in VTK_MODES:
            import difflib

            near = difflib.get_close_matches(m, VTK_MODES, n=1)
            hint = f" (did you mean {near[0]!r}?)" if near else ""
            raise argparse.ArgumentTypeError(f"VTK mode {m!r} unknown{hint}; known: {', '.join(VTK_MODES)}")
    return modes


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n", 1)[0])
    p.add_argument("--volume", type=Path, default=REPO / "data" / "engine.vti")
    p.add_argument("--size", type=parse_size, default=(512, 512), help="WxH (default 512x512)")
    p.add_argument("--frames", type=int, default=5, help="VTK frames timed after the first (default 5)")
    p.add_argument("--rounds", type=int, default=3, help="alternating VTK/sweeplab rounds (default 3)")
    p.add_argument("--modes", type=parse_modes, default=list(VTK_MODES), help="VTK configurations, comma-separated")
    p.add_argument("--window", choices=("egl", "x"), default="egl", help="offscreen EGL, or GLX (under Xvfb)")
    p.add_argument("--sweeplab", type=Path, default=REPO / "target" / "release" / "sweeplab")
    p.add_argument("--no-sweeplab", action="store_true", help="time VTK only")
    p.add_argument("--json", type=Path, help="write every run and the summary as JSON")
    p.add_argument("--markdown", type=Path, help="write the summary table as Markdown")
    p.add_argument("--png", type=Path, help="save VTK's unshaded frame (the first mode's, last round)")
    p.add_argument("--png-size", type=int, default=256)
    p.add_argument("--child", choices=VTK_MODES, help=argparse.SUPPRESS)
    args = p.parse_args()
    if args.frames < 1 or args.rounds < 1:
        p.error("--frames and --rounds must be at least 1")
    if not args.volume.is_file():
        p.error(f"volume {args.volume} not found")
    args.volume = args.volume.resolve()

    if args.child:
        print(json.dumps(measure_vtk(args)))
        return
    if not args.no_sweeplab and not args.sweeplab.is_file():
        p.error(f"{args.sweeplab} not found: run `cargo build --release` or pass --no-sweeplab")

    vtk_runs = {m: [] for m in args.modes}
    sweeplab_runs = {label: [] for label, _ in SWEEPLAB_RUNS} if not args.no_sweeplab else {}
    with tempfile.TemporaryDirectory() as scratch:
        scratch = Path(scratch)
        for round_index in range(args.rounds):
            last = round_index == args.rounds - 1
            for i, mode in enumerate(args.modes):
                png = args.png if (last and i == 0 and args.png) else None
                record = run_vtk(args, mode, png)
                vtk_runs[mode].append(record)
                print(f"round {round_index + 1} VTK {mode}: frame {record['frame_median_s']:.3f} s", file=sys.stderr)
            scene = sweeplab_scene(vtk_runs[args.modes[0]][-1])
            for label, extra in SWEEPLAB_RUNS if not args.no_sweeplab else ():
                record = run_sweeplab(args, label, scene + extra, scratch)
                sweeplab_runs[label].append(record)
                print(f"round {round_index + 1} sweeplab {label}: GPU {record['gpu_s']:.3f} s", file=sys.stderr)

    rows = summarize(vtk_runs, sweeplab_runs)
    by_name = {r["what"]: r for r in rows}
    # Wall: sweeplab's GPU time over VTK's frame. CPU (robust to the other processes'
    # load): sweeplab's whole process over VTK's frame, so sweeplab's start-up counts
    # against it.
    ratios = {}
    for ours in ("sweeplab dvr", "sweeplab ipsvi view-samples", "sweeplab ipsvi light-rays"):
        for theirs in ("VTK unshaded", "VTK shaded", "VTK shadows"):
            if ours in by_name and theirs in by_name:
                a, b = by_name[ours], by_name[theirs]
                ratios[f"{ours} / {theirs}"] = {
                    "wall": a["frame_s"] / b["frame_s"],
                    "cpu": a["process_cpu_s"] / b["frame_cpu_s"],
                }
    loads = [float(r["loadavg_before"][0]) for runs in (*vtk_runs.values(), *sweeplab_runs.values()) for r in runs]
    first = next(iter(vtk_runs.values()))[0]
    meta = {
        "volume": args.volume.name,
        "size": f"{args.size[0]}x{args.size[1]}",
        "rounds": args.rounds,
        "frames": args.frames,
        "vtk_version": first["vtk_version"],
        "gl_renderer": first["gl_renderer"],
        "gl_version": first["gl_version"],
        "window_class": first["window_class"],
        "vulkan_device": next((r["vulkan_device"] for runs in sweeplab_runs.values() for r in runs), "not run"),
        "lp_num_threads": "unset (llvmpipe/lavapipe default: all cores)",
        "cores": os.cpu_count(),
        "loadavg_range": f"{min(loads):.2f}-{max(loads):.2f}",
        "command": " ".join([Path(sys.executable).name, *sys.argv]),
        "host_cpu": host_cpu(),
        "sweeplab_commit": git_commit(),
        "date": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
    }
    table = markdown(rows, ratios, meta)
    print(table)
    if args.markdown:
        args.markdown.write_text(table)
    if args.json:
        result = {"meta": meta, "summary": rows, "ratios": ratios, "vtk_runs": vtk_runs, "sweeplab_runs": sweeplab_runs}
        args.json.write_text(json.dumps(result, indent=2) + "\n")


if __name__ == "__main__":
    main()
