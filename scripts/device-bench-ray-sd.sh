#!/usr/bin/env bash
# The ray-traced stochastic depth map (issue 12, seed 002) against the raster map, in one device
# call: `obscura bench --techniques vao,sd-vao,sd-svao,ray-sd-vao-full,ray-sd-vao` (then
# `sd-svao --sd-mask discard`, the ray-traced rows at 1/2 and 1/4 resolution, and `ray-sd-vao`
# without ray intervals at 1/1 and 1/4) at 1920x1080
# on Crytek Sponza (camera of BENCHMARKS.md) and the built-in tower and stairs close-ups, medians
# of 100 frames after 20 warm-up frames. Writes $OUT/summary.md and $OUT/runs.tar.gz.
# Carry .devbin (../shared/tools/prepare-device.sh crytek-sponza) and .gl.
set -uo pipefail
source "$(dirname "$0")/device-env.sh"
runs=$out/runs
mkdir -p "$runs"
$bin info | tee "$out/info.txt"
bench() { # name, arguments...
  local name=$1
  shift
  $bin bench "$@" --size 1920x1080 --frames 100 --warmup 20 --json "$runs/$name.json" \
    >> "$out/bench.txt" 2>&1
}
for scene in sponza tower stairs; do
  args=(--scene "$scene")
  [ "$scene" = sponza ] && args=("${sponza[@]}")
  bench "$scene" "${args[@]}" --techniques vao,sd-vao,sd-svao,ray-sd-vao-full,ray-sd-vao
  bench "$scene-discard" "${args[@]}" --techniques sd-svao --sd-mask discard
  for res in 2 4; do
    bench "$scene-res$res" "${args[@]}" --techniques ray-sd-vao-full,ray-sd-vao --ray-sd-res $res
  done
  for res in 1 4; do
    bench "$scene-nointervals-res$res" "${args[@]}" --techniques ray-sd-vao --ray-sd-res $res \
      --no-intervals
  done
done
python3 - "$runs" <<'PY' | tee "$out/summary.md"
import json, pathlib, sys
runs = pathlib.Path(sys.argv[1])
print("| scene | technique | map (reset + map), ms | AO passes, ms | total without G-buffer, ms |")
print("|---|---|---|---|---|")
for path in sorted(runs.glob("*.json")):
    data = json.loads(path.read_text())
    for r in data["results"]:
        p = r["passes"]
        g = p.get("gbuffer", 0) + p.get("gbuffer_resolve", 0)
        sd = p.get("sd_reset", 0) + p.get("sd_map", 0)
        total = r["total_ms"] - g
        ao = total - sd - p.get("blur", 0)
        name = r["technique"] + (" (discard)" if "discard" in path.stem else "")
        if "-res" in path.stem:
            name += " 1/" + path.stem.rsplit("res", 1)[1]
        if "nointervals" in path.stem:
            name += " (no intervals)"
        print(f"| {path.stem.split('-')[0]} | {name} | {sd:.3f} | {ao:.3f} | {total:.3f} |")
PY
tar -C "$out" -czf "$out/runs.tar.gz" runs && rm -rf "$runs"
