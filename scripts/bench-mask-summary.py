#!/usr/bin/env python3
"""Markdown table from the runs folder of scripts/device-bench-sd-mask.sh: per scene, `sd-vao`'s
full map and `sd-svao`'s map with each `--sd-mask`, the medians over rounds of the map (clear +
reset + triangle cull + raster, the raster's fragments per framebuffer pixel in brackets) and of the whole
technique without the G-buffer (`total_ms` less `gbuffer` and `gbuffer_resolve`), and `sd-vao`'s
total over each. A run file is SCENE-VARIANT-ROUND.json."""
import json
import pathlib
import statistics
import sys

runs = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "/tmp/out/runs")
MAP = ["sd_clear", "sd_reset", "sd_cull", "sd_map"]
cells = {}
adapter = None
for path in sorted(runs.glob("*-*-*.json")):
    scene, variant, _ = path.stem.rsplit("-", 2)
    data = json.loads(path.read_text())
    adapter = adapter or f"{data['adapter']}, driver {data['driver']}"
    for r in data["results"]:
        p = r["passes"]
        total = r["total_ms"] - p.get("gbuffer", 0.0) - p.get("gbuffer_resolve", 0.0)
        frags = r.get("fragments", {}).get("sd_map", {}).get("per_pixel", float("nan"))
        cells.setdefault((scene, variant), []).append(
            ([p.get(k, 0.0) for k in MAP], frags, total))
print(f"Adapter: {adapter}. Medians over rounds of per-run medians, ms.\n")
print("| scene | map | clear + reset + cull + raster (fragments per pixel) | total without G-buffer | `sd-vao` total / this |")
print("|---|---|---|---|---|")
med = statistics.median
for scene in dict.fromkeys(s for s, _ in cells):
    full = med(t for _, _, t in cells.get((scene, "full"), [(0, 0, float("nan"))]))
    for variant in ["full", "stencil", "depth", "discard"]:
        rows = cells.get((scene, variant))
        if not rows:
            continue
        parts = [med(r[0][i] for r in rows) for i in range(len(MAP))]
        frags = med(r[1] for r in rows)
        total = med(r[2] for r in rows)
        name = "full (`sd-vao`)" if variant == "full" else f"`--sd-mask {variant}`"
        print(f"| {scene} | {name} | {sum(parts):.3f} ({'+'.join(f'{x:.3f}' for x in parts)}; {frags:.2f}) "
              f"| {total:.3f} | {full / total:.2f} |")
