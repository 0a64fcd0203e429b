#!/usr/bin/env bash
# The raster passes (issue 16) of two builds against each other and against a real engine's
# prepass, in one device call on one card: `obscura bench --techniques vao,vao-dual,sd-vao` (the
# G-buffer, depth peeling and the stochastic depth map) with .devbin/obscura-old and
# .devbin/obscura alternating for ROUNDS rounds, on Crytek Sponza (guard band 64 and 0), the
# built-in `colonnade` close-up and, when carried, Sibenik (an OBJ: every triangle double-sided),
# all at 1920x1080, and Sponza along scripts/sponza-walk.json (a 5 m walk from that view, turning
# 20° each way, over 60 frames: the camera moves every frame, so occlusion culling's first phase
# works from the last frame's view); then
# the peer benchmark (Bevy 0.19 depth + normal prepass and SSAO high,
# ../shared/tools/peers/README.md). Writes $OUT/summary.md (scripts/bench-raster-summary.py),
# $OUT/bevy.txt and $OUT/runs.tar.gz (every JSON).
# Carry .devbin (../shared/tools/prepare-device.sh crytek-sponza sibenik, plus the old binary)
# and .gl.
set -uo pipefail
source "$(dirname "$0")/device-env.sh"
new=$bin old=./.devbin/obscura-old
techniques=${TECHNIQUES:-vao,vao-dual,sd-vao}
rounds=${ROUNDS:-2}
runs=$out/runs
mkdir -p "$runs"
$new info | tee "$out/info.txt"
bench() { # name, binary, scene arguments... (FRAMES: timed frames, 200)
  local name=$1 b=$2
  shift 2
  $b bench "$@" --size 1920x1080 --techniques "$techniques" --frames "${FRAMES:-200}" --warmup 20 \
    --json "$runs/$name.json" >> "$out/bench.txt" 2>&1
}
for round in $(seq "$rounds"); do
  for side in old new; do
    b=$new; [ "$side" = old ] && b=$old
    [ -x "$b" ] || continue
    bench "sponza-$side-$round" "$b" "${sponza[@]}"
    bench "sponza0-$side-$round" "$b" "${sponza[@]}" --guard-band 0
    FRAMES=60 bench "sponzawalk-$side-$round" "$b" "${sponza[0]}" "${sponza[1]}" \
      --path scripts/sponza-walk.json
    bench "colonnade-$side-$round" "$b" --scene colonnade --camera closeup
    [ -d .devbin/scenes/sibenik ] && bench "sibenik-$side-$round" "$b" "${sibenik[@]}"
  done
done
if [ -f .devbin/bevy_ssao_bench.xz ]; then
  xz -dc .devbin/bevy_ssao_bench.xz > /tmp/bevy && chmod +x /tmp/bevy
  /tmp/bevy .devbin/scenes/crytek-sponza/sponza.glb --size 1920x1080 --quality high --frames 200 \
    --warmup 30 --json "$runs/bevy_high.json" > "$out/bevy.txt" 2>&1
fi
python3 "$(dirname "$0")/bench-raster-summary.py" "$runs" | tee "$out/summary.md"
tar -C "$out" -czf "$out/runs.tar.gz" runs && rm -rf "$runs"
