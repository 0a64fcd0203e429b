#!/usr/bin/env bash
# How `sd-svao` limits its stochastic depth map to the requested pixels (issue 16): `sd-vao` (the
# full map) against `sd-svao` with each `--sd-mask` (stencil, depth, discard), in one device call
# on one card, ROUNDS alternating rounds, on Crytek Sponza (guard band 64 and 0), the built-in
# `colonnade` close-up and, when carried, Sibenik, all at 1920x1080. Writes $OUT/info.txt,
# $OUT/bench.txt, $OUT/summary.md (scripts/bench-mask-summary.py) and $OUT/runs.tar.gz.
# Carry .devbin (../shared/tools/prepare-device.sh crytek-sponza sibenik) and .gl.
set -uo pipefail
source "$(dirname "$0")/device-env.sh"
rounds=${ROUNDS:-2}
runs=$out/runs
mkdir -p "$runs"
$bin info | tee "$out/info.txt"
bench() { # name, scene and technique arguments...
  local name=$1
  shift
  $bin bench "$@" --size 1920x1080 --frames 200 --warmup 20 --json "$runs/$name.json" \
    >> "$out/bench.txt" 2>&1
}
for round in $(seq "$rounds"); do
  for scene in sponza sponza0 colonnade sibenik; do
    scene_args "$scene" || continue
    bench "$scene-full-$round" "${args[@]}" --techniques sd-vao
    for mask in stencil depth discard; do
      bench "$scene-$mask-$round" "${args[@]}" --techniques sd-svao --sd-mask $mask
    done
  done
done
python3 "$(dirname "$0")/bench-mask-summary.py" "$runs" | tee "$out/summary.md"
tar -C "$out" -czf "$out/runs.tar.gz" runs && rm -rf "$runs"
