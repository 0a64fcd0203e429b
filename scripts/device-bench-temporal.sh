#!/usr/bin/env bash
# Issue 13 on the device, in one call:
# 1. the temporal accumulation pass at 1920x1080 on Crytek Sponza (camera of BENCHMARKS.md):
#    `obscura bench --techniques vao [--temporal]`, two rounds alternating, medians of 200 frames;
# 2. the viewer's render path offscreen at 1920x1080 with vao (`obscura view --offscreen-frames`),
#    on Sponza and the stairs close-up;
# 3. the temporal metrics along the built-in paths of stairs, colonnade and tower (24 frames,
#    320x192) against the cosine-weighted hemisphere truth traced on the GPU at 16384 rays per
#    pixel (little Monte Carlo noise left to count as flicker), for vao, sd-vao, rt-svao and
#    ray-sd-vao, and for vao with --temporal; against the vao model; and against the vao model
#    averaged over its pattern's 16 turns (vao-mean), all four with and without --temporal.
# Writes $OUT/results.tar.gz (everything) and $OUT/summary.txt.
# Carry .devbin (the device preparation, scenes: crytek-sponza) and .gl.
set -uo pipefail
source "$(dirname "$0")/device-env.sh"
runs=$out/runs
mkdir -p "$runs"
$bin info > "$runs/info.txt" 2>&1
for round in 1 2; do
  for mode in off on; do
    flag=()
    [ "$mode" = on ] && flag=(--temporal)
    $bin bench "${sponza[@]}" --size 1920x1080 --techniques vao "${flag[@]}" --frames 200 \
      --warmup 20 --json "$runs/bench-$mode-$round.json" > "$runs/bench-$mode-$round.txt" 2>&1
  done
done
$bin view "${sponza[@]}" --technique vao --size 1920x1080 --offscreen-frames 200 \
  > "$runs/view-sponza.txt" 2>&1
$bin view --scene stairs --technique vao --size 1920x1080 --offscreen-frames 200 \
  > "$runs/view-stairs.txt" 2>&1
export OBSCURA_CACHE_DIR=$out/cache
for pair in stairs:dolly colonnade:truck tower:climb; do
  scene=${pair%%:*}
  path=${pair##*:}
  common=(--scene "$scene" --path "$path" --frames 24 --size 320x192 --timing-frames 0)
  hemi=(--reference-model hemisphere --spp 16384)
  $bin compare "${common[@]}" "${hemi[@]}" --techniques vao,sd-vao,rt-svao,ray-sd-vao \
    --out "$runs/$scene-hemi" > "$runs/$scene-hemi.md" 2> "$runs/$scene-hemi.err"
  $bin compare "${common[@]}" "${hemi[@]}" --techniques vao --temporal \
    --out "$runs/$scene-hemi-temporal" > "$runs/$scene-hemi-temporal.md" 2>&1
  $bin compare "${common[@]}" --techniques vao,sd-vao,rt-svao,ray-sd-vao \
    --out "$runs/$scene-vao" > "$runs/$scene-vao.md" 2>&1
  for temporal in off on; do
    flag=()
    [ "$temporal" = on ] && flag=(--temporal)
    $bin compare "${common[@]}" --reference-model vao-mean \
      --techniques vao,sd-vao,rt-svao,ray-sd-vao "${flag[@]}" \
      --out "$runs/$scene-mean-$temporal" > "$runs/$scene-mean-$temporal.md" 2>&1
  done
done
rm -rf "$out/cache"
{
  grep -h "temporal" "$runs"/bench-*.txt | head -20
  grep -h "" "$runs"/view-*.txt
  for f in "$runs"/*-hemi*.md "$runs"/*-vao*.md "$runs"/*-mean-*.md; do
    echo "== $(basename "$f")"
    grep -A8 "Along the camera" "$f" | grep '^| `'
  done
} > "$out/summary.txt" 2>&1
tar czf "$out/results.tar.gz" -C "$out" runs
rm -rf "$runs"
