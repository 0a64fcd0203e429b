#!/usr/bin/env bash
# Seed 001 in full on the device GPU (BENCHMARKS.md, issue 11), one call, 1920x1080 + 64:
# 1. Tab. 1's analogue: Crytek Sponza, SSAO / HBAO / HBAO+ regular and their stochastic-depth rows
#    with S = 1, 2, 4, 8, 16 at the paper's α = 0.2 (AO pass times);
# 2. Tab. 2's analogue: sd-hbao+ at full and half resolution with S = 1 … 16 (α = 0.2) on Sponza
#    and Sibenik, and at S = 4 on stairs and tower (total and SD-map times);
# 3. bent normals: gtao, gtao-vb, sd-gtao-vb with and without --bent-normals on Sponza;
# 4. compensation: sd-hbao+ and sd-vao with --sd-compensation 2 against 1 on Sponza (its cost).
# Run from the repo root on the device machine with .devbin/ and .gl/ carried
# (the device preparation, scenes: crytek-sponza sibenik); results go to $OUT;
# scripts/bench-seed001-summary.py $OUT makes the tables.
set -uo pipefail
source "$(dirname "$0")/device-env.sh"
$bin info | tee "$out/info.txt"
bench=(--size 1920x1080 --frames ${FRAMES:-100} --warmup 10)
run() { # name, then bench arguments
  local name=$1; shift
  $bin bench "${bench[@]}" "$@" --json "$out/$name.json" 2>&1 | tee -a "$out/bench.txt"
}
run tab1-regular "${sponza[@]}" --techniques ssao,hbao,hbao+
for s in 1 2 4 8 16; do
  run "tab1-sd$s" "${sponza[@]}" --techniques sd-ssao,sd-hbao,sd-hbao+ --sd-samples $s --sd-alpha 0.2
done
for s in 1 2 4 8 16; do
  for res in full half; do
    run "tab2-sponza-sd$s-$res" "${sponza[@]}" --techniques sd-hbao+ --sd-samples $s --sd-alpha 0.2 --resolution $res
    run "tab2-sibenik-sd$s-$res" "${sibenik[@]}" --techniques sd-hbao+ --sd-samples $s --sd-alpha 0.2 --resolution $res
  done
done
for scene in stairs tower; do
  for res in full half; do
    run "tab2-$scene-sd4-$res" --scene $scene --techniques sd-hbao+ --sd-samples 4 --sd-alpha 0.2 --resolution $res
  done
done
run bent-off "${sponza[@]}" --techniques gtao,gtao-vb,sd-gtao-vb
run bent-on "${sponza[@]}" --techniques gtao,gtao-vb,sd-gtao-vb --bent-normals
run compensation-1 "${sponza[@]}" --techniques sd-hbao+,sd-vao
run compensation-2 "${sponza[@]}" --techniques sd-hbao+,sd-vao --sd-compensation 2
