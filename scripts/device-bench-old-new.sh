#!/usr/bin/env bash
# One build against the one before, in one device call: `bench` of $TECHNIQUES on Sponza
# 1920x1080 + 64 (or the view in $VIEW, e.g. VIEW="--eye=… --target=… --fov 60"), both builds
# alternated over ROUNDS rounds (default 2), medians of 200 frames after 20 warm-up frames. The
# old build is .devbin/obscura-old(.xz) (or OLD_BIN); EXTRA is passed to both, EXTRA_NEW to the
# new one only (OLD_BIN=.devbin/obscura then compares a setting on one build). Writes
# $OUT/${NAME:-old-new}.md (per pass, old → new) and $OUT/${NAME:-old-new}-runs.tar.gz.
set -uo pipefail
source "$(dirname "$0")/device-env.sh"
old=${OLD_BIN:-.devbin/obscura-old}
[ -f "$old" ] || xz -dkc "$old.xz" > "$old" && chmod +x "$old"
name=${NAME:-old-new}
runs=$out/$name-runs
mkdir -p "$runs"
view=("${sponza[@]}")
[ -n "${VIEW:-}" ] && view=(--scene .devbin/scenes/crytek-sponza/sponza.glb $VIEW)
for round in $(seq "${ROUNDS:-2}"); do
  for build in old new; do
    b=$bin
    flags=${EXTRA:-}
    if [ $build = old ]; then b=$old; else flags="$flags ${EXTRA_NEW:-}"; fi
    # shellcheck disable=SC2086 # flags is a list of flags
    $b bench "${view[@]}" --size 1920x1080 --techniques "$TECHNIQUES" --frames 200 --warmup 20 \
      $flags --json "$runs/$build-$round.json" >> "$out/$name-bench.txt" 2>&1
  done
done
python3 - "$runs" <<'PY' | tee "$out/$name.md"
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
tar -C "$out" -czf "$out/$name-runs.tar.gz" "$name-runs" "$name-bench.txt" && rm -rf "$runs"
