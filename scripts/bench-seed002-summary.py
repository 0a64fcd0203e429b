#!/usr/bin/env python3
"""Seed 002 Tab. 1 and Fig. 7 analogue tables from scripts/device-bench-seed002.sh's runs.

Usage: bench-seed002-summary.py RUNS_DIR (the `obscura bench --json` files). Times in ms; every
total leaves out the G-buffer (`gbuffer` + `gbuffer_resolve`), which an engine has anyway.
"""
import json
import pathlib
import sys

runs = pathlib.Path(sys.argv[1])
SCENES = ["sponza", "tower", "grass", "stairs"]


def results(name):
    path = runs / f"{name}.json"
    if not path.exists():
        return {}
    return {r["technique"]: r for r in json.loads(path.read_text())["results"]}


def without_gbuffer(r):
    p = r["passes"]
    return r["total_ms"] - p.get("gbuffer", 0) - p.get("gbuffer_resolve", 0)


def cell(v):
    return "–" if v is None else f"{v:.3f}"


def cells(p, keys):
    """The passes `keys` of one run's pass timings `p`, as table cells."""
    return " | ".join(cell(p.get(k)) for k in keys)


print("### Seed 002 Tab. 1 analogue: `ray-sd-vao` pass by pass (ms)\n")
print("| scene | map resolution | intervals | request clear | AO phase 1 + requests | SD map "
      "| indirect set-up | AO phase 2 | blur | all but the G-buffer |")
print("|---|---|---|---|---|---|---|---|---|---|")
for scene in SCENES:
    for res in (1, 4):
        for intervals in (True, False):
            name = f"{scene}-res{res}" if intervals else f"{scene}-nointervals-res{res}"
            r = results(name).get("ray-sd-vao")
            if r is None:
                continue
            p = r["passes"]
            phases = ("sd_request_clear", "svao_phase1", "sd_map", "svao_indirect", "svao_phase2",
                      "blur")
            print(f"| {scene} | 1/{res} | {'on' if intervals else 'off'} | {cells(p, phases)} "
                  f"| {cell(without_gbuffer(r))} |")

print("\n### Seed 002 Fig. 7 analogue: all but the G-buffer (ms)\n")
print("| scene | `vao` (no map) | `ray-sd-vao` 1/1 | 1/2 | 1/4 | raster `sd-svao` | `rt-svao` |")
print("|---|---|---|---|---|---|---|")
for scene in SCENES:
    base = results(f"{scene}-baselines")
    ray = [results(f"{scene}-res{res}").get("ray-sd-vao") for res in (1, 2, 4)]
    row = [base.get("vao")] + ray + [base.get("sd-svao"), base.get("rt-svao")]
    print(f"| {scene} | " + " | ".join(cell(without_gbuffer(r)) if r else "–" for r in row) + " |")

print("\n### Seed 002 §3.5 / Fig. 14 analogue: the map's own guard band (ms)\n")
print("| scene | map resolution | band | request clear | AO phase 1 + requests | SD map "
      "| AO phase 2 | all but the G-buffer |")
print("|---|---|---|---|---|---|---|---|")
for scene in SCENES:
    for res in (1, 4):
        for band, name in (("512 px (default)", f"{scene}-res{res}"),
                           ("none", f"{scene}-noband-res{res}")):
            r = results(name).get("ray-sd-vao")
            if r is None:
                continue
            p = r["passes"]
            phases = ("sd_request_clear", "svao_phase1", "sd_map", "svao_phase2")
            print(f"| {scene} | 1/{res} | {band} | {cells(p, phases)} "
                  f"| {cell(without_gbuffer(r))} |")
