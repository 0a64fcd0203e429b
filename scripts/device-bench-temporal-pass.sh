#!/usr/bin/env bash
# The temporal accumulation pass, several builds in one device call (issue 13's ≤ 0.03 ms target):
# `obscura bench --techniques vao --temporal` at 1920x1080, medians of 200 frames after 20 warm-up
# frames, ROUNDS rounds (default 2) alternating the builds:
#   still  — Crytek Sponza, camera of BENCHMARKS.md (a still camera reads one history texel);
#   moving — the built-in stairs `dolly` path (every frame moves: four texels, bilinear).
# BUILDS is a list of name:binary (xz-compressed binaries are unpacked first), e.g.
# BUILDS="before:.devbin/obscura-base after:.devbin/obscura". Writes $OUT/temporal-pass.md and
# $OUT/temporal-pass-runs.tar.gz. Carry .devbin (../shared/tools/prepare-device.sh crytek-sponza)
# and .gl.
set -uo pipefail
source "$(dirname "$0")/device-env.sh"
runs=$out/temporal-pass-runs
mkdir -p "$runs"
$bin info > "$runs/info.txt" 2>&1
for build in ${BUILDS:?name:binary list}; do
  b=${build#*:}
  [ -f "$b" ] || { xz -dkc "$b.xz" > "$b" && chmod +x "$b"; }
done
for round in $(seq "${ROUNDS:-2}"); do
  for build in $BUILDS; do
    name=${build%%:*}
    b=${build#*:}
    $b bench "${sponza[@]}" --size 1920x1080 --techniques vao --temporal --frames 200 --warmup 20 \
      --json "$runs/still-$name-$round.json" >> "$runs/bench.txt" 2>&1
    $b bench --scene stairs --path dolly --size 1920x1080 --techniques vao --temporal \
      --frames 200 --warmup 20 --json "$runs/moving-$name-$round.json" >> "$runs/bench.txt" 2>&1
  done
done
python3 - "$runs" "$BUILDS" <<'PY' | tee "$out/temporal-pass.md"
import json, pathlib, statistics, sys
runs = pathlib.Path(sys.argv[1])
names = [b.split(":")[0] for b in sys.argv[2].split()]
print("| view | " + " | ".join(names) + " |")
print("|---|" + "---|" * len(names))
for view in ("still", "moving"):
    cells = []
    for name in names:
        v = [json.loads(f.read_text())["results"][0]["passes"]["temporal"]
             for f in sorted(runs.glob(f"{view}-{name}-[0-9]*.json"))]
        cells.append(f"{statistics.median(v):.4f} ({', '.join(f'{x:.4f}' for x in v)})" if v else "–")
    print(f"| {view} | " + " | ".join(cells) + " |")
PY
tar -C "$out" -czf "$out/temporal-pass-runs.tar.gz" temporal-pass-runs && rm -rf "$runs"
