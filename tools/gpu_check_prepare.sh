#!/usr/bin/env bash
# Prepares, here (with a compiler and the network), what tools/gpu_check.sh
# needs on a machine that has only a GPU driver: the release sweeplab, the
# scenes, the CT engine (Table 1's data set), and the Vulkan loader and
# Khronos validation layer as Debian packages unpacked in place (no root on
# the target; the packages themselves are left out). Writes the bundle to
# DIR (default target/gpu-check) and a tarball DIR.tar.gz beside it.
#
#   tools/gpu_check_prepare.sh [DIR]
#   scp target/gpu-check.tar.gz gpu-host: && ssh gpu-host 'tar xzf gpu-check.tar.gz && gpu-check/tools/gpu_check.sh out'
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
dir=${1:-$root/target/gpu-check}
cd "$root"
cargo build --release --bin sweeplab
rm -rf "$dir"
mkdir -p "$dir/bin" "$dir/tools" "$dir/tests" "$dir/data" "$dir/debs" "$dir/vulkan"
cp target/release/sweeplab "$dir/bin/"
# Debug info is not needed there (and would be most of the size).
strip "$dir/bin/sweeplab" 2>/dev/null || true
cp tools/gpu_check.sh "$dir/tools/"
cp -r tests/scenes "$dir/tests/"
cp data/engine.vti data/README.md "$dir/data/"
(cd "$dir/debs" && apt-get download libvulkan1 vulkan-validationlayers)
for deb in "$dir"/debs/*.deb; do
    dpkg -x "$deb" "$dir/vulkan"
done
rm -rf "$dir/vulkan/usr/share/doc" "$dir/debs"
size=$(du -sm "$dir" | cut -f1)
echo "bundle: $dir (${size} MiB)"
if [ "$size" -gt 64 ]; then
    echo "the bundle is over 64 MiB" >&2
    exit 1
fi
tar -C "$(dirname "$dir")" -czf "$dir.tar.gz" "$(basename "$dir")"
echo "tarball: $dir.tar.gz ($(du -m "$dir.tar.gz" | cut -f1) MiB)"
