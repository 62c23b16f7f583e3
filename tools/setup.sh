#!/usr/bin/env bash
# Installs what sweeplab needs on a fresh Debian machine (as root), only where
# missing, and sets the environment the build needs (the callers build). Safe to
# run again.
#   Vulkan loader + lavapipe (CPU Vulkan) + Khronos validation layers,
#   Xvfb and the X11 libraries of the viewer (and its tests),
#   Debian's static shaderc/glslang/SPIRV-Tools (build.rs links them: no 12-minute
#   source build), and a Rust toolchain if none is on PATH.
set -euo pipefail
# Its own folder, also when sourced from a script run by a relative path.
cd "$(dirname "${BASH_SOURCE[0]}")/.."

packages=(
  libvulkan1 libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers vulkan-tools
  libshaderc-dev glslang-dev spirv-tools
  pkg-config gcc g++ ca-certificates curl
  # sweeplab view: Xvfb for its tests, and the X11 libraries winit loads at run time.
  xvfb xauth libx11-6 libx11-xcb1 libxcursor1 libxrandr2 libxi6 libxkbcommon-x11-0
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  if [ "$(id -u)" -ne 0 ]; then
    echo "setup: run as root (or install these with sudo): ${missing[*]}" >&2
    exit 1
  fi
  export DEBIAN_FRONTEND=noninteractive
  # apt's progress goes to a log, named only when something fails.
  apt_log="${TMPDIR:-/tmp}/sweeplab-setup-apt.log"
  if ! { apt-get update -qq && apt-get install -y -qq --no-install-recommends "${missing[@]}"; } >"$apt_log" 2>&1; then
    echo "setup: installing packages failed; the last lines of $apt_log:" >&2
    tail -n 20 "$apt_log" >&2
    exit 1
  fi
fi

if ! command -v cargo >/dev/null 2>&1; then
  if [ -x "$HOME/.cargo/bin/cargo" ]; then
    export PATH="$HOME/.cargo/bin:$PATH"
  else
    echo "setup: installing Rust with rustup"
    rustup_log="${TMPDIR:-/tmp}/sweeplab-setup-rustup.log"
    if ! curl -sSf https://sh.rustup.rs 2>"$rustup_log" | sh -s -- -y --profile minimal --component clippy,rustfmt >>"$rustup_log" 2>&1; then
      echo "setup: installing Rust failed; the last lines of $rustup_log:" >&2
      tail -n 20 "$rustup_log" >&2
      exit 1
    fi
    export PATH="$HOME/.cargo/bin:$PATH"
  fi
fi
# tools/test.sh checks formatting and lints: a minimal rustup toolchain has
# neither rustfmt nor clippy (rustup's proxies for them exist all the same, so
# ask each for its version).
if ! { clippy-driver -V && rustfmt --version; } >/dev/null 2>&1 && command -v rustup >/dev/null 2>&1; then
  echo "setup: adding the clippy and rustfmt components"
  rustup component add clippy rustfmt >/dev/null 2>&1 || echo "setup: rustup could not add clippy and rustfmt" >&2
fi

# lavapipe needs a runtime dir for its shader cache warnings to stay quiet.
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp}"
