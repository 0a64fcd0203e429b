#!/usr/bin/env bash
# Make sure a Vulkan driver is installed, and what the viewer's test needs to open a window without
# a screen. On a machine without them (no GPU, fresh Debian/Ubuntu), install Mesa's software
# Vulkan driver (lavapipe: slow but real, enough for the demo and tests), Xvfb (a virtual X
# display: `obscura view` runs under it in tests/it/view.rs) and the X libraries winit loads at run
# time. Only what is missing is installed; nothing at all when everything is there.
set -euo pipefail
need=()
# Any one of the usual ICD folders holding a manifest will do (`ls` of all three would fail as soon
# as one folder is missing).
have_icd=no
for icd in /usr/share/vulkan/icd.d/*.json /etc/vulkan/icd.d/*.json /usr/local/share/vulkan/icd.d/*.json; do
  if [ -e "$icd" ]; then have_icd=yes; break; fi
done
if [ "$have_icd" = no ]; then
  echo "ensure-vulkan: no Vulkan driver found; installing mesa-vulkan-drivers (software Vulkan)" >&2
  need+=(mesa-vulkan-drivers libvulkan1)
fi
if ! command -v Xvfb >/dev/null 2>&1; then
  echo "ensure-vulkan: no Xvfb found; installing xvfb (the viewer's test runs it)" >&2
  need+=(xvfb)
fi
# The libraries winit opens at run time for an X11 window (library, Debian package).
ldconfig_bin="$(command -v ldconfig || echo /sbin/ldconfig)"
libs="$("$ldconfig_bin" -p 2>/dev/null || true)"
for pair in libX11.so.6:libx11-6 libX11-xcb.so.1:libx11-xcb1 libxkbcommon-x11.so.0:libxkbcommon-x11-0 \
  libXcursor.so.1:libxcursor1 libXrandr.so.2:libxrandr2 libXi.so.6:libxi6; do
  if ! grep -qF "${pair%%:*}" <<<"$libs"; then need+=("${pair#*:}"); fi
done
if [ "${#need[@]}" -eq 0 ]; then exit 0; fi
echo "ensure-vulkan: installing ${need[*]}" >&2
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq "${need[@]}" >/dev/null
