#!/usr/bin/env bash
# Stochastic-depth benchmarks on the device GPU (BENCHMARKS.md): the analogues of seed 000 Tab. 1
# (cost of the hidden depth: single depth, depth peeling, SD2/SD4/SD8, stenciled SD2/4/8),
# Tab. 2 (VAO, VAO-dual, SD-VAO, SD-SVAO at S = 4: SD map / AO / total / speed-up) and Tab. 3
# (SD-VAO and SD-SVAO at 1440p and 4K) for crytek-sponza, colonnade, grass and tower.
# Same set-up as scripts/device-bench.sh: run from the repo root on the device machine with .devbin/
# (release binary + scenes, from the device preparation, scene crytek-sponza) and .gl/ carried.
# Results go to $OUT: info.txt, sd-bench.txt (the bench output), sd-bench.json (every run's JSON
# report by name, and the runs that failed) and sd-tables.md (the tables). The device tool returns
# at most 8 files, so the per-run JSON files stay in a scratch folder and are merged.
# An --sd-samples count the adapter cannot do (or any other failing run) is noted in the tables and
# the other runs go on. About 24 bench runs of 100 timed frames each.
# Local dry run on lavapipe (small sizes): OBSCURA_BIN=target/release/obscura HD=160x90
#   LARGER=192x108 FRAMES=3 WARMUP=1 OUT=/tmp/sd-out bash scripts/device-bench-sd.sh
set -uo pipefail
# The Vulkan loader from .gl/ only on the device (its NVIDIA driver is mounted there), not on a
# machine where this runs as a dry run.
if [ -d /usr/local/nvidia ]; then for f in .gl/*.deb; do dpkg -x "$f" / 2>/dev/null; done; ldconfig; fi
export OBSCURA_BACKEND=${OBSCURA_BACKEND:-vulkan}
bin=${OBSCURA_BIN:-./.devbin/obscura}
if ! $bin info >/dev/null 2>&1 || ! $bin info | grep -qi nvidia; then
  [ -f /usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json ] &&
    export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
fi
out=${OUT:-/tmp/out}
mkdir -p "$out"
runs=$(mktemp -d)
hd=${HD:-1920x1080}
larger=${LARGER:-2560x1440 3840x2160}
timing=(--frames "${FRAMES:-100}" --warmup "${WARMUP:-20}")
$bin info | tee "$out/info.txt"
$bin info --json >"$runs/info.json"
: >"$out/sd-bench.txt"

# bench NAME ARGS...: one `obscura bench` into $runs/NAME.json; a failure is logged and noted.
bench() {
  local name=$1 log="$runs/$1.log"
  shift
  echo "== $name: obscura bench $*" | tee -a "$out/sd-bench.txt"
  timeout 240 $bin bench "$@" "${timing[@]}" --json "$runs/$name.json" >"$log" 2>&1
  local rc=$?
  cat "$log" | tee -a "$out/sd-bench.txt"
  if [ $rc -ne 0 ]; then
    local why
    why=$(grep -m1 '^error:' "$log" || echo "exit status $rc")
    printf '%s\t%s\n' "$name" "$why" >>"$runs/failed.tsv"
    echo "== $name FAILED ($why); going on" | tee -a "$out/sd-bench.txt"
  fi
}

sponza=(--scene .devbin/scenes/crytek-sponza/sponza.glb --eye=-9.5,1.8,-0.4 --target=0,3.5,0.6 --fov 60 --normals face)
for scene in crytek-sponza colonnade grass tower; do
  if [ "$scene" = crytek-sponza ]; then s=("${sponza[@]}"); else s=(--scene "$scene"); fi
  bench "$scene-$hd-base" "${s[@]}" --size "$hd" --techniques vao,vao-dual
  for S in 2 4 8; do
    bench "$scene-$hd-S$S" "${s[@]}" --size "$hd" --techniques sd-vao,sd-svao --sd-samples "$S"
    bench "$scene-$hd-S$S-discard" "${s[@]}" --size "$hd" --techniques sd-svao --sd-samples "$S" --sd-mask discard
  done
  for size in $larger; do
    bench "$scene-$size-S4" "${s[@]}" --size "$size" --techniques sd-vao,sd-svao --sd-samples 4
    bench "$scene-$size-S4-discard" "${s[@]}" --size "$size" --techniques sd-svao --sd-samples 4 --sd-mask discard
  done
done

# Merge the runs and write the tables (python3's standard library only).
python3 - "$runs" "$out" "$hd" "$larger" "${FRAMES:-100}" <<'EOF'
import glob, json, os, sys

runs_dir, out, hd, larger, frames = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4].split(), sys.argv[5]
scenes = ["crytek-sponza", "colonnade", "grass", "tower"]
runs = {}
for path in sorted(glob.glob(os.path.join(runs_dir, "*.json"))):
    name = os.path.basename(path)[:-5]
    if name != "info":
        with open(path) as f:
            runs[name] = json.load(f)
with open(os.path.join(runs_dir, "info.json")) as f:
    info = json.load(f)
failed = {}
if os.path.exists(os.path.join(runs_dir, "failed.tsv")):
    with open(os.path.join(runs_dir, "failed.tsv")) as f:
        for line in f:
            name, _, why = line.rstrip("\n").partition("\t")
            failed[name] = why
with open(os.path.join(out, "sd-bench.json"), "w") as f:
    json.dump({"adapter": info, "runs": runs, "failed": failed}, f, indent=1)

# Passes that are not the AO kernel (everything else in a result is).
NOT_AO = {"gbuffer", "gbuffer_resolve", "depth_peel", "depth_peel_resolve", "sd_reset", "sd_map",
          "blur", "triangle_cull", "occlusion_pyramid", "sd_clear", "sd_cull"}
# The G-buffer: its raster (visibility) pass and its compute resolve.
GBUFFER = ("gbuffer", "gbuffer_resolve")

def result(run, technique):
    for r in runs.get(run, {}).get("results", []):
        if r["technique"] == technique:
            return r
    return None

def p(r, *passes):
    return sum(r["passes"].get(x, 0.0) for x in passes)

def ao(r):
    return sum(v for k, v in r["passes"].items() if k not in NOT_AO and not k.startswith("blur_"))

def ms(v):
    return "–" if v is None else f"{v:.3f}"

def missing(run):
    return "n/a" if run not in failed else "failed"

md = []
a = info
md.append("# Stochastic depth benchmarks\n")
md.append(f"Adapter: {a['name']} ({a['backend']}), driver {a['driver']} {a['driver_info']}; "
          f"SD map {a.get('sd_format', '?')}, --sd-samples {a.get('sd_layouts', '?')}. "
          f"Medians of {frames} frames, GPU timestamps, ms. Made by `scripts/device-bench-sd.sh`.\n")

# Tab. 1: hidden depth, at HD, every scene.
md.append(f"## Hidden depth ({hd}, seed 000 Tab. 1)\n")
md.append("Time of the pass(es) that make the depth, then in brackets the total with the single "
          "depth (G-buffer) pass of the same run. Every map = `sd_reset` (emptying it; for a "
          "stenciled map also the copy of the request mask into the stencil) + `sd_map`. SD = "
          "sd-vao's full map; Stenciled = sd-svao's (its phase 1 is not counted, as in the paper); "
          "Discard = sd-svao with `--sd-mask discard` (no stencil; the map's shader drops "
          "unrequested pixels).\n")
md.append("| | " + " | ".join(scenes) + " |")
md.append("|---|" + "---|" * len(scenes))

def tab1_row(label, run_of, technique, passes):
    cells = []
    for sc in scenes:
        run = run_of(sc)
        r = result(run, technique)
        if r is None:
            cells.append(missing(run))
            continue
        t = p(r, *passes) if passes else p(r, *GBUFFER)
        total = t if not passes else t + p(r, *GBUFFER)
        cells.append(f"{ms(t)} ({ms(total)})")
    md.append(f"| {label} | " + " | ".join(cells) + " |")

tab1_row("single depth", lambda sc: f"{sc}-{hd}-base", "vao", ())
tab1_row("depth peeling", lambda sc: f"{sc}-{hd}-base", "vao-dual", ("depth_peel", "depth_peel_resolve"))
def layout(S):
    """ " (2 maps of 4)" when S was stacked on this adapter."""
    for sc in scenes:
        r = result(f"{sc}-{hd}-S{S}", "sd-vao") or result(f"{sc}-{hd}-S{S}", "sd-svao")
        if r is not None and r.get("layout", {}).get("maps", 1) > 1:
            return f" ({r['layout']['maps']} maps of {r['layout']['samples_per_map']})"
    return ""

for S in (2, 4, 8):
    tab1_row(f"SD{S}{layout(S)}", lambda sc, S=S: f"{sc}-{hd}-S{S}", "sd-vao",
             ("sd_cull", "sd_reset", "sd_map"))
for S in (2, 4, 8):
    tab1_row(f"Stenciled-SD{S}{layout(S)}", lambda sc, S=S: f"{sc}-{hd}-S{S}", "sd-svao",
             ("sd_cull", "sd_reset", "sd_map"))
for S in (2, 4, 8):
    tab1_row(f"Discard-SD{S}{layout(S)}", lambda sc, S=S: f"{sc}-{hd}-S{S}-discard", "sd-svao",
             ("sd_cull", "sd_reset", "sd_map"))
md.append("")

# Tab. 2 / 3: AO techniques per scene and size (S = 4).
def ao_rows(sc, size, with_baselines):
    rows = []
    sd_run = f"{sc}-{size}-S4"
    base_run = f"{sc}-{size}-base"
    entries = []
    if with_baselines:
        entries += [("VAO", base_run, "vao"), ("VAO-dual", base_run, "vao-dual")]
    entries += [("SD-VAO", sd_run, "sd-vao"), ("SD-SVAO", sd_run, "sd-svao"),
                ("SD-SVAO (discard)", sd_run + "-discard", "sd-svao")]
    totals = {}
    blur = None
    for label, run, technique in entries:
        r = result(run, technique)
        if r is None:
            rows.append(f"| {label} | {missing(run)} | | | |")
            continue
        blur = r["passes"].get("blur", blur)
        total = r["total_ms"] - p(r, *GBUFFER)
        totals[label] = total
        depth = {"VAO": None, "VAO-dual": p(r, "depth_peel", "depth_peel_resolve"), "SD-VAO": p(r, "sd_cull", "sd_reset", "sd_map"),
                 "SD-SVAO": p(r, "sd_cull", "sd_reset", "sd_map"),
                 "SD-SVAO (discard)": p(r, "sd_cull", "sd_reset", "sd_map")}[label]
        depth_cell = ms(depth) if depth is not None else ""
        if label == "VAO-dual":
            depth_cell += " (peel)"
        if label.startswith("SD-SVAO"):
            ao_cell = f"{ms(p(r, 'svao_phase1'))}+{ms(p(r, 'svao_indirect', 'svao_phase2'))}"
            speedup = (f"{totals['SD-VAO'] / total:.2f}" if "SD-VAO" in totals and total > 0 else "")
        else:
            ao_cell, speedup = ms(ao(r)), ""
        rows.append(f"| {label} | {depth_cell} | {ao_cell} | {ms(total)} | {speedup} |")
    return rows, blur

md.append(f"## AO at {hd} (seed 000 Tab. 2), S = 4\n")
md.append("SD map: the stochastic depth map, its culling, reset and raster (SD-SVAO: limited to the requested "
          "pixels; VAO-dual: its "
          "depth peeling pass). AO: the kernel (SD-SVAO: phase 1 + indirect and phase 2). Total: "
          "every pass but the G-buffer (seed 000 §4.2: depth and normals are taken as given), "
          "blur included. Speed-up: SD-VAO total / SD-SVAO total. SD-SVAO (discard): "
          "`--sd-mask discard` instead of the stencil.\n")
for sc in scenes:
    rows, blur = ao_rows(sc, hd, True)
    md.append(f"**{sc}** (blur {ms(blur)} ms)\n")
    md.append("| | SD map | AO | total | speed-up |")
    md.append("|---|---|---|---|---|")
    md += rows
    md.append("")

md.append("## Resolutions (seed 000 Tab. 3), S = 4\n")
md.append("Columns as above, for SD-VAO then SD-SVAO; default guard bands (64 px at 1080p, 96 at "
          "1440p, 128 at 4K).\n")
md.append("| scene | size | SD-VAO: SD map | AO | total | SD-SVAO: SD map | AO | total | speed-up | blur | SD-SVAO (discard): total | speed-up |")
md.append("|---|---|---|---|---|---|---|---|---|---|---|---|")
for sc in scenes:
    for size in [hd] + larger:
        run = f"{sc}-{size}-S4"
        v, sv = result(run, "sd-vao"), result(run, "sd-svao")
        cells = [sc, size]
        if v is None:
            cells += [missing(run), "", ""]
        else:
            cells += [ms(p(v, "sd_cull", "sd_reset", "sd_map")), ms(ao(v)), ms(v["total_ms"] - p(v, *GBUFFER))]
        if sv is None:
            cells += [missing(run), "", "", "", ""]
        else:
            total = sv["total_ms"] - p(sv, *GBUFFER)
            speedup = ""
            if v is not None and total > 0:
                speedup = f"{(v['total_ms'] - p(v, 'gbuffer')) / total:.2f}"
            cells += [ms(p(sv, "sd_cull", "sd_reset", "sd_map")),
                      f"{ms(p(sv, 'svao_phase1'))}+{ms(p(sv, 'svao_indirect', 'svao_phase2'))}",
                      ms(total), speedup, ms(sv["passes"].get("blur"))]
        d = result(run + "-discard", "sd-svao")
        if d is None:
            cells += [missing(run + "-discard"), ""]
        else:
            total = d["total_ms"] - p(d, *GBUFFER)
            speedup = ""
            if v is not None and total > 0:
                speedup = f"{(v['total_ms'] - p(v, 'gbuffer')) / total:.2f}"
            cells += [ms(total), speedup]
        md.append("| " + " | ".join(cells) + " |")
md.append("")

if failed:
    md.append("## Runs that failed\n")
    for name, why in sorted(failed.items()):
        md.append(f"- `{name}`: {why}")
    md.append("")
with open(os.path.join(out, "sd-tables.md"), "w") as f:
    f.write("\n".join(md))
print("\n".join(md))
EOF
rm -rf "$runs"
