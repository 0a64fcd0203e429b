#!/usr/bin/env bash
# The horizon-family estimators against VAO on the device GPU (BENCHMARKS.md, issue 10): every
# technique of TECHNIQUES (default: vao and every hbao and gtao row) on Crytek Sponza, stairs and colonnade
# at 1920x1080 + 64, one run. Run from the repo root on the device machine with .devbin/ and .gl/
# carried (../shared/tools/prepare-device.sh crytek-sponza); results go to $OUT.
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
all=$($bin info --techniques)
techniques=${TECHNIQUES:-vao,$(echo "$all" | tr ',' '\n' | grep -E "hbao|gtao" | paste -sd,)}
sponza=(--scene .devbin/scenes/crytek-sponza/sponza.glb --eye=-9.5,1.8,-0.4 --target=0,3.5,0.6 --fov 60)
$bin bench "${sponza[@]}" --size 1920x1080 --techniques "$techniques" --frames 200 --warmup 20 \
  --json "$out/sponza.json" 2>&1 | tee -a "$out/bench.txt"
for scene in stairs colonnade; do
  $bin bench --scene $scene --size 1920x1080 --techniques "$techniques" --frames 200 --warmup 20 \
    --json "$out/$scene.json" 2>&1 | tee -a "$out/bench.txt"
done
