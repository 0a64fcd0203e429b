#!/usr/bin/env bash
# Make sure a Vulkan driver is installed. On a machine without one (no GPU, fresh Debian/Ubuntu),
# install Mesa's software Vulkan driver (lavapipe): slow but real, enough for the demo and tests.
set -euo pipefail
# Any one of the usual ICD folders holding a manifest will do (`ls` of all three would fail as soon
# as one folder is missing).
for icd in /usr/share/vulkan/icd.d/*.json /etc/vulkan/icd.d/*.json /usr/local/share/vulkan/icd.d/*.json; do
  if [ -e "$icd" ]; then exit 0; fi
done
echo "ensure-vulkan: no Vulkan driver found; installing mesa-vulkan-drivers (software Vulkan)" >&2
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq mesa-vulkan-drivers libvulkan1 >/dev/null
