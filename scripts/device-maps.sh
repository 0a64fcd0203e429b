#!/usr/bin/env bash
# Issue 58 on the device, one call: the hemisphere march over the stochastic depth maps
# (`sd-hemisphere`, `ray-sd-hemisphere`) against the march over the first layer (`hemisphere`),
# the rays through the BVH (`rtao`) and `gtao`, at 1920x1080 on Sponza and Sibenik.
# 1. quality against cost (scripts/device-quality.sh, 1024-ray hemisphere truth): one frame at
#    the defaults, one frame at `--preset high` (gtao high; 2 rays and 12 steps for the hemisphere
#    rows), and after 16 still frames with temporal accumulation;
# 2. GPU times per pass (`bench`, medians of 100 frames after 30 warm-up frames) on Sponza.
# Carry .devbin (obscura.xz, scenes/crytek-sponza, scenes/sibenik) and .gl.
# Writes $OUT/summary.txt and $OUT/results.tar.gz.
set -uo pipefail
here=$(dirname "$0")
source "$here/device-env.sh"
runs=$out/runs
mkdir -p "$runs"
$bin info > "$runs/info.txt" 2>&1
export OBSCURA_CACHE_DIR=$out/cache
rows=gtao,hemisphere,sd-hemisphere,ray-sd-hemisphere,rtao

VIEWS="sponza sibenik" TECHNIQUES=$rows OUT=$runs/quality \
  VARIANTS="one=;high=--preset high;still16=--temporal --timing-frames 15" \
  bash "$here/device-quality.sh" > "$runs/quality.out" 2>&1

bench=("${sponza[@]}" --size 1920x1080 --frames 100 --warmup 30)
$bin bench "${bench[@]}" --techniques gtao --preset high > "$runs/bench-gtao-high.txt" 2>&1
$bin bench "${bench[@]}" --techniques hemisphere,sd-hemisphere,ray-sd-hemisphere,rtao \
  --temporal > "$runs/bench-hemisphere.txt" 2>&1
rm -rf "$out/cache"

{
  head -5 "$runs/info.txt"
  nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
  echo "== quality"; column -t -s $'\t' "$runs/quality/quality.tsv"
  for f in "$runs"/bench-*.txt; do
    echo "== $(basename "$f")"; grep -v "^\s*$" "$f" | tail -30
  done
} > "$out/summary.txt" 2>&1
tar czf "$out/results.tar.gz" -C "$out" runs
cat "$out/summary.txt"
