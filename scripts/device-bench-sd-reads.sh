#!/usr/bin/env bash
# The stochastic depth maps' readers against the build before (issue 11's "SD AO pass ≤ 2× its
# regular twin"): every row that reads a map, on Sponza 1920x1080 + 64 (S = 4, N = 4), and the
# regular twins, in one device call, both builds alternated over ROUNDS rounds. The old build is
# .devbin/obscura-old(.xz) (or OLD_BIN). Medians of 200 frames after 20 warm-up frames. Writes
# $OUT/summary.md and $OUT/runs.tar.gz.
set -uo pipefail
source "$(dirname "$0")/device-env.sh"
old=${OLD_BIN:-.devbin/obscura-old}
[ -f "$old" ] || xz -dkc "$old.xz" > "$old" && chmod +x "$old"
runs=$out/runs
mkdir -p "$runs"
techniques=ssao,sd-ssao,sd-ssao-stenciled,hbao,sd-hbao,hbao+,sd-hbao+,sd-hbao+-stenciled,gtao-vb,sd-gtao-vb,sd-gtao-vb-stenciled,vao,sd-vao,sd-svao,ray-sd-vao
for round in $(seq "${ROUNDS:-2}"); do
  for build in old new; do
    b=$bin
    [ $build = old ] && b=$old
    $b bench "${sponza[@]}" --size 1920x1080 --techniques $techniques --frames 200 --warmup 20 \
      --json "$runs/$build-$round.json" >> "$out/bench.txt" 2>&1
  done
done
python3 - "$runs" <<'PY' | tee "$out/summary.md"
import json, pathlib, statistics, sys
runs = pathlib.Path(sys.argv[1])
table = {}
for f in sorted(runs.glob("*.json")):
    build = f.stem.split("-")[0]
    for r in json.loads(f.read_text())["results"]:
        p = r["passes"]
        table.setdefault(r["technique"], {}).setdefault(build, []).append((p, r["total_ms"]))
print("| row | passes (old → new, medians over rounds) |")
print("|---|---|")
for t, builds in table.items():
    keys = sorted({k for b in builds.values() for p, _ in b for k in p})
    cells = []
    for k in keys:
        if k.startswith(("gbuffer", "blur")):
            continue
        v = {b: statistics.median(p.get(k, 0) for p, _ in builds[b]) for b in builds}
        cells.append(f"{k} {v.get('old', 0):.4f} → {v.get('new', 0):.4f}")
    print(f"| `{t}` | " + "; ".join(cells) + " |")
PY
tar -C "$out" -czf "$out/runs.tar.gz" runs bench.txt && rm -rf "$runs"
