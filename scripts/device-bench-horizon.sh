#!/usr/bin/env bash
# The horizon-family estimators against VAO on the device GPU (BENCHMARKS.md, issue 10), one call:
# 1. every technique of TECHNIQUES (default: vao, vao-interleaved and every hbao, gtao and sao
#    row) on Crytek Sponza, stairs and colonnade at 1920x1080 + 64, at the defaults and, on
#    Sponza, at `--preset high`;
# 2. seed 004 Tab. 1's analogue on Sponza at the paper's 1280x720: HBAO D×S = 8×10, 16×20, 32×40,
#    64×80, Pyramid HBAO and SAO with L = 1 … 5 levels, at R = 1 m (the paper gives no R), each
#    timed by `bench` (the AO pass and the pyramid's build) and compared by `compare` with the
#    hemisphere ground truth of the same radius (1024 rays per pixel; blurred, as the paper
#    filters its maps but leaves the filter out of its times).
# SKIP_BENCH=1 runs part 2 only, SKIP_TAB1=1 part 1 only.
# Run from the repo root on the device machine with .devbin/ and .gl/ carried
# (the device preparation, scenes: crytek-sponza); results go to $OUT.
set -uo pipefail
source "$(dirname "$0")/device-env.sh"
$bin info | tee "$out/info.txt"
all=$($bin info --techniques)
techniques=${TECHNIQUES:-vao,vao-interleaved,$(echo "$all" | tr ',' '\n' | grep -E "hbao|gtao|sao" | paste -sd,)}
bench=(--frames 200 --warmup 20)
if [ -z "${SKIP_BENCH:-}" ]; then
$bin bench "${sponza[@]}" --size 1920x1080 --techniques "$techniques" "${bench[@]}" \
  --json "$out/sponza.json" 2>&1 | tee -a "$out/bench.txt"
$bin bench "${sponza[@]}" --size 1920x1080 --techniques "$techniques" --preset high "${bench[@]}" \
  --json "$out/sponza-high.json" 2>&1 | tee -a "$out/bench.txt"
for scene in stairs colonnade; do
  $bin bench --scene $scene --size 1920x1080 --techniques "$techniques" "${bench[@]}" \
    --json "$out/$scene.json" 2>&1 | tee -a "$out/bench.txt"
done
fi
[ -n "${SKIP_TAB1:-}" ] && exit 0
for grid in 8x10 16x20 32x40 64x80; do
  d=${grid%x*} s=${grid#*x}
  hbao=(--techniques hbao --horizon-directions "$d" --horizon-steps "$s" --horizon-radius 1 --radius 1)
  $bin bench "${sponza[@]}" --size 1280x720 "${hbao[@]}" --frames 50 --warmup 5 \
    --json "$out/tab1-$grid.json" 2>&1 | tee -a "$out/tab1.txt"
  $bin compare "${sponza[@]}" --size 1280x720 "${hbao[@]}" --reference-model hemisphere \
    --spp 1024 --out "$out/tab1-$grid" 2>&1 | tee -a "$out/tab1.txt"
done
for levels in 1 2 3 4 5; do
  pyr=(--techniques pyramid-hbao,sao --pyramid-levels "$levels" --phbao-radius 1 --sao-radius 1 --radius 1)
  $bin bench "${sponza[@]}" --size 1280x720 "${pyr[@]}" --frames 50 --warmup 5 \
    --json "$out/tab1-L$levels.json" 2>&1 | tee -a "$out/tab1.txt"
  $bin compare "${sponza[@]}" --size 1280x720 "${pyr[@]}" --reference-model hemisphere \
    --spp 1024 --out "$out/tab1-L$levels" 2>&1 | tee -a "$out/tab1.txt"
done
