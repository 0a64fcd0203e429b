#!/usr/bin/env bash
# Issue 58's denoiser on the device, one call: `hemisphere` and `rtao` at 1920x1080 on Sponza and
# Sibenik against the 1024-ray hemisphere truth (scripts/device-quality.sh), with the bilateral
# blur and with `--denoise`, one frame and after 16 still frames; then the denoiser's passes
# (`bench --temporal --denoise`, Sponza, medians of 100 frames after 30 warm-up frames); then
# along the built-in paths (24 frames at 320x192, 4096-ray truth) `gtao` and `rtao` with
# `--temporal`, with the blur and with `--denoise`.
# Carry .devbin (obscura.xz, scenes/crytek-sponza, scenes/sibenik) and .gl.
# Writes $OUT/summary.txt.
set -uo pipefail
here=$(dirname "$0")
source "$here/device-env.sh"
export OBSCURA_CACHE_DIR=$out/cache
VIEWS="sponza sibenik" TECHNIQUES=hemisphere,rtao OUT=$out/quality \
  VARIANTS="one=;one-denoised=--denoise;still16=--temporal --timing-frames 15;still16-denoised=--temporal --denoise --timing-frames 15" \
  bash "$here/device-quality.sh" > /dev/null 2>&1
$bin bench "${sponza[@]}" --size 1920x1080 --frames 100 --warmup 30 --techniques rtao \
  --temporal --denoise > "$out/bench-denoise.txt" 2>&1
for pair in stairs:dolly colonnade:truck tower:climb; do
  scene=${pair%%:*}
  for filter in blur denoise; do
    flags=()
    [ $filter = denoise ] && flags=(--denoise)
    $bin compare --scene "$scene" --path "${pair##*:}" --frames 24 --size 320x192 \
      --timing-frames 0 --reference-model hemisphere --spp 4096 --techniques gtao,rtao \
      --temporal "${flags[@]}" --out "$out/path-$scene-$filter" > /dev/null 2>&1
  done
done
rm -rf "$out/cache" "$out/quality/reports.tar.gz"
{
  nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
  cat "$out/quality/quality.tsv" "$out/bench-denoise.txt"
  for d in "$out"/path-*; do
    echo "== $(basename "$d")"; grep -A5 "Along the camera" "$d/report.md" | grep '^| `'
  done
} > "$out/summary.txt" 2>&1
rm -rf "$out"/path-*
cat "$out/summary.txt"
