#!/usr/bin/env bash
# The stochastic depth map (issue 16) of two builds against each other, in one device call on one
# card: `obscura bench --techniques sd-vao,sd-svao` with the stencil and with `--sd-mask discard`
# (run files SCENE_discard-*), .devbin/obscura-old and .devbin/obscura alternating for ROUNDS
# rounds, on Crytek Sponza (guard band 64 and 0), the built-in `colonnade` close-up and, when
# carried, Sibenik, all at 1920x1080; then the G-buffer's peer (Bevy 0.19 depth + normal prepass,
# ../shared/tools/peers/README.md) when carried. Writes $OUT/summary.md
# (scripts/bench-raster-summary.py), $OUT/info.txt, $OUT/bench.txt and $OUT/runs.tar.gz.
# Carry .devbin (../shared/tools/prepare-device.sh crytek-sponza sibenik, plus the old binary as
# .devbin/obscura-old or .devbin/obscura-old.xz)
# and .gl. OLD_ARGS and NEW_ARGS: more `bench` arguments for each side, e.g. one binary twice
# with OLD_BIN=./.devbin/obscura OLD_ARGS="--sd-rasterizer hardware" NEW_ARGS="--sd-rasterizer
# compute".
set -uo pipefail
source "$(dirname "$0")/device-env.sh"
new=$bin old=${OLD_BIN:-./.devbin/obscura-old}
# The old build may come compressed (the carry limit): .devbin/obscura-old.xz. OLD_BIN: any other
# command in its place (e.g. a wrapper setting an environment variable).
if [ -z "${OLD_BIN:-}" ] && [ -f .devbin/obscura-old.xz ]; then
  xz -dc .devbin/obscura-old.xz > /tmp/obscura-old && chmod +x /tmp/obscura-old && old=/tmp/obscura-old
fi
rounds=${ROUNDS:-2}
runs=$out/runs
mkdir -p "$runs"
$new info | tee "$out/info.txt"
bench() { # name, binary, scene arguments...
  local name=$1 b=$2
  shift 2
  $b bench "$@" --size 1920x1080 --frames 200 --warmup 20 --json "$runs/$name.json" \
    >> "$out/bench.txt" 2>&1
}
for round in $(seq "$rounds"); do
  for side in old new; do
    b=$new more=${NEW_ARGS:-}
    [ "$side" = old ] && b=$old more=${OLD_ARGS:-}
    [ -x "$b" ] || continue
    # shellcheck disable=SC2206
    extra=($more)
    for scene in sponza sponza0 colonnade sibenik; do
      scene_args "$scene" || continue
      bench "$scene-$side-$round" "$b" "${args[@]}" "${extra[@]}" --techniques sd-vao,sd-svao
      bench "${scene}_discard-$side-$round" "$b" "${args[@]}" "${extra[@]}" --techniques sd-svao \
        --sd-mask discard
    done
  done
done
if [ -f .devbin/bevy_ssao_bench.xz ]; then
  xz -dc .devbin/bevy_ssao_bench.xz > /tmp/bevy && chmod +x /tmp/bevy
  /tmp/bevy .devbin/scenes/crytek-sponza/sponza.glb --size 1920x1080 --quality high --frames 200 \
    --warmup 30 --json "$runs/bevy_high.json" > "$out/bevy.txt" 2>&1
fi
python3 "$(dirname "$0")/bench-raster-summary.py" "$runs" | tee "$out/summary.md"
tar -C "$out" -czf "$out/runs.tar.gz" runs && rm -rf "$runs"
