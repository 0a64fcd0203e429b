#!/usr/bin/env bash
# Seed 001 Tab. 3's analogue on the device GPU (BENCHMARKS.md, issue 11), one call: SD-HBAO+ on
# Sibenik at 1920x1080 + 64, α = 0.2, S = 1, 2, 4, 8: the single camera at full resolution, and
# sd-hbao+-multiview at full resolution, at half resolution (--resolution half) and with only the
# second view at half (--mv-resolution half).
# Run from the repo root on the device machine with .devbin/ and .gl/ carried
# (the device preparation, scenes: sibenik); results go to $OUT;
# scripts/bench-seed001-summary.py $OUT makes the table.
set -uo pipefail
source "$(dirname "$0")/device-env.sh"
$bin info | tee "$out/info.txt"
bench=(--size 1920x1080 --frames ${FRAMES:-100} --warmup 10 --sd-alpha 0.2)
for s in 1 2 4 8; do
  run() { # name, then bench arguments
    local name=$1; shift
    $bin bench "${bench[@]}" "${sibenik[@]}" --sd-samples $s "$@" --json "$out/tab3-sd$s-$name.json" \
      2>&1 | tee -a "$out/bench.txt"
  }
  run single --techniques sd-hbao+
  run multiview --techniques sd-hbao+-multiview
  run multiview-half --techniques sd-hbao+-multiview --resolution half
  run multiview-second-half --techniques sd-hbao+-multiview --mv-resolution half
done
