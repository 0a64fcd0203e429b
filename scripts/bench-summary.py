#!/usr/bin/env python3
"""Summary of a scripts/device-bench.sh call, as markdown.

Usage: bench-summary.py RUNS_DIR [--passes a,b,...]

RUNS_DIR holds the call's `obscura bench --json` files and its manifest.tsv (file, build, round,
view, size, variant, command). For every view, size, variant and technique row: each pass's
median over the rounds of each build's per-run medians, then `total` (`total_ms`, the passes'
sum, the blur counted once), `no G-buffer` (total less the G-buffer's triangle cull, pass,
occlusion pyramid and resolve) and `span` (first pass start to last pass end), with the last
build against the first (last/first) where there are two builds or more, and the spread over
rounds of the last build. Raster passes' fragments per framebuffer pixel where the adapter
counts them. Then the peer benchmark's passes (its peer-*.json files), if it ran.
Python 3 standard library only. SUMMARY_PASSES in the environment, or --passes, keeps only the
named passes (the three totals are always shown).
"""
import json
import os
import pathlib
import statistics
import sys

GBUFFER = ("triangle_cull", "gbuffer", "occlusion_pyramid", "gbuffer_resolve")


def main():
    args = sys.argv[1:]
    keep = os.environ.get("SUMMARY_PASSES", "")
    if "--passes" in args:
        i = args.index("--passes")
        keep = args[i + 1]
        del args[i:i + 2]
    keep = {p for p in keep.split(",") if p}
    runs = pathlib.Path(args[0] if args else "/tmp/out/runs")
    manifest = runs / "manifest.tsv"
    if not manifest.exists():
        sys.exit(f"bench-summary.py: no {manifest}")
    lines = manifest.read_text().splitlines()
    head = lines[0].split("\t")
    rows = [dict(zip(head, line.split("\t"))) for line in lines[1:]]
    builds = list(dict.fromkeys(r["build"] for r in rows))
    cells = {}  # (view, size, variant, technique) -> pass -> build -> [ms per round]
    frags = {}  # (view, size, variant, technique) -> pass -> build -> [per pixel]
    adapter = None
    commands = {}
    failed = []
    for r in rows:
        path = runs / r["file"]
        if not path.exists():
            failed.append(r["file"])
            continue
        data = json.loads(path.read_text())
        adapter = adapter or f"{data['adapter']} ({data.get('backend', '')}), driver {data['driver']}"
        commands.setdefault(r["variant"], r["command"])
        for res in data["results"]:
            key = (r["view"], r["size"], r["variant"], res["technique"])
            p = res["passes"]
            values = {k: v for k, v in p.items() if not k.startswith("blur_")}
            values["total"] = res["total_ms"]
            values["no G-buffer"] = res["total_ms"] - sum(p.get(k, 0.0) for k in GBUFFER)
            if "span_ms" in res:
                values["span"] = res["span_ms"]
            for k, v in values.items():
                cells.setdefault(key, {}).setdefault(k, {}).setdefault(r["build"], []).append(v)
            for k, f in (res.get("fragments") or {}).items():
                frags.setdefault(key, {}).setdefault(k, {}).setdefault(r["build"], []).append(f["per_pixel"])
    med = statistics.median
    print(f"Adapter: {adapter}. Builds: {', '.join(builds)} (each round runs them in this order). "
          "Medians over rounds of per-run medians, ms.\n")
    for variant, cmd in commands.items():
        print(f"- {variant}: {cmd} (per build, view and size)")
    print()
    two = len(builds) > 1
    header = "| view | size | variant | row | pass | " + " | ".join(builds)
    header += f" | {builds[-1]}/{builds[0]}" if two else ""
    header += f" | spread over rounds ({builds[-1]}) |"
    print(header)
    print("|---|---|---|---|---|" + "---|" * (len(builds) + (1 if two else 0) + 1))
    for key, passes in cells.items():
        view, size, variant, technique = key
        order = [k for k in passes if k not in ("total", "no G-buffer", "span")]
        order = [k for k in order if not keep or k in keep] + [k for k in ("total", "no G-buffer", "span") if k in passes]
        for k in order:
            by = passes[k]
            m = {b: med(v) for b, v in by.items()}
            line = f"| {view} | {size} | {variant} | `{technique}` | {k} | "
            line += " | ".join(f"{m[b]:.4f}" if b in m else "–" for b in builds)
            if two:
                first, last = m.get(builds[0]), m.get(builds[-1])
                line += " | " + (f"{last / first:.3f}" if first and last is not None else "–")
            last = by.get(builds[-1], [])
            line += " | " + (f"{min(last):.4f}–{max(last):.4f}" if last else "–") + " |"
            print(line)
    if frags:
        print("\nFragments per framebuffer pixel (raster passes; the compute rasteriser's own count):\n")
        print("| view | size | variant | row | pass | " + " | ".join(builds) + " |")
        print("|---|---|---|---|---|" + "---|" * len(builds))
        for (view, size, variant, technique), passes in frags.items():
            for k, by in passes.items():
                print(f"| {view} | {size} | {variant} | `{technique}` | {k} | "
                      + " | ".join(f"{med(by[b]):.2f}" if b in by else "–" for b in builds) + " |")
    peers = sorted(runs.glob("peer-*.json"))
    if peers:
        print("\nThe peer benchmark (Bevy SSAO) in the same call, median ms:\n")
        print("| run | depth + normal prepass | SSAO passes | SSAO total |")
        print("|---|---|---|---|")
        for f in peers:
            peer = json.loads(f.read_text())
            p = peer["passes"]
            ssao = {k: v["median_ms"] for k, v in p.items() if k.startswith("ssao/")}
            pre = p.get("early prepass", {}).get("median_ms")
            parts = " + ".join(f"{v:.4f}" for v in ssao.values())
            print(f"| {f.stem} ({peer['adapter']['name']}) | "
                  f"{'–' if pre is None else f'{pre:.4f}'} | {parts} | {sum(ssao.values()):.4f} |")
    if failed:
        print("\nRuns that wrote no JSON (see bench.txt): " + ", ".join(failed))


if __name__ == "__main__":
    main()
