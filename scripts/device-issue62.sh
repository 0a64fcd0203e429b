#!/usr/bin/env bash
# Issue 62 on the device, one call: (A) what the raster stochastic map's guard band and its
# nearest-layer selection cost with the compute rasteriser (the default on GPUs), to choose their
# defaults; (B) the rows issue 62 found wrong against the truth, before ($OLD_BIN) and after
# ($bin), against the hemisphere ground truth (scripts/device-quality.sh).
# Run from the repository root on the device machine with .devbin/ and .gl/ carried
# (scripts/device-bench.sh says how). Writes $OUT/sd-defaults.tsv (view, selection, band,
# technique, pass, median ms), $OUT/sd-defaults.txt (every run's output) and, for (B),
# $OUT/rows-old.tsv / rows-new.tsv.
# Dry run on lavapipe: OBSCURA_BIN=target/release/obscura SIZE=160x96 BANDS="0 16" FRAMES=3 \
#   WARMUP=1 PART=A OUT=/tmp/i62 bash scripts/device-issue62.sh
set -uo pipefail
here=$(dirname "$0")
source "$here/device-env.sh"
for b in "$bin" "${OLD_BIN:-}"; do
  [ -n "$b" ] && [ ! -f "$b" ] && [ -f "$b.xz" ] && xz -dkc "$b.xz" >"$b" && chmod +x "$b"
done
size=${SIZE:-1920x1080}
bands=${BANDS:-0 128 256 512}
part=${PART:-AB}
runs=$(mktemp -d)
$bin info >"$out/info.txt" 2>&1
if [[ $part == *A* ]]; then
  printf 'view\tselection\tband\ttechnique\tpass\tms\n' >"$out/sd-defaults.tsv"
  : >"$out/sd-defaults.txt"
  for view in ${VIEWS:-sponza sibenik}; do
    scene_args "$view" || { echo "no files for $view" >>"$out/sd-defaults.txt"; continue; }
    for selection in stochastic nearest; do
      for band in $bands; do
        name=$view-$selection-$band
        echo "== $name" >>"$out/sd-defaults.txt"
        timeout 300 "$bin" bench "${args[@]}" --size "$size" --techniques sd-vao,sd-svao,sd-gtao-vb \
          --sd-select "$selection" --sd-map-guard-band "$band" --frames "${FRAMES:-100}" \
          --warmup "${WARMUP:-20}" --json "$runs/$name.json" >>"$out/sd-defaults.txt" 2>&1 ||
          { echo "failed: $name" >>"$out/sd-defaults.txt"; continue; }
        python3 - "$runs/$name.json" "$view" "$selection" "$band" >>"$out/sd-defaults.tsv" <<'PY'
import json, sys
path, view, selection, band = sys.argv[1:]
report = json.load(open(path))
for r in report["results"]:
    for name, ms in r["passes"].items():
        print("\t".join([view, selection, band, r["technique"], name, f"{ms:.4f}"]))
    print("\t".join([view, selection, band, r["technique"], "total", f"{r['total_ms']:.4f}"]))
PY
      done
    done
  done
fi
if [[ $part == *B* ]]; then
  techniques=${ROW_TECHNIQUES:-ssao,sao,gtao,gtao-vb,hbao,pyramid-hbao}
  for which in old new; do
    b=$bin
    [ $which = old ] && b=${OLD_BIN:-}
    [ -n "$b" ] && [ -f "$b" ] || continue
    OBSCURA_BIN=$b OUT=$runs/$which TECHNIQUES=$techniques SPP=${SPP:-256} \
      bash "$here/device-quality.sh" >/dev/null 2>&1
    cp "$runs/$which/quality.tsv" "$out/rows-$which.tsv"
    cat "$runs/$which/quality.txt" >>"$out/sd-defaults.txt"
  done
fi
column -t -s $'\t' "$out/sd-defaults.tsv" 2>/dev/null | head -80
