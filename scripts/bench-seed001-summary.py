#!/usr/bin/env python3
"""Markdown tables from scripts/device-bench-seed001.sh's $OUT (median ms per pass, G-buffer left out):
seed 001 Tab. 1 (AO pass), Tab. 2 (sd-hbao+ total with the SD map's time in parentheses, full and
half resolution), the bent-normal and compensation costs."""
import json
import pathlib
import sys

out = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "/tmp/out")


def results(name):
    path = out / f"{name}.json"
    if not path.exists():
        return None
    data = json.loads(path.read_text())
    return data, {r["technique"]: r["passes"] for r in data["results"]}


def sd_map(p):
    return p.get("sd_map", 0.0) + p.get("sd_reset", 0.0)


def total(p):
    """Everything but the G-buffer (blur_x/blur_y are inside blur)."""
    return sum(v for k, v in p.items() if k not in ("gbuffer", "gbuffer_resolve", "blur_x", "blur_y"))


first = results("tab1-regular")
if first:
    data, regular = first
    print(f"\nAdapter: {data['adapter']}, driver {data['driver']}\n")
    print("### Seed 001 Tab. 1 analogue: AO pass (ms), Crytek Sponza 1920×1080 + 64, α = 0.2\n")
    print("| technique | regular | S = 1 | S = 2 | S = 4 | S = 8 | S = 16 |")
    print("|---|---|---|---|---|---|---|")
    for t in ["ssao", "hbao", "hbao+"]:
        cells = [f"{regular[t][t]:.3f}"]
        for s in [1, 2, 4, 8, 16]:
            r = results(f"tab1-sd{s}")
            cells.append(f"{r[1]['sd-' + t]['sd-' + t]:.3f}" if r else "–")
        print(f"| {t} | " + " | ".join(cells) + " |")

print("\n### Seed 001 Tab. 2 analogue: sd-hbao+ everything but the G-buffer (ms; the SD map's reset + raster in parentheses), α = 0.2\n")
print("| scene | resolution | S = 1 | S = 2 | S = 4 | S = 8 | S = 16 |")
print("|---|---|---|---|---|---|---|")
for scene in ["sponza", "sibenik", "stairs", "tower"]:
    for res in ["full", "half"]:
        cells = []
        for s in [1, 2, 4, 8, 16]:
            r = results(f"tab2-{scene}-sd{s}-{res}")
            if r:
                p = r[1]["sd-hbao+"]
                cells.append(f"{total(p):.3f} ({sd_map(p):.3f})")
            else:
                cells.append("–")
        print(f"| {scene} | {res} | " + " | ".join(cells) + " |")

off, on = results("bent-off"), results("bent-on")
if off and on:
    print("\n### Bent normals: AO pass (ms), Crytek Sponza 1920×1080 + 64\n")
    print("| technique | AO only | AO + bent normals | added |")
    print("|---|---|---|---|")
    for t in ["gtao", "gtao-vb", "sd-gtao-vb"]:
        a, b = off[1][t][t], on[1][t][t]
        print(f"| {t} | {a:.4f} | {b:.4f} | {100 * (b / a - 1):+.1f} % |")

one, two = results("compensation-1"), results("compensation-2")
if one and two:
    print("\n### Compensation 2 against 1: AO pass (ms), Crytek Sponza 1920×1080 + 64, S = 4\n")
    print("| technique | compensation 1 | compensation 2 |")
    print("|---|---|---|")
    for t in ["sd-hbao+", "sd-vao"]:
        print(f"| {t} | {one[1][t][t]:.4f} | {two[1][t][t]:.4f} |")

rows = []
for s in [1, 2, 4, 8]:
    cells = []
    for config in ["single", "multiview", "multiview-half", "multiview-second-half"]:
        r = results(f"tab3-sd{s}-{config}")
        if not r:
            cells.append("–")
            continue
        p = next(iter(r[1].values()))
        maps = sd_map(p) + p.get("multiview_sd_map", 0.0) + p.get("multiview_sd_reset", 0.0)
        cells.append(f"{total(p):.3f} ({maps:.3f})")
    rows.append(f"| {s}-sample SD-HBAO+ | " + " | ".join(cells) + " |")
if any("–" not in row.replace("| –", "") for row in rows) and results("tab3-sd1-single"):
    print("\n### Seed 001 Tab. 3 analogue: SD-HBAO+ on Sibenik, 1920×1080 + 64, α = 0.2 (ms, all but the G-buffer; both maps' reset + raster in parentheses)\n")
    print("| | single camera, full | multi-view, full | multi-view, half | multi-view, half second view only |")
    print("|---|---|---|---|---|")
    print("\n".join(rows))
