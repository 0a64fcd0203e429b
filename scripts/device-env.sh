# Sourced by the device scripts (scripts/device-bench*.sh): the Vulkan loader carried in .gl/
# unpacked, the Vulkan backend, the NVIDIA driver's ICD where the loader does not find it, and
# $bin, $out (created), $sponza and $sibenik (the views of BENCHMARKS.md) and scene_args (the
# views by name that scripts/device-bench.sh's VIEWS takes).
# The loader only on the device (its NVIDIA driver is mounted there), never over a local system
# where a script runs as a dry run.
if [ -d /usr/local/nvidia ]; then
  for f in .gl/*.deb; do dpkg -x "$f" / 2>/dev/null; done
  ldconfig
fi
export OBSCURA_BACKEND=vulkan
bin=${OBSCURA_BIN:-./.devbin/obscura}
# The carried binary is compressed (.devbin/obscura.xz): unpacked once, where it is missing.
[ -f "$bin" ] || { [ -f "$bin.xz" ] && xz -dkc "$bin.xz" > "$bin" && chmod +x "$bin"; }
# Only where that ICD exists, so that a dry run here keeps lavapipe.
nvidia_icd=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
if [ -f $nvidia_icd ] && { ! $bin info >/dev/null 2>&1 || ! $bin info | grep -qi nvidia; }; then
  export VK_DRIVER_FILES=$nvidia_icd
fi
out=${OUT:-/tmp/out}
mkdir -p "$out"
# Face normals, as the papers' tables and BENCHMARKS.md were measured (the default became the
# file's shading normals in issue 62); the scene file stays ${sponza[1]} (the Bevy runs read it).
sponza=(--scene .devbin/scenes/crytek-sponza/sponza.glb --eye=-9.5,1.8,-0.4 --target=0,3.5,0.6 --fov 60 --normals face)
sibenik=(--scene .devbin/scenes/sibenik/sibenik.obj --eye=-17,-9,0 --target=0,-10,0 --fov 60 --normals face)
# Sets `args` to the `bench` arguments of the view $1: sponza, sponza0 (guard band 0),
# sponza-walk (scripts/sponza-walk.json, a 5 m walk from the sponza view), colonnade (its
# close-up), sibenik, stairs-dolly (the built-in stairs along its `dolly` path), or any other name
# as a built-in scene at its first camera (stairs, tower, grass, ...); fails when the scene's
# files were not carried.
scene_args() {
  case $1 in
    sponza) args=("${sponza[@]}") ;;
    sponza0) args=("${sponza[@]}" --guard-band 0) ;;
    sponza-walk) args=("${sponza[0]}" "${sponza[1]}" --normals face --path scripts/sponza-walk.json) ;;
    colonnade) args=(--scene colonnade --camera closeup) ;;
    sibenik) [ -d .devbin/scenes/sibenik ] || return 1; args=("${sibenik[@]}") ;;
    stairs-dolly) args=(--scene stairs --path dolly) ;;
    *) args=(--scene "$1") ;;
  esac
  case $1 in sponza*) [ -f "${sponza[1]}" ] || return 1 ;; esac
}
