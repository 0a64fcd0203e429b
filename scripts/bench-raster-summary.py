#!/usr/bin/env python3
"""Markdown tables from the runs folder of scripts/device-bench-gbuffer.sh or
scripts/device-bench-sd-map.sh: per scene and build, the median over rounds of each raster pass
(G-buffer = triangle cull + visibility pass + occlusion pyramid + resolve, depth peeling = pass +
resolve, SD map =
clear + reset + triangle cull + map, or with `--sd-rasterizer compute` clear + bin + tiles + map, for
`sd-vao` and for `sd-svao`, whose map covers the requested pixels only) with fragments per
framebuffer pixel (for the compute rasteriser, the pixel centres its passes shade); then each stochastic-depth technique's total without the G-buffer; then the
peer's prepass. A run file is SCENE-SIDE-ROUND.json (SIDE: old or new)."""
import json
import pathlib
import statistics
import sys

runs = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "/tmp/out/runs")
PASSES = {
    "G-buffer": ("vao", ["triangle_cull", "gbuffer", "occlusion_pyramid", "gbuffer_resolve"], ["gbuffer"]),
    "depth peeling": ("vao-dual", ["depth_peel", "depth_peel_resolve"], ["depth_peel"]),
    "SD map S = 4": ("sd-vao", ["sd_clear", "sd_reset", "sd_cull", "sd_bin", "sd_tiles", "sd_map"], ["sd_map", "sd_bin", "sd_tiles"]),
    "SD map S = 4, requested pixels": ("sd-svao", ["sd_clear", "sd_reset", "sd_cull", "sd_bin", "sd_tiles", "sd_map"], ["sd_map", "sd_bin", "sd_tiles"]),
}
# Whole techniques without the G-buffer (what the stencil of sd-svao is for, seed 000 §3.9).
TOTALS = ["sd-vao", "sd-svao"]
totals = {}
cells = {}
# Frame spans (`span_ms`: first pass start to last pass end, what the GPU does between passes
# included), per scene, technique and side; absent in builds before it was reported.
spans = {}
adapter = None
for path in sorted(runs.glob("*-*-*.json")):
    scene, side, _ = path.stem.rsplit("-", 2)
    data = json.loads(path.read_text())
    adapter = adapter or f"{data['adapter']}, driver {data['driver']}"
    for r in data["results"]:
        if "span_ms" in r:
            spans.setdefault((scene, r["technique"], side), []).append(r["span_ms"])
        if r["technique"] in TOTALS:
            # `total_ms` holds `blur` once (its `blur_x` and `blur_y` are parts of it).
            p = r["passes"]
            ms = r["total_ms"] - sum(p.get(k, 0.0) for k in ["triangle_cull", "gbuffer", "occlusion_pyramid", "gbuffer_resolve"])
            totals.setdefault((scene, r["technique"], side), []).append(ms)
        for label, (technique, passes, counted) in PASSES.items():
            if r["technique"] != technique:
                continue
            ms = sum(r["passes"].get(p, 0.0) for p in passes)
            parts = "+".join(f"{r['passes'][p]:.3f}" for p in passes if p in r["passes"])
            # The compute rasteriser's passes count the pixel centres they shade, the first
            # layer's own included (the hardware's early depth test drops those before its count).
            counts = [r.get("fragments", {}).get(c, {}).get("per_pixel") for c in counted]
            counts = [c for c in counts if c is not None]
            frags = sum(counts) if counts else None
            cells.setdefault((scene, label, side), []).append((ms, parts, frags))
print(f"Adapter: {adapter}. Medians over rounds of per-run medians, ms.\n")
print("| scene | pass | old | new | new/old | fragments per pixel old → new |")
print("|---|---|---|---|---|---|")
for scene in dict.fromkeys(k[0] for k in cells):
    for label in PASSES:
        old, new = cells.get((scene, label, "old")), cells.get((scene, label, "new"))
        if not new:
            continue
        def med(v):
            return statistics.median(x[0] for x in v) if v else None
        o, n = med(old), med(new)
        fo = old[0][2] if old else None
        fn = new[0][2]
        ratio = f"{n / o:.2f}" if o else "–"
        frag = f"{fo:.2f} → {fn:.2f}" if fo is not None and fn is not None else "–"
        print(f"| {scene} | {label} | {o and f'{o:.3f}' or '–'} | {n:.3f} ({new[0][1]}) | {ratio} | {frag} |")


def old_new_table(title, values, rows):
    """A table of medians per (scene, technique) row, old against new."""
    print(title)
    print("| scene | technique | old | new | new/old |")
    print("|---|---|---|---|---|")
    for scene, t in rows:
        old, new = values.get((scene, t, "old")), values.get((scene, t, "new"))
        if not new:
            continue
        o, n = (statistics.median(v) if v else None for v in (old, new))
        ratio = f"{n / o:.2f}" if o else "–"
        print(f"| {scene} | {t} | {o and f'{o:.3f}' or '–'} | {n:.3f} | {ratio} |")


if totals:
    old_new_table(
        "\nTechnique totals without the G-buffer (ms), medians over rounds:\n",
        totals,
        [(scene, t) for scene in dict.fromkeys(k[0] for k in totals) for t in TOTALS],
    )
if spans:
    old_new_table(
        "\nFrame span, first pass start to last pass end (ms; the G-buffer, AO and blur, and what"
        " the\nGPU does between passes), medians over rounds:\n",
        spans,
        list(dict.fromkeys((k[0], k[1]) for k in spans)),
    )
bevy = runs / "bevy_high.json"
if bevy.exists():
    peer = json.loads(bevy.read_text())
    p = peer["passes"]
    ssao = sum(p[k]["median_ms"] for k in p if k.startswith("ssao/"))
    print(f"\nPeer, same call ({peer['adapter']['name']}): Bevy depth + normal prepass "
          f"(`early prepass`) {p['early prepass']['median_ms']:.3f} ms; SSAO high, three passes, "
          f"{ssao:.3f} ms.")
