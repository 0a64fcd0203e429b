#!/usr/bin/env bash
# Issue 58's path target on the device, one call: `gtao` and the hemisphere rows along the
# built-in paths (stairs dolly, colonnade truck, tower climb; 24 frames at 320×192 against a
# 4096-ray truth, temporal accumulation on), at each ray count of RAYS; then Sponza's 16 still
# frames with the history clip on and off (scripts/device-quality.sh), which must agree now that
# the clip is at least the rays' sampling noise.
# Carry .devbin (obscura.xz, scenes/crytek-sponza, scenes/sibenik) and .gl. Settings: RAYS
# ("1 4 16"). Writes $OUT/paths.tsv (path, rays, technique, temporal error, popping, mean MSE),
# $OUT/paths.txt and $OUT/quality.tsv.
set -uo pipefail
here=$(dirname "$0")
source "$here/device-env.sh"
xz -dc .devbin/obscura.xz > /tmp/obscura && chmod +x /tmp/obscura
bin=/tmp/obscura
rays=${RAYS:-1 4 16}
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > "$out/gpu.txt" 2>&1
printf 'path\trays\ttechnique\ttemporal_error\tpopping\tmean_mse\n' > "$out/paths.tsv"
for pair in stairs:dolly colonnade:truck tower:climb; do
  scene=${pair%%:*}
  path=${pair##*:}
  for r in $rays; do
    dir=/tmp/paths/$scene-$r
    $bin compare --scene "$scene" --path "$path" --frames 24 --size 320x192 --timing-frames 0 \
      --reference-model hemisphere --spp 4096 --techniques gtao,hemisphere,rtao --temporal \
      --hemisphere-rays "$r" --out "$dir" >> "$out/paths.txt" 2>&1
    python3 - "$dir/report.json" "$scene $path" "$r" >> "$out/paths.tsv" <<'PY'
import json, sys
report = json.load(open(sys.argv[1]))
for t in report["temporal"]["results"]:
    mse = sum(t["mse"]) / len(t["mse"])
    print(f'{sys.argv[2]}\t{sys.argv[3]}\t{t["technique"]}\t{t["temporal_error"]:.5f}\t'
          f'{100 * t["popping"]:.2f}%\t{mse:.3e}')
PY
  done
done
OUT=$out/quality VIEWS=sponza TECHNIQUES=hemisphere,rtao \
  VARIANTS="x16clip=--temporal --timing-frames 15;x16noclip=--temporal --temporal-no-clamp --timing-frames 15" \
  OBSCURA_BIN=$bin bash "$here/device-quality.sh" > /dev/null 2>&1
cp "$out/quality/quality.tsv" "$out/quality.tsv" 2>/dev/null
rm -rf "$out/quality"
cat "$out/gpu.txt" "$out/paths.tsv" "$out/quality.tsv"
