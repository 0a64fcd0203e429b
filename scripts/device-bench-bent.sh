#!/usr/bin/env bash
# What bent normals cost (issue 11's ≤ 10 %), several builds in one device call: `obscura bench
# --techniques $TECHNIQUES` with and without `--bent-normals` on Crytek Sponza with guard band 0
# (`sponza0` of device-env.sh) at 1920x1080, medians of 200 frames after 20 warm-up frames, at
# the defaults and at `--preset high` ($HIGH, default gtao,gtao-vb), ROUNDS rounds (default 2)
# alternating the builds; then each build's register counts for the bent passes
# (tools/pipeline-stats, if .devbin/pipeline-stats(.xz) was carried).
# BUILDS is a list of name:binary (xz-compressed binaries are unpacked first), e.g.
# BUILDS="base:.devbin/obscura-base new:.devbin/obscura". Writes $OUT/bent.md (the AO pass per
# row and build, and each build's change against the first) and $OUT/bent-runs.tar.gz. Carry
# .devbin (../shared/tools/prepare-device.sh crytek-sponza) and .gl. SIZE, FRAMES and WARMUP
# shrink the runs for a dry run on lavapipe.
set -uo pipefail
source "$(dirname "$0")/device-env.sh"
scene_args sponza0
techniques=${TECHNIQUES:-gtao,gtao-vb,sd-gtao-vb,vao,sd-vao,hbao+,sd-hbao+}
high=${HIGH:-gtao,gtao-vb}
runs=$out/bent-runs
mkdir -p "$runs"
for build in ${BUILDS:?name:binary list}; do
  b=${build#*:}
  [ -f "$b" ] || { xz -dkc "$b.xz" > "$b" && chmod +x "$b"; }
done
stats=.devbin/pipeline-stats
[ -f $stats ] || { [ -f $stats.xz ] && xz -dkc $stats.xz > $stats && chmod +x $stats; }
first=${BUILDS%% *}
${first#*:} info > "$runs/info.txt" 2>&1
nvidia-smi --query-gpu=name,driver_version --format=csv >> "$runs/info.txt" 2>&1
if [ -x $stats ]; then
  for build in $BUILDS; do
    name=${build%%:*}
    OBSCURA_DUMP_WGSL=/tmp/dump-$name ${build#*:} bench "${args[@]}" --size 640x360 \
      --techniques "$techniques" --bent-normals --frames 1 --warmup 0 > /dev/null 2>&1
    echo "== $name, bent normals" >> "$runs/stats.txt"
    $stats /tmp/dump-$name >> "$runs/stats.txt" 2>&1
  done
fi
for round in $(seq "${ROUNDS:-2}"); do
  for build in $BUILDS; do
    name=${build%%:*}
    b=${build#*:}
    run() {
      $b bench "${args[@]}" --size "${SIZE:-1920x1080}" --frames "${FRAMES:-200}" \
        --warmup "${WARMUP:-20}" "$@" >> "$runs/bench.txt" 2>&1
    }
    run --techniques "$techniques" --json "$runs/$name-plain-$round.json"
    run --techniques "$techniques" --bent-normals --json "$runs/$name-bent-$round.json"
    run --techniques "$high" --preset high --json "$runs/$name-high-$round.json"
    run --techniques "$high" --preset high --bent-normals --json "$runs/$name-highbent-$round.json"
  done
done
python3 - "$runs" "$BUILDS" <<'PY' | tee "$out/bent.md"
import json, pathlib, statistics, sys
runs = pathlib.Path(sys.argv[1])
builds = [b.split(":")[0] for b in sys.argv[2].split()]
ao = {}
for f in sorted(runs.glob("*.json")):
    build, kind, _ = f.stem.rsplit("-", 2)
    for r in json.loads(f.read_text())["results"]:
        ao.setdefault((r["technique"], kind), {}).setdefault(build, []).append(r["passes"][r["technique"]])
print("| row | " + " | ".join(builds) + " |")
print("|---|" + "---|" * len(builds))
for (t, kind), v in ao.items():
    m = {b: statistics.median(v[b]) for b in builds if b in v}
    cells = [f"{m[b]:.4f} ({100 * (m[b] / m[builds[0]] - 1):+.1f} %)" for b in builds if b in m]
    print(f"| `{t}` {kind} | " + " | ".join(cells) + " |")
print()
print("Bent normals against the plain pass, per build:")
for b in builds:
    for kinds in (("plain", "bent"), ("high", "highbent")):
        for (t, kind), v in ao.items():
            if kind == kinds[0] and (t, kinds[1]) in ao and b in v:
                plain, bent = statistics.median(v[b]), statistics.median(ao[(t, kinds[1])][b])
                print(f"- {b} `{t}` {kinds[0]}: {plain:.4f} → {bent:.4f} ({100 * (bent / plain - 1):+.1f} %)")
PY
grep -E "^==|gtao|vao|hbao" "$runs/stats.txt" 2>/dev/null | head -80 | tee -a "$out/bent.md"
tar -C "$out" -czf "$out/bent-runs.tar.gz" bent-runs && rm -rf "$runs"
