#!/usr/bin/env bash
# Issue 58's two-phase rays on the device, one call: for Sponza and Sibenik at 1920×1080, one ray
# a pixel, `rtao` and `rtao-two-phase` with phase 1 walking rays of up to 0 … 256 pixels
# (`--proof-pixels`): the rays phase 2 traced (`render --debug-out`, stats.json) and the GPU time
# after the G-buffer (`bench`, medians of 100 frames after 30 warm-up frames); and, where
# .devbin/obscura-old.xz is carried, the build before the blocked proof (free proofs only, walks
# of up to 256 pixels) in the same call. Then the MAE of both rows against the 1024-ray truth
# (scripts/device-quality.sh), which must agree.
# Carry .devbin (obscura.xz, scenes/crytek-sponza, scenes/sibenik) and .gl.
# Writes $OUT/two-phase.tsv (build, view, technique, proof pixels, rays traced, of rays,
# phase 1 ms, phase 2 ms, total ms), $OUT/quality.tsv and $OUT/two-phase.txt (every output).
set -uo pipefail
here=$(dirname "$0")
source "$here/device-env.sh"
builds=new
cp "$bin" /tmp/obscura-new
if [ -f .devbin/obscura-old.xz ]; then
  xz -dc .devbin/obscura-old.xz > /tmp/obscura-old && chmod +x /tmp/obscura-old
  builds="new old"
fi
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > "$out/gpu.txt" 2>&1
log_all=$out/two-phase.txt
printf 'build\tview\ttechnique\tproof_pixels\ttraced\trays\tphase1_ms\tphase2_ms\ttotal_ms\n' \
  > "$out/two-phase.tsv"
pass_ms() { awk -v p="$1" '$1 == p && $3 == "ms" {print $2}' "$2"; }
for build in $builds; do
  b=/tmp/obscura-$build
  for view in sponza sibenik; do
    scene_args "$view" || continue
    rows="rtao:- rtao-two-phase:256"
    [ "$build" = new ] && rows="rtao:- rtao-two-phase:0 rtao-two-phase:16 rtao-two-phase:32 rtao-two-phase:64 rtao-two-phase:128 rtao-two-phase:256"
    for row in $rows; do
      t=${row%%:*}; px=${row#*:}
      flags=(); [ "$px" != - ] && [ "$build" = new ] && flags=(--proof-pixels "$px")
      log=/tmp/bench-$build-$view-$t-$px.txt
      $b bench "${args[@]}" --size 1920x1080 --frames 100 --warmup 30 --techniques "$t" \
        "${flags[@]}" > "$log" 2>&1
      traced=-; rays=$((1920 * 1080))
      if [ "$t" = rtao-two-phase ]; then
        d=/tmp/dbg-$build-$view-$px; mkdir -p "$d"
        $b render "${args[@]}" --size 1920x1080 --technique "$t" "${flags[@]}" \
          --debug-out "$d" --out "$d/ao.png" >> "$log" 2>&1
        traced=$(python3 -c "import json;print(json.load(open('$d/stats.json'))['rays_traced'])" 2>/dev/null || echo -)
      fi
      cat "$log" >> "$log_all"
      p1=$(pass_ms svao_phase1 "$log"); p2=$(pass_ms svao_phase2 "$log")
      [ "$t" = rtao ] && p2=$(pass_ms rtao "$log")
      total=$(awk '$1 == "total" {print $2}' "$log")
      printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$build" "$view" "$t" "$px" "$traced" "$rays" \
        "${p1:--}" "${p2:--}" "${total:--}" >> "$out/two-phase.tsv"
    done
  done
done
OUT=$out/quality VIEWS="sponza sibenik" TECHNIQUES=rtao,rtao-two-phase VARIANTS="one=" \
  OBSCURA_BIN=/tmp/obscura-new bash "$here/device-quality.sh" > /dev/null 2>&1
cp "$out/quality/quality.tsv" "$out/quality.tsv" 2>/dev/null
rm -rf "$out/quality"
cat "$out/gpu.txt" "$out/two-phase.tsv" "$out/quality.tsv"
