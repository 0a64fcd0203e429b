#!/usr/bin/env bash
# Quality against cost on the device: for every view × variant one `obscura compare` against the
# hemisphere ground truth, and one line per technique in quality.tsv: view, variant, technique,
# MAE, SSIM, bright halo, and the median GPU ms of the timed frames after the G-buffer (the
# report's `gpu_ms`). A variant with `--temporal --timing-frames 15` compares the image after 16
# still frames (compare reads the image after its timed frames). Run on the device machine from
# the repository root with .devbin/ and .gl/ carried (scripts/device-bench.sh says how); settings
# from the environment:
#   VIEWS       view names of scripts/device-env.sh's scene_args (default "sponza sibenik")
#   SIZE        WxH (default 1920x1080)
#   TECHNIQUES  `--techniques` list (default "gtao,hemisphere,rtao")
#   SPP, RADIUS the ground truth's rays per pixel and R (default 1024 and 0.5; `--ao-radius`)
#   VARIANTS    ";"-separated "label=flags" (default "default=")
# Writes $OUT/quality.tsv, $OUT/quality.txt (every run's output) and $OUT/reports.tar.gz (each
# run's report.json).
# A dry run on lavapipe: OBSCURA_BIN=target/release/obscura VIEWS=stairs SIZE=96x64 SPP=64
#   OUT=/tmp/quality bash scripts/device-quality.sh
set -uo pipefail
here=$(dirname "$0")
source "$here/device-env.sh"
[ -f "$bin" ] || { [ -f "$bin.xz" ] && xz -dkc "$bin.xz" > "$bin" && chmod +x "$bin"; }
views=${VIEWS:-sponza sibenik}
size=${SIZE:-1920x1080}
techniques=${TECHNIQUES:-gtao,hemisphere,rtao}
spp=${SPP:-1024}
radius=${RADIUS:-0.5}
variants=${VARIANTS:-default=}
reports=$out/reports
mkdir -p "$reports"
printf 'view\tvariant\ttechnique\tmae\tssim\thalo_bright\tgpu_ms\n' > "$out/quality.tsv"
: > "$out/quality.txt"
IFS=';' read -ra variant_list <<< "$variants"
for view in $views; do
  scene_args "$view" || { echo "device-quality.sh: no files for view $view" >&2; continue; }
  for variant in "${variant_list[@]}"; do
    label=${variant%%=*}
    read -ra flags <<< "${variant#*=}"
    dir=$reports/$view-$label
    echo "== $view $label: ${flags[*]}" >> "$out/quality.txt"
    "$bin" compare "${args[@]}" --size "$size" --techniques "$techniques" \
      --reference-model hemisphere --spp "$spp" --ao-radius "$radius" "${flags[@]}" \
      --out "$dir" >> "$out/quality.txt" 2>&1 || { echo "failed: $view $label" >> "$out/quality.txt"; continue; }
    python3 - "$dir/report.json" "$view" "$label" >> "$out/quality.tsv" <<'PY'
import json, sys
report, view, label = sys.argv[1:]
for r in json.load(open(report))["results"]:
    ms = r.get("gpu_ms")
    print("\t".join([view, label, r["technique"], f"{r['mae']:.4f}", f"{r['ssim']:.4f}",
                     f"{r['halo_bright']:.4f}", "" if ms is None else f"{ms:.4f}"]))
PY
  done
done
tar czf "$out/reports.tar.gz" -C "$out" reports --exclude='*.png' --exclude='*.html' 2>/dev/null
rm -rf "$reports"
column -t -s $'\t' "$out/quality.tsv"
