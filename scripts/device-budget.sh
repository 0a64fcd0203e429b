#!/usr/bin/env bash
# Issue 58's ray budget on the device, one call: `obscura bench` of `rtao` and `hemisphere` with
# temporal accumulation on Sponza at 1920×1080, without a budget and under budgets of all, half
# and a quarter of the pixels' rays, for this build and, when .devbin/obscura-old.xz is carried,
# the build before (the same call, the same card); then the 16-still-frame MAE of `rtao` under
# half the rays (scripts/device-quality.sh) for this build.
# Carry .devbin (obscura.xz, optionally obscura-old.xz, scenes/crytek-sponza) and .gl.
# Writes $OUT/budget.tsv (build, technique, budget, ray_budget ms, AO pass ms, total ms) and
# $OUT/budget.txt (every bench's output).
set -uo pipefail
here=$(dirname "$0")
source "$here/device-env.sh"
builds=new
xz -dc .devbin/obscura.xz > /tmp/obscura-new && chmod +x /tmp/obscura-new
if [ -f .devbin/obscura-old.xz ]; then
  xz -dc .devbin/obscura-old.xz > /tmp/obscura-old && chmod +x /tmp/obscura-old
  builds="old new"
fi
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > "$out/gpu.txt" 2>&1
pixels=$((1920 * 1080))
printf 'build\ttechnique\tbudget\tray_budget_ms\tao_ms\ttotal_ms\n' > "$out/budget.tsv"
for build in $builds; do
  for t in rtao hemisphere; do
    for b in 0 $pixels $((pixels / 2)) $((pixels / 4)); do
      log=/tmp/bench-$build-$t-$b.txt
      /tmp/obscura-$build bench "${sponza[@]}" --size 1920x1080 --frames 100 --warmup 20 \
        --techniques $t --temporal --ray-budget $b > "$log" 2>&1
      cat "$log" >> "$out/budget.txt"
      rb=$(awk '$1 == "ray_budget" {print $2}' "$log")
      ao=$(awk -v t=$t '$1 == t && $3 == "ms" {print $2}' "$log")
      total=$(awk '$1 == "total" {print $2}' "$log")
      printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$build" "$t" "$b" "${rb:--}" "${ao:--}" "${total:--}" \
        >> "$out/budget.tsv"
    done
  done
done
OUT=$out/quality VIEWS=sponza TECHNIQUES=rtao \
  VARIANTS="x16=--temporal --timing-frames 15;x16half=--temporal --ray-budget $((pixels / 2)) --timing-frames 15" \
  OBSCURA_BIN=/tmp/obscura-new bash "$here/device-quality.sh" > /dev/null 2>&1
cp "$out/quality/quality.tsv" "$out/quality.tsv" 2>/dev/null
rm -rf "$out/quality"
cat "$out/gpu.txt" "$out/budget.tsv" "$out/quality.tsv"
