#!/usr/bin/env bash
# Seed 002 Tab. 1 and Fig. 7 analogues (issue 12) in one device call, 1920x1080 + 64, on Crytek
# Sponza (camera of BENCHMARKS.md) and the built-in tower, grass and stairs close-ups:
# - Tab. 1: `ray-sd-vao` pass by pass (AO phase 1 with the requests and intervals, SD map, the
#   indirect dispatch's set-up, AO phase 2, blur), with and without ray intervals, at 1/1 and 1/4;
# - Fig. 7: everything but the G-buffer for `ray-sd-vao` at 1/1, 1/2 and 1/4, against `vao` (no
#   map), the raster `sd-svao` and `rt-svao` (column rays), all in this call;
# - §3.5 / Fig. 14: the map's own guard band (on by default, 512 px at 1080p) against none
#   (`--sd-guard-band 0`) at 1/1 and 1/4.
# Medians of 100 frames after 20 warm-up frames (`obscura bench --json`). Writes $OUT/summary.md
# and $OUT/runs.tar.gz. Carry .devbin (the device preparation, scenes: crytek-sponza) and .gl.
set -uo pipefail
source "$(dirname "$0")/device-env.sh"
runs=$out/runs
mkdir -p "$runs"
$bin info > "$runs/info.txt" 2>&1
bench() { # name, arguments...
  local name=$1
  shift
  $bin bench "$@" --size 1920x1080 --frames 100 --warmup 20 --json "$runs/$name.json" \
    >> "$out/bench.txt" 2>&1
}
for scene in sponza tower grass stairs; do
  args=(--scene "$scene")
  [ "$scene" = sponza ] && args=("${sponza[@]}")
  bench "$scene-baselines" "${args[@]}" --techniques vao,sd-svao,rt-svao
  for res in 1 2 4; do
    bench "$scene-res$res" "${args[@]}" --techniques ray-sd-vao --ray-sd-res $res
  done
  for res in 1 4; do
    bench "$scene-nointervals-res$res" "${args[@]}" --techniques ray-sd-vao --ray-sd-res $res \
      --no-intervals
    bench "$scene-noband-res$res" "${args[@]}" --techniques ray-sd-vao --ray-sd-res $res \
      --sd-guard-band 0
  done
done
python3 "$(dirname "$0")/bench-seed002-summary.py" "$runs" | tee "$out/summary.md"
tar -C "$out" -czf "$out/runs.tar.gz" runs bench.txt && rm -rf "$runs"
