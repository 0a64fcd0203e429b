#!/usr/bin/env bash
# The device benchmark driver: every build × round × view × size × variant as one
# `obscura bench --json` run, builds alternated within each round so that the card's drift shows
# as spread between rounds rather than as a difference between builds; then one summary
# (scripts/bench-summary.py). Run on the device machine from the repository root, with .devbin/
# (the release binary, the scenes, and the peer benchmark, as the device preparation gathers them)
# and .gl/ (the Vulkan loader) carried. Settings, all from the environment:
#   BUILDS      "name:binary ..." (default "new:$OBSCURA_BIN", i.e. new:./.devbin/obscura); a
#               binary missing but present as BINARY.xz is unpacked first. The first build is the
#               baseline of the summary's ratios, the last the one it calls new.
#   ROUNDS      rounds (default 2)
#   VIEWS       view names of scripts/device-env.sh's scene_args (default "sponza"): sponza,
#               sponza0, sponza-walk, colonnade, sibenik, stairs-dolly, or a built-in scene name
#   SIZES       "WxH ..." (default 1920x1080)
#   TECHNIQUES  `--techniques` list (default vao; "all" = every row of `obscura info --techniques`)
#   FRAMES, WARMUP  timed and warm-up frames (default 200 and 20)
#   EXTRA       more `bench` flags for every run (e.g. "--sd-samples 8")
#   VARIANTS    ";"-separated "label=flags" runs made for every build and view (default one run,
#               label "default", no flags), e.g. "plain=;bent=--bent-normals;high=--preset high"
#   ARGS_<build>  more `bench` flags for one build only (e.g. ARGS_new="--sd-rasterizer compute",
#               to compare a setting on one binary named twice)
#   PEER=1      also run the peer benchmark (Bevy SSAO, .devbin/bevy_ssao_bench.xz) on Sponza at
#               each size in the same call, at PEER_QUALITY ("medium high" by default)
#   STATS=1     also dump each build's WGSL and pipeline constants (OBSCURA_DUMP_WGSL, one short
#               run of TECHNIQUES and every variant) and print the driver's register counts and
#               binary sizes with .devbin/pipeline-stats(.xz) (built from tools/pipeline-stats)
#   SUMMARY_PASSES  passes the summary lists (default: all)
# Writes to $OUT: info.txt (adapter, driver, nvidia-smi), bench.txt (every run's output),
# summary.md, stats.txt (STATS=1), peer.txt (PEER=1) and runs.tar.gz: runs/*.json (every
# `bench --json` file and the peer's) and runs/manifest.tsv (file, build, round, view, size,
# variant, command). scripts/bench-table.py turns the runs into BENCHMARKS.md's tables.
# A dry run on lavapipe: OBSCURA_BIN=target/release/obscura VIEWS=stairs SIZES=160x96 FRAMES=3
#   WARMUP=1 OUT=/tmp/bench bash scripts/device-bench.sh
set -uo pipefail
here=$(dirname "$0")
source "$here/device-env.sh"
builds=${BUILDS:-new:$bin}
rounds=${ROUNDS:-2}
views=${VIEWS:-sponza}
sizes=${SIZES:-1920x1080}
frames=${FRAMES:-200}
warmup=${WARMUP:-20}
variants=${VARIANTS:-default=}
runs=$out/runs
mkdir -p "$runs"
for build in $builds; do
  b=${build#*:}
  [ -f "$b" ] || { [ -f "$b.xz" ] && xz -dkc "$b.xz" > "$b" && chmod +x "$b"; } ||
    { echo "device-bench.sh: build ${build%%:*}: no $b or $b.xz" >&2; exit 2; }
done
first=${builds%% *}
first_bin=${first#*:}
techniques=${TECHNIQUES:-vao}
[ "$techniques" = all ] && techniques=$($first_bin info --techniques)
{ $first_bin info; nvidia-smi --query-gpu=name,driver_version --format=csv 2>/dev/null; } \
  > "$out/info.txt" 2>&1
: > "$out/bench.txt"
printf 'file\tbuild\tround\tview\tsize\tvariant\tcommand\n' > "$runs/manifest.tsv"

if [ -n "${STATS:-}" ]; then
  stats=.devbin/pipeline-stats
  [ -f $stats ] || { [ -f $stats.xz ] && xz -dkc $stats.xz > $stats && chmod +x $stats; }
  scene_args "${views%% *}"
  for build in $builds; do
    name=${build%%:*}
    IFS=';' read -ra vs <<< "$variants"
    for v in "${vs[@]}"; do
      # shellcheck disable=SC2086 # flags are lists of flags
      OBSCURA_DUMP_WGSL=/tmp/dump-$name ${build#*:} bench "${args[@]}" --size 640x360 \
        --techniques "$techniques" ${EXTRA:-} ${v#*=} --frames 1 --warmup 0 > /dev/null 2>&1
    done
    echo "== $name" >> "$out/stats.txt"
    if [ -x $stats ]; then $stats /tmp/dump-$name >> "$out/stats.txt" 2>&1
    else echo "no .devbin/pipeline-stats: WGSL dumped to /tmp/dump-$name only" >> "$out/stats.txt"; fi
  done
fi

for round in $(seq "$rounds"); do
  for build in $builds; do
    name=${build%%:*}
    b=${build#*:}
    more=ARGS_$name
    for view in $views; do
      scene_args "$view" || { echo "== $view: scene not carried, skipped" >> "$out/bench.txt"; continue; }
      for size in $sizes; do
        IFS=';' read -ra vs <<< "$variants"
        for v in "${vs[@]}"; do
          label=${v%%=*}
          file=$view-$size-$label-$name-$round.json
          # shellcheck disable=SC2206 # flags are lists of flags
          flags=(${EXTRA:-} ${v#*=} ${!more:-})
          cmd=(bench "${args[@]}" --size "$size" --techniques "$techniques" --frames "$frames"
            --warmup "$warmup" "${flags[@]}")
          echo "== $file: obscura ${cmd[*]}" >> "$out/bench.txt"
          $b "${cmd[@]}" --json "$runs/$file" >> "$out/bench.txt" 2>&1 ||
            echo "== $file FAILED" >> "$out/bench.txt"
          printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$file" "$name" "$round" "$view" "$size" "$label" \
            "\`obscura ${cmd[*]}\`" >> "$runs/manifest.tsv"
        done
      done
    done
  done
done

if [ -n "${PEER:-}" ]; then
  if [ -f .devbin/bevy_ssao_bench.xz ]; then
    xz -dc .devbin/bevy_ssao_bench.xz > /tmp/bevy && chmod +x /tmp/bevy
    for size in $sizes; do
      for q in ${PEER_QUALITY:-medium high}; do
        echo "== peer $q $size" >> "$out/peer.txt"
        /tmp/bevy "${sponza[1]}" --size "$size" --quality "$q" --frames "$frames" --warmup 30 \
          --json "$runs/peer-$q-$size.json" >> "$out/peer.txt" 2>&1
      done
    done
  else
    echo "PEER=1: no .devbin/bevy_ssao_bench.xz (the device preparation copies it there)" | tee "$out/peer.txt"
  fi
fi

python3 "$here/bench-summary.py" "$runs" | tee "$out/summary.md"
tar -C "$out" -czf "$out/runs.tar.gz" runs && rm -rf "$runs"
