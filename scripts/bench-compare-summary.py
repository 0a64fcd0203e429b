#!/usr/bin/env python3
"""Summarise scripts/device-bench-compare.sh: per technique and pass, the median over rounds of
each build's per-pass medians, and new/old. Usage: bench-compare-summary.py DIR (the $OUT files)."""
import glob
import json
import os
import statistics
import sys

rows = {}
for side in ("old", "new"):
    for path in sorted(glob.glob(os.path.join(sys.argv[1], f"sponza-{side}-*.json"))):
        for result in json.load(open(path))["results"]:
            passes = dict(result["passes"], total=result["total_ms"])
            for name, ms in passes.items():
                rows.setdefault((result["technique"], name), {}).setdefault(side, []).append(ms)
print("| technique | pass | old ms | new ms | new/old |\n|---|---|---|---|---|")
for (technique, name), sides in rows.items():
    if name.startswith("blur_") or "old" not in sides or "new" not in sides:
        continue
    old, new = statistics.median(sides["old"]), statistics.median(sides["new"])
    print(f"| {technique} | {name} | {old:.4f} | {new:.4f} | {new / old:.3f} |")
