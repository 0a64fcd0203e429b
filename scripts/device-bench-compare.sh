#!/usr/bin/env bash
# Two builds on the same device in one call (e.g. before/after a refactor): every technique on
# Sponza at 1920x1080, `obscura bench` alternating old and new binary three times, so drift of the
# card shows up as spread rather than as a difference. Run on the device machine from the repo
# root with .devbin/obscura (new), .devbin/obscura-old and .devbin/scenes/crytek-sponza, and .gl/
# carried (../shared/tools/prepare-device.sh crytek-sponza, then copy the old binary in).
set -uo pipefail
source "$(dirname "$0")/device-env.sh"
new=$bin old=./.devbin/obscura-old
$new info | tee "$out/info.txt"
techniques=${TECHNIQUES:-$($new info --techniques)}
for round in 1 2 3; do
  for side in old new; do
    bin=$new; [ "$side" = old ] && bin=$old
    $bin bench "${sponza[@]}" --size 1920x1080 --techniques "$techniques" --frames 100 --warmup 20 \
      --json "$out/sponza-$side-$round.json" 2>&1 | tee -a "$out/bench-$side.txt"
  done
done
