#!/usr/bin/env bash
# Ray-tracing benchmarks on the device GPU (BENCHMARKS.md, issue 4): VAO, RT-VAO and RT-SVAO (both
# phase-2 variants). Same set-up as scripts/device-bench.sh.
set -uo pipefail
for f in .gl/*.deb; do dpkg -x "$f" / 2>/dev/null; done; ldconfig
export OBSCURA_BACKEND=vulkan
bin=./.devbin/obscura
$bin info | grep -qi nvidia || export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
out=${OUT:-/tmp/out}
mkdir -p "$out"
sponza=(--scene .devbin/scenes/crytek-sponza/sponza.glb --eye=-9.5,1.8,-0.4 --target=0,3.5,0.6 --fov 60)
t=vao,rt-vao,rt-svao,rt-svao-dense
for size in 1920x1080 2560x1440 3840x2160; do
  $bin bench "${sponza[@]}" --size $size --techniques $t --frames 100 --warmup 10 --json "$out/rt-sponza-$size.json" 2>&1 | tee -a "$out/rt-bench.txt"
done
for scene in stairs grass tower; do
  for size in 1920x1080 2560x1440 3840x2160; do
    $bin bench --scene $scene --size $size --techniques $t --frames 100 --warmup 10 --json "$out/rt-$scene-$size.json" 2>&1 | tee -a "$out/rt-bench.txt"
  done
done
