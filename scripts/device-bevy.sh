#!/usr/bin/env bash
# Issue 61 on the device, one call: the plugin's example app (crates/bevy_obscura/examples/sponza.rs)
# on Sponza at 1920×1080 with every choice (Bevy's SSAO medium and high, obscura's rows), the peer
# benchmark (Bevy's own app, tools/peers) at medium and high in the same call, and each choice's AO
# against the hemisphere ground truth of the same camera (R = 0.5, guard band 0, the file's
# shading normals, as Bevy's prepass has them).
# Carry .devbin (obscura.xz, bevy_sponza.xz, bevy_ssao_bench.xz, scenes/crytek-sponza) and .gl.
# Settings: FRAMES (200), WARMUP (30), SPP (1024), SIZE (1920x1080).
# Writes $OUT/app.json (the app's median GPU ms per pass and choice), $OUT/peer-*.txt,
# $OUT/mae.txt (`obscura diff` of the truth against each choice's AO) and $OUT/images.tar.gz.
set -uo pipefail
here=$(dirname "$0")
source "$here/device-env.sh"
frames=${FRAMES:-200}
warmup=${WARMUP:-30}
spp=${SPP:-1024}
size=${SIZE:-1920x1080}
# Unpacked afresh each call: the device keeps ignored files of earlier calls.
for f in obscura bevy_sponza bevy_ssao_bench; do
  xz -dc ".devbin/$f.xz" > "/tmp/$f" && chmod +x "/tmp/$f"
done
bin=/tmp/obscura
scene=${sponza[1]}
view=(--eye=-9.5,1.8,-0.4 --target=0,3.5,0.6 --fov 60)
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > "$out/gpu.txt" 2>&1
/tmp/bevy_sponza --scene "$scene" --headless --size "$size" --frames "$frames" \
  --warmup "$warmup" --out "$out/app" > "$out/app.txt" 2>&1
cp "$out/app/times.json" "$out/app.json" 2>/dev/null
for q in medium high; do
  /tmp/bevy_ssao_bench "$scene" --size "$size" --quality $q --frames "$frames" \
    --warmup "$warmup" > "$out/peer-$q.txt" 2>&1
done
"$bin" reference --scene "$scene" "${view[@]}" --size "$size" --guard-band 0 --model hemisphere \
  --spp "$spp" --ao-radius 0.5 --no-cache --out "$out/truth.exr" > "$out/truth.txt" 2>&1
: > "$out/mae.txt"
for f in "$out"/app/*.ao.png; do
  "$bin" diff "$out/truth.exr" "$f" >> "$out/mae.txt" 2>&1
done
(cd "$out" && tar czf images.tar.gz app/*.ao.png app/gtao-high.png app/bevy-ssao-high.png)
rm -rf "$out/app"
cat "$out/gpu.txt" "$out/app.txt" "$out/mae.txt"
