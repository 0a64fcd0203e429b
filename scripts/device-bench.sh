#!/usr/bin/env bash
# Benchmarks on the device GPU (see BENCHMARKS.md). Run from the repo root on the device machine
# with .devbin/ (release binary + scenes, from ../shared/tools/prepare-device.sh crytek-sponza) and
# .gl/ (Vulkan loader) carried; results go to $OUT.
set -uo pipefail
source "$(dirname "$0")/device-env.sh"
$bin info | tee "$out/info.txt"
$bin info --json > "$out/info.json"
for size in 1920x1080 2560x1440 3840x2160; do
  $bin bench --scene stairs --size $size --techniques vao --frames 200 --warmup 20 --json "$out/stairs-$size.json" 2>&1 | tee -a "$out/bench.txt"
  $bin bench "${sponza[@]}" --size $size --techniques vao --frames 200 --warmup 20 --json "$out/sponza-$size.json" 2>&1 | tee -a "$out/bench.txt"
done
$bin render "${sponza[@]}" --size 1280x720 --out "$out/sponza-vao.png" --composite 2>&1 | tail -1
