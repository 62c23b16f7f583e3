#!/usr/bin/env bash
# Here, before a lent GPU machine's one call (the `device` tool's `run`; see
# docs/bench-on-your-gpu.md, "On a lent machine"): builds the bundle
# (tools/gpu_check_prepare.sh) and puts it, with the Vulkan loader and the GL
# vendor-neutral libraries NVIDIA's Vulkan driver loads, as Debian packages,
# into .gl/ (git-ignored), the one folder the call carries. Prints the call.
#
#   tools/gpu_check_stage.sh
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
git check-ignore -q .gl/x || {
    echo ".gl/ is not ignored by git: it would travel as part of the tree and be committed" >&2
    exit 1
}
tools/gpu_check_prepare.sh
mkdir -p .gl /tmp/amd64/partial
rm -f .gl/*.deb .gl/gpu-check.tar.gz
# The device's processor is x86-64 whatever this one is; its own lists, not the system's.
apt_amd64=(-oAPT::Architecture=amd64 -oAPT::Architectures=amd64 -oDir::State::Lists=/tmp/amd64)
apt-get "${apt_amd64[@]}" update -qq
(cd .gl && apt-get "${apt_amd64[@]}" download -qq libvulkan1 libegl1 libglvnd0 libopengl0 libgl1 libglx0 libgles2)
cp target/gpu-check.tar.gz .gl/

# What the call sends: the tracked tree, what git neither tracks nor ignores, and .gl/.
tree=$(git ls-files -z --cached --others --exclude-standard | du -cb --files0-from=- 2>/dev/null | tail -n 1 | cut -f1)
staged=$(du -sb .gl | cut -f1)
mib=$(((tree + staged) / 1048576))
echo "staged: .gl/ ($((staged / 1048576)) MiB) and the tree ($((tree / 1048576)) MiB): ${mib} MiB of the call's 64"
if [ "$mib" -ge 64 ]; then
    echo "over the 64 MiB a call may send" >&2
    exit 1
fi
echo "the call: run(command=\"bash tools/gpu_check_on_device.sh\", carry=[\".gl\"], timeout_s=600)"
