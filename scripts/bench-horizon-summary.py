#!/usr/bin/env python3
"""Markdown tables from scripts/device-bench-horizon.sh's $OUT: per scene the median ms of every
technique's passes (G-buffer left out), then seed 004 Tab. 1's analogue (ms, MAE, SSIM)."""
import json
import pathlib
import sys

out = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "/tmp/out")
for name in ["sponza", "sponza-high", "stairs", "colonnade"]:
    path = out / f"{name}.json"
    if not path.exists():
        continue
    data = json.loads(path.read_text())
    print(f"\n### {name} ({data['adapter']}, {data['driver']})\n")
    print("| technique | passes (ms) | all but G-buffer |")
    print("|---|---|---|")
    for r in data["results"]:
        passes = {k: v for k, v in r["passes"].items() if not k.startswith("gbuffer")}
        shown = ", ".join(f"{k} {v:.4f}" for k, v in passes.items() if k not in ("blur_x", "blur_y"))
        rest = sum(v for k, v in passes.items() if k not in ("blur_x", "blur_y"))
        print(f"| `{r['technique']}` | {shown} | {rest:.4f} |")
rows = []
for grid in ["8x10", "16x20", "32x40", "64x80"]:
    bench, report = out / f"tab1-{grid}.json", out / f"tab1-{grid}" / "report.json"
    if not (bench.exists() and report.exists()):
        continue
    passes = json.loads(bench.read_text())["results"][0]["passes"]
    result = json.loads(report.read_text())["results"][0]
    rows.append(f"| {grid.replace('x', ' × ')} | {passes['hbao']:.3f} | {result['mae']:.4f} | {result['ssim']:.4f} |")
if rows:
    print("\n### Seed 004 Tab. 1 analogue: HBAO on Crytek Sponza, 1280×720, R = 1\n")
    print("| D × S | AO pass (ms) | MAE | SSIM |")
    print("|---|---|---|---|")
    print("\n".join(rows))
rows = []
for levels in range(1, 6):
    bench, report = out / f"tab1-L{levels}.json", out / f"tab1-L{levels}" / "report.json"
    if not (bench.exists() and report.exists()):
        continue
    timed = {r["technique"]: r["passes"] for r in json.loads(bench.read_text())["results"]}
    measured = {r["technique"]: r for r in json.loads(report.read_text())["results"]}
    cells = []
    for t in ["pyramid-hbao", "sao"]:
        passes = timed[t]
        build = passes.get("depth_pyramid", 0.0)
        cells.append(f"{passes[t]:.3f} + {build:.3f} | {measured[t]['mae']:.4f} | {measured[t]['ssim']:.4f}")
    rows.append(f"| {levels} | " + " | ".join(cells) + " |")
if rows:
    print("\n### Seed 004 Tab. 1 analogue: Pyramid HBAO and SAO on Crytek Sponza, 1280×720, R = 1\n")
    print("| L | Pyramid HBAO: AO + pyramid (ms) | MAE | SSIM | SAO: AO + pyramid (ms) | MAE | SSIM |")
    print("|---|---|---|---|---|---|---|")
    print("\n".join(rows))
