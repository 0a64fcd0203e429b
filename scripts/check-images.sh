#!/usr/bin/env bash
# Image identity across two builds (e.g. before and after a refactor): every technique renders the
# close-ups of stairs, colonnade and grass and Crytek Sponza's default view at 320x180 as float EXR
# with binary A and binary B, then `B diff` requires max |A - B| <= 1e-6 per image. Sponza renders
# with `--normals face` (both builds take it), so that builds from before issue 62's default of
# shading normals compare with later ones.
#
#   bash scripts/check-images.sh OLD_BIN NEW_BIN OUT_DIR [SPONZA_GLB]
#
# Renders go to OUT_DIR/a and OUT_DIR/b (A's renders are kept and reused when present, so a
# baseline made once can be checked against several later builds). TECHNIQUES overrides the list
# (default: every row of `B info --techniques`; rows A does not know are skipped, with a note);
# MAX_ABS overrides the bound.
set -euo pipefail
if [ $# -lt 3 ]; then
    echo "usage: $0 OLD_BIN NEW_BIN OUT_DIR [SPONZA_GLB]" >&2
    exit 2
fi
old=$1 new=$2 out=$3 sponza=${4:-../shared/scenes/crytek-sponza/sponza.glb}
techniques=${TECHNIQUES:-$("$new" info --techniques)}
max_abs=${MAX_ABS:-1e-6}
scenes=(stairs colonnade grass)
if [ -f "$sponza" ]; then scenes+=("$sponza"); else echo "note: no Sponza at '$sponza', skipped" >&2; fi
mkdir -p "$out/a" "$out/b"
failed=0
for scene in "${scenes[@]}"; do
    tag=$(basename "$scene" .glb)
    normals=()
    [ "$scene" = "$sponza" ] && normals=(--normals face)
    for t in ${techniques//,/ }; do
        if [ ! -f "$out/a/$tag-$t.exr" ] &&
            ! "$old" render --scene "$scene" "${normals[@]}" --technique "$t" --size 320x180 \
                --out "$out/a/$tag-$t.exr" >/dev/null 2>"$out/a/$tag-$t.log"; then
            echo "note: $old cannot render $t ($(grep -m1 error "$out/a/$tag-$t.log")); skipped" >&2
            continue
        fi
        "$new" render --scene "$scene" "${normals[@]}" --technique "$t" --size 320x180 --out "$out/b/$tag-$t.exr" >/dev/null
        if ! "$new" diff "$out/a/$tag-$t.exr" "$out/b/$tag-$t.exr" --max-abs "$max_abs"; then
            failed=1
        fi
    done
done
exit $failed
