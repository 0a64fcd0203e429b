#!/usr/bin/env bash
# Benchmarks on the device GPU (see BENCHMARKS.md). Run from the repo root on the device machine
# with .devbin/ (release binary + scenes, from ../shared/tools/prepare-device.sh crytek-sponza) and
# .gl/ (Vulkan loader) carried; results go to $OUT.
set -uo pipefail
for f in .gl/*.deb; do dpkg -x "$f" / 2>/dev/null; done; ldconfig
export OBSCURA_BACKEND=vulkan
bin=./.devbin/obscura
if ! $bin info >/dev/null 2>&1 || ! $bin info | grep -qi nvidia; then
  export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
fi
out=${OUT:-/tmp/out}
mkdir -p "$out"
$bin info | tee "$out/info.txt"
$bin info --json > "$out/info.json"
sponza=(--scene .devbin/scenes/crytek-sponza/sponza.glb --eye=-9.5,1.8,-0.4 --target=0,3.5,0.6 --fov 60)
for size in 1920x1080 2560x1440 3840x2160; do
  $bin bench --scene stairs --size $size --techniques vao --frames 200 --warmup 20 --json "$out/stairs-$size.json" 2>&1 | tee -a "$out/bench.txt"
  $bin bench "${sponza[@]}" --size $size --techniques vao --frames 200 --warmup 20 --json "$out/sponza-$size.json" 2>&1 | tee -a "$out/bench.txt"
done
$bin render "${sponza[@]}" --size 1280x720 --out "$out/sponza-vao.png" --composite 2>&1 | tail -1
