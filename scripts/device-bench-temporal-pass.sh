#!/usr/bin/env bash
# What temporal accumulation costs, several builds in one device call (issue 13's ≤ 0.03 ms
# target): `obscura bench --techniques vao [--temporal]` at 1920x1080, medians of 200 frames after
# 20 warm-up frames, ROUNDS rounds (default 2) alternating the builds. The cost is the pass
# `temporal`, or for a build whose blur accumulates in its first pass (`temporal_blur_x`, the
# variant of BENCHMARKS.md 2026-12-04, not kept) that pass less the same round's plain
# `blur_x`. Views:
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
    for temporal in "" --temporal; do
      tag=${temporal:+-temporal}
      $b bench "${sponza[@]}" --size 1920x1080 --techniques vao $temporal --frames 200 \
        --warmup 20 --json "$runs/still-$name-$round$tag.json" >> "$runs/bench.txt" 2>&1
      $b bench --scene stairs --path dolly --size 1920x1080 --techniques vao $temporal \
        --frames 200 --warmup 20 --json "$runs/moving-$name-$round$tag.json" \
        >> "$runs/bench.txt" 2>&1
    done
  done
done
python3 - "$runs" "$BUILDS" <<'PY' | tee "$out/temporal-pass.md"
import json, pathlib, statistics, sys
runs = pathlib.Path(sys.argv[1])
names = [b.split(":")[0] for b in sys.argv[2].split()]
print("| view | " + " | ".join(names) + " |")
print("|---|" + "---|" * len(names))
def passes(path):
    return json.loads(path.read_text())["results"][0]["passes"]
def cost(view, name, round_):
    t = passes(runs / f"{view}-{name}-{round_}-temporal.json")
    if "temporal" in t:
        return t["temporal"]
    return t["temporal_blur_x"] - passes(runs / f"{view}-{name}-{round_}.json")["blur_x"]
for view in ("still", "moving"):
    cells = []
    for name in names:
        rounds = sorted({f.name.split("-")[2] for f in runs.glob(f"{view}-{name}-*-temporal.json")})
        v = [cost(view, name, r) for r in rounds]
        cells.append(f"{statistics.median(v):.4f} ({', '.join(f'{x:.4f}' for x in v)})" if v else "–")
    print(f"| {view} | " + " | ".join(cells) + " |")
print()
print("Accumulation and blur together (`temporal` + `blur`), and the blur alone, ms:")
print()
print("| view | " + " | ".join(names) + " |")
print("|---|" + "---|" * len(names))
for view in ("still", "moving"):
    cells = []
    for name in names:
        both = [sum(v for k, v in passes(f).items() if "temporal" in k or k.startswith("blur_"))
                for f in sorted(runs.glob(f"{view}-{name}-*-temporal.json"))]
        alone = [passes(f)["blur"] for f in sorted(runs.glob(f"{view}-{name}-[0-9]*.json"))
                 if "temporal" not in f.name]
        cells.append(f"{statistics.median(both):.4f} / {statistics.median(alone):.4f}" if both else "–")
    print(f"| {view} | " + " | ".join(cells) + " |")
PY
tar -C "$out" -czf "$out/temporal-pass-runs.tar.gz" temporal-pass-runs && rm -rf "$runs"
