#!/usr/bin/env bash
# Issue 59 on the device: the dataset runner's throughput against the raw `reference` command's,
# and the Ray executor's overhead over the local one (docs/DATASETS.md, BENCHMARKS.md "Datasets").
# Run from the repository root on the device machine with .devbin/ and .gl/ carried
# (scripts/device-bench.sh says how), plus for PART R (Python and Ray):
#   .devbin/py/_native.abi3.so.xz  the Python module built here (scripts/python-tests.sh builds
#                                  it: target/release/libobscura_py.so, stripped, xz)
#   .devbin/py/site.tar.xz         Ray for the device's Python (3.12) and what it needs beyond the
#                                  device's packages: `pip download --no-deps --only-binary=:all:
#                                  --python-version 3.12 --platform manylinux2014_x86_64` of ray,
#                                  jsonschema, jsonschema-specifications, referencing and rpds-py,
#                                  unzipped into one folder, ray/jars, ray/rllib, ray/llm and
#                                  ray/dashboard/client removed and the binaries stripped (so it
#                                  fits the 64 MiB a call carries: about 25 MiB as tar.xz)
# Parts (PART, default "ABR"):
#   A  raw `reference --model hemisphere` at SIZE and SPP, RUNS times per scene (its own printed
#      trace time: scene and BVH upload, pipeline and rays; the BVH build is not in it);
#   B  `obscura dataset` (the local executor) on one spec per scene: VIEWS random views, the truth
#      alone, and again storing depth, normals and albedo too;
#   R  Python: obscura.dataset.run(executor="local") and (executor="ray") on a Ray cluster
#      started beforehand, and the cluster's start on its own.
# Writes $OUT/dataset.tsv (part, scene, what, views, seconds, views/s, median truth ms) and
# $OUT/dataset.txt (every command's output).
# Dry run on lavapipe: OBSCURA_BIN=target/release/obscura SIZE=64 SPP=16 VIEWS=8 RUNS=2 \
#   SCENES="stairs" OUT=/tmp/ds bash scripts/device-dataset.sh
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
source "$here/device-env.sh"
[ ! -f "$bin" ] && [ -f "$bin.xz" ] && xz -dkc "$bin.xz" >"$bin" && chmod +x "$bin"
part=${PART:-ABR}
size=${SIZE:-512}
spp=${SPP:-256}
views=${VIEWS:-128}
per_shard=${PER_SHARD:-32}
runs=${RUNS:-5}
work=$(mktemp -d)
log=$out/dataset.txt
tsv=$out/dataset.tsv
: >"$log"
printf 'part\tscene\twhat\tviews\tseconds\tviews_per_s\ttruth_ms_median\n' >"$tsv"
$bin info >"$out/info.txt" 2>&1
nvidia-smi --query-gpu=name,driver_version,pci.bus_id --format=csv >>"$out/info.txt" 2>&1

# The scene's file (absolute) or built-in name, and the raw command's camera.
scene_of() {
  case $1 in
    sponza) echo "path = \"$PWD/.devbin/scenes/crytek-sponza/sponza.glb\"" ;;
    sibenik) echo "path = \"$PWD/.devbin/scenes/sibenik/sibenik.obj\"" ;;
    *) echo "name = \"$1\"" ;;
  esac
}
present() {
  case $1 in
    sponza) [ -f .devbin/scenes/crytek-sponza/sponza.glb ] ;;
    sibenik) [ -f .devbin/scenes/sibenik/sibenik.obj ] ;;
    *) true ;;
  esac
}
# spec SCENE STORE: a spec file for VIEWS random views of SCENE, storing STORE.
spec() {
  local file=$work/$1-$2.toml
  cat >"$file" <<EOF
seed = 59
size = [$size, $size]
views_per_shard = $per_shard
format = "npz"
store = [$(echo "$2" | sed 's/[a-z]*/"&"/g; s/+/, /g')]

[truth]
model = "hemisphere"
spp = $spp
radius = 0.5

[[scenes]]
$(scene_of "$1")
normals = "face"
views = $views
cameras = "random"
EOF
  echo "$file"
}
# row PART SCENE WHAT DATASET_DIR: one line of the table from a dataset's summary and timings.
row() {
  python3 - "$@" >>"$tsv" <<'PY'
import json, pathlib, statistics, sys
part, scene, what, folder = sys.argv[1:]
summary = json.load(open(pathlib.Path(folder) / "summary.json"))
truth = [json.loads(l)["ms"]["truth"] for t in pathlib.Path(folder).glob("shard-*/timings.jsonl")
         for l in open(t) if '"ms"' in l and '"truth"' in l]
med = statistics.median(truth) if truth else float("nan")
print("\t".join([part, scene, what, str(summary["views_written"]), f"{summary['seconds']:.3f}",
                 f"{summary['views_per_second']:.3f}", f"{med:.2f}"]))
PY
}

for scene in ${SCENES:-sponza sibenik}; do
  present "$scene" || { echo "no files for $scene" >>"$log"; continue; }
  if [[ $part == *A* ]]; then
    case $scene in
      sponza) cam=("${sponza[@]}") ;;
      sibenik) cam=("${sibenik[@]}") ;;
      *) cam=(--scene "$scene") ;;
    esac
    for i in $(seq 1 "$runs"); do
      echo "== A $scene run $i" >>"$log"
      $bin reference "${cam[@]}" --model hemisphere --spp "$spp" --size "${size}x${size}" \
        --no-cache --gpu --out "$work/ref.exr" >>"$log" 2>&1 || echo "failed" >>"$log"
    done
    python3 - "$log" "$scene" "$runs" >>"$tsv" <<'PY'
import re, statistics, sys
log, scene, runs = sys.argv[1], sys.argv[2], int(sys.argv[3])
text = open(log).read().split(f"== A {scene} run 1")[-1]
secs = [float(s) for s in re.findall(r"rays in ([0-9.]+) s", text)][:runs]
if secs:
    med = statistics.median(secs)
    print(f"A\t{scene}\treference (median of {len(secs)})\t1\t{med:.3f}\t{1/med:.3f}\t{med*1e3:.2f}")
PY
  fi
  if [[ $part == *B* ]]; then
    for store in truth depth+normals+albedo+truth; do
      s=$(spec "$scene" "$store")
      echo "== B $scene $store" >>"$log"
      t0=$(date +%s.%N)
      $bin dataset "$s" --out "$work/cli-$scene-$store" >>"$log" 2>&1 || echo "failed" >>"$log"
      echo "process wall: $(python3 -c "print(round($(date +%s.%N) - $t0, 3))") s" >>"$log"
      row B "$scene" "cli local $store" "$work/cli-$scene-$store"
    done
  fi
  if [[ $part == *R* ]] && [ -f .devbin/py/_native.abi3.so.xz ]; then
    if [ ! -d "$work/py/obscura" ]; then
      mkdir -p "$work/py" "$work/site"
      cp -r crates/obscura-py/python/obscura "$work/py/"
      xz -dc .devbin/py/_native.abi3.so.xz >"$work/py/obscura/_native.abi3.so"
      [ -f .devbin/py/site.tar.xz ] && tar -xJf .devbin/py/site.tar.xz -C "$work/site"
    fi
    s=$(spec "$scene" truth)
    echo "== R $scene" >>"$log"
    PYTHONPATH="$work/py:$work/site${PYTHONPATH:+:$PYTHONPATH}" PYTHONUNBUFFERED=1 python3 - "$s" "$work/r-$scene" >>"$log" 2>&1 <<'PY'
import json, sys, time
import obscura.dataset
spec, base = sys.argv[1:]
t = time.monotonic()
local = obscura.dataset.run(spec, base + "-local")
print(f"python local: {local['views_written']} views in {local['seconds']:.3f} s = {local['views_per_second']:.3f} views/s")
try:
    import ray
except ImportError as e:
    print(f"no ray: {e}"); sys.exit(0)
t = time.monotonic()
ray.init(include_dashboard=False, log_to_driver=False)
print(f"ray.init: {time.monotonic() - t:.3f} s; resources {ray.cluster_resources()}")
summary = obscura.dataset.run(spec, base + "-ray", executor="ray")
print(f"python ray: {summary['views_written']} views in {summary['seconds']:.3f} s = {summary['views_per_second']:.3f} views/s, devices {summary['devices']}")
# A second Ray run: worker processes (and their devices) are warm now, as in a long job.
summary = obscura.dataset.run(spec, base + "-ray2", executor="ray")
print(f"python ray warm: {summary['views_written']} views in {summary['seconds']:.3f} s = {summary['views_per_second']:.3f} views/s")
PY
    for kind in local ray ray2; do
      [ -f "$work/r-$scene-$kind/summary.json" ] && row R "$scene" "python $kind truth" "$work/r-$scene-$kind"
    done
    # The executors must write the same bytes (the manifests' hashes).
    for kind in ray ray2; do
      [ -f "$work/r-$scene-$kind/manifest.jsonl" ] &&
        { cmp -s "$work/r-$scene-local/manifest.jsonl" "$work/r-$scene-$kind/manifest.jsonl" &&
          echo "R $scene: $kind manifest = local manifest" || echo "R $scene: $kind manifest DIFFERS"; } >>"$log"
    done
    [ -f "$work/cli-$scene-truth/manifest.jsonl" ] &&
      { cmp -s "$work/cli-$scene-truth/manifest.jsonl" "$work/r-$scene-local/manifest.jsonl" &&
        echo "R $scene: python manifest = CLI manifest" || echo "R $scene: python manifest DIFFERS from CLI"; } >>"$log"
  fi
done
cat "$tsv"
