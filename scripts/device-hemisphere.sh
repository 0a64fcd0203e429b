#!/usr/bin/env bash
# Issue 58 on the device, in one call (carry .devbin and .gl; scripts/device-bench.sh says how):
# 1. quality against cost at 1920x1080 on Sponza and Sibenik (scripts/device-quality.sh): gtao,
#    hemisphere, hemisphere-dual, rtao and rtao-two-phase against the 1024-ray hemisphere truth, one frame, after
#    16 still frames (history unclipped), with the denoiser, under a ray budget of half a ray a
#    pixel and under a time budget;
# 2. rtao-two-phase's rays traced per view (`render --debug-out`, stats.json);
# 3. GPU times at 1920x1080 on Sponza (`bench`, medians of 100 frames after 30 warm-up frames,
#    whose frames settle a time budget): gtao high, rtao one ray, rtao under ray budgets of 1/4,
#    1/2 and 1 ray a pixel and a 0.6 ms time budget, hemisphere; the Bevy peer (medium, high);
# 4. along the built-in paths (stairs dolly, colonnade truck, tower climb; 24 frames at
#    320x192; 4096-ray hemisphere truth): temporal error and popping of gtao, hemisphere and
#    rtao, each with --temporal;
# 5. the GPU reference's rays/s with this build's BVH and with the previous build's
#    (.devbin/obscura-old.xz, if carried), Sponza 1920x1080 at 256 rays a pixel.
# Writes $OUT/summary.txt and $OUT/results.tar.gz.
set -uo pipefail
here=$(dirname "$0")
source "$here/device-env.sh"
[ -f "$bin" ] || { xz -dkc "$bin.xz" > "$bin" && chmod +x "$bin"; }
runs=$out/runs
mkdir -p "$runs"
$bin info > "$runs/info.txt" 2>&1
export OBSCURA_CACHE_DIR=$out/cache

# 1. Quality against cost.
half=$((1920 * 1080 / 2))
VIEWS="sponza sibenik" TECHNIQUES=gtao,hemisphere,hemisphere-dual,rtao,rtao-two-phase OUT=$runs/quality \
  VARIANTS="one=;still16=--temporal --temporal-no-clamp --timing-frames 15;denoised16=--temporal --temporal-no-clamp --denoise --timing-frames 15;budget16=--temporal --temporal-no-clamp --ray-budget $half --timing-frames 15;time16=--temporal --temporal-no-clamp --time-budget 0.6 --timing-frames 15" \
  bash "$here/device-quality.sh" > "$runs/quality.out" 2>&1

# 2. Rays traced by the two-phase row.
for view in sponza sibenik; do
  scene_args "$view" || continue
  mkdir -p "$runs/two-phase-$view"
  $bin render "${args[@]}" --size 1920x1080 --technique rtao-two-phase \
    --debug-out "$runs/two-phase-$view" --out "$runs/two-phase-$view/ao.png" \
    > "$runs/two-phase-$view.txt" 2>&1
done

# 3. GPU times.
bench=("${sponza[@]}" --size 1920x1080 --frames 100 --warmup 30)
$bin bench "${bench[@]}" --techniques gtao --preset high --json "$runs/bench-gtao-high.json" \
  > "$runs/bench-gtao-high.txt" 2>&1
$bin bench "${bench[@]}" --techniques hemisphere,rtao --temporal --json "$runs/bench-rtao.json" \
  > "$runs/bench-rtao.txt" 2>&1
for rays in 518400 1036800 2073600; do
  $bin bench "${bench[@]}" --techniques rtao --temporal --ray-budget $rays \
    --json "$runs/bench-budget-$rays.json" > "$runs/bench-budget-$rays.txt" 2>&1
done
$bin bench "${bench[@]}" --techniques rtao --temporal --time-budget 0.6 \
  --json "$runs/bench-time.json" > "$runs/bench-time.txt" 2>&1
if [ -f .devbin/bevy_ssao_bench.xz ]; then
  xz -dc .devbin/bevy_ssao_bench.xz > /tmp/bevy && chmod +x /tmp/bevy
  for q in medium high; do
    /tmp/bevy "${sponza[1]}" --size 1920x1080 --quality $q --frames 100 --warmup 30 \
      --json "$runs/peer-$q.json" > "$runs/peer-$q.txt" 2>&1
  done
fi

# 4. Along the built-in paths.
for pair in stairs:dolly colonnade:truck tower:climb; do
  scene=${pair%%:*}
  path=${pair##*:}
  $bin compare --scene "$scene" --path "$path" --frames 24 --size 320x192 --timing-frames 0 \
    --reference-model hemisphere --spp 4096 --techniques gtao,hemisphere,rtao --temporal \
    --out "$runs/path-$scene" > "$runs/path-$scene.md" 2> "$runs/path-$scene.err"
done

# 5. The reference's rays/s, this BVH and the previous build's.
ref=("${sponza[@]}" --size 1920x1080 --model hemisphere --spp 256 --no-cache)
$bin reference "${ref[@]}" --out "$runs/ref-new.exr" > "$runs/ref-new.txt" 2>&1
if [ -f .devbin/obscura-old.xz ]; then
  xz -dc .devbin/obscura-old.xz > /tmp/obscura-old && chmod +x /tmp/obscura-old
  /tmp/obscura-old reference "${ref[@]}" --out "$runs/ref-old.exr" > "$runs/ref-old.txt" 2>&1
  $bin reference "${ref[@]}" --out "$runs/ref-new2.exr" > "$runs/ref-new2.txt" 2>&1
fi
rm -f "$runs"/ref-*.exr
rm -rf "$out/cache"

{
  grep -h "" "$runs/info.txt" | head -5
  echo "== quality"; column -t -s $'\t' "$runs/quality/quality.tsv"
  for view in sponza sibenik; do
    echo "== two-phase $view"; cat "$runs/two-phase-$view/stats.json" 2>/dev/null
    grep -h "debug:" "$runs/two-phase-$view.txt"
  done
  for f in "$runs"/bench-*.txt "$runs"/peer-*.txt; do
    echo "== $(basename "$f")"; grep -v "^\s*$" "$f" | tail -25
  done
  for f in "$runs"/path-*.md; do
    echo "== $(basename "$f")"; grep -A8 "Along the camera" "$f" | grep '^| `'
  done
  for f in "$runs"/ref-*.txt; do echo "== $(basename "$f")"; grep "rays/s" "$f"; done
} > "$out/summary.txt" 2>&1
tar czf "$out/results.tar.gz" -C "$out" runs
