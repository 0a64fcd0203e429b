#!/usr/bin/env bash
# The G-buffer against the build before a change and against a real engine's prepass (issue 16),
# in one device call on one card: `obscura bench --techniques vao` on Sponza at 1920x1080 with the
# guard band 0 and 64, alternating .devbin/obscura-old and .devbin/obscura three times, then the
# peer benchmark (Bevy 0.19 depth + normal prepass and SSAO high, ../shared/tools/peers/README.md).
# Then, once per build, the built-in `colonnade` close-up and, when carried, Sibenik (an OBJ: every
# triangle double-sided) at 1920x1080 + 64.
# Carry .devbin (../shared/tools/prepare-device.sh crytek-sponza [sibenik], plus the old binary)
# and .gl.
set -uo pipefail
source "$(dirname "$0")/device-env.sh"
new=$bin old=./.devbin/obscura-old
$new info | tee "$out/info.txt"
for round in 1 2 3; do
  for side in old new; do
    bin=$new; [ "$side" = old ] && bin=$old
    for band in 0 64; do
      $bin bench "${sponza[@]}" --size 1920x1080 --guard-band $band --techniques vao --frames 200 \
        --warmup 20 --json "$out/gbuffer-$side-$band-$round.json" >> "$out/bench.txt" 2>&1
    done
  done
done
if [ -f .devbin/bevy_ssao_bench.xz ]; then
  xz -dc .devbin/bevy_ssao_bench.xz > /tmp/bevy && chmod +x /tmp/bevy
  /tmp/bevy .devbin/scenes/crytek-sponza/sponza.glb --size 1920x1080 --quality high --frames 200 \
    --warmup 30 --json "$out/bevy_high.json" > "$out/bevy.txt" 2>&1
fi
sibenik=(--scene .devbin/scenes/sibenik/sibenik.obj --eye=-17,-9,0 --target=0,-10,0 --fov 60)
for side in old new; do
  bin=$new; [ "$side" = old ] && bin=$old
  $bin bench --scene colonnade --camera closeup --size 1920x1080 --techniques vao --frames 200 \
    --warmup 20 --json "$out/colonnade-$side.json" >> "$out/bench.txt" 2>&1
  if [ -d .devbin/scenes/sibenik ]; then
    $bin bench "${sibenik[@]}" --size 1920x1080 --techniques vao --frames 200 --warmup 20 \
      --json "$out/sibenik-$side.json" >> "$out/bench.txt" 2>&1
  fi
done
