#!/usr/bin/env bash
# The horizon-family estimators against VAO on the device GPU (BENCHMARKS.md, issue 10): every
# technique of TECHNIQUES (default: vao and every hbao and gtao row) on Crytek Sponza, stairs and colonnade
# at 1920x1080 + 64, one run. Run from the repo root on the device machine with .devbin/ and .gl/
# carried (../shared/tools/prepare-device.sh crytek-sponza); results go to $OUT.
set -uo pipefail
source "$(dirname "$0")/device-env.sh"
$bin info | tee "$out/info.txt"
all=$($bin info --techniques)
techniques=${TECHNIQUES:-vao,$(echo "$all" | tr ',' '\n' | grep -E "hbao|gtao" | paste -sd,)}
$bin bench "${sponza[@]}" --size 1920x1080 --techniques "$techniques" --frames 200 --warmup 20 \
  --json "$out/sponza.json" 2>&1 | tee -a "$out/bench.txt"
for scene in stairs colonnade; do
  $bin bench --scene $scene --size 1920x1080 --techniques "$techniques" --frames 200 --warmup 20 \
    --json "$out/$scene.json" 2>&1 | tee -a "$out/bench.txt"
done
