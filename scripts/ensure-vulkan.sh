#!/usr/bin/env bash
# Make sure a Vulkan driver is installed. On a machine without one (no GPU, fresh Debian/Ubuntu),
# install Mesa's software Vulkan driver (lavapipe): slow but real, enough for the demo and tests.
set -euo pipefail
if ls /usr/share/vulkan/icd.d/*.json /etc/vulkan/icd.d/*.json /usr/local/share/vulkan/icd.d/*.json >/dev/null 2>&1; then
  exit 0
fi
echo "ensure-vulkan: no Vulkan driver found; installing mesa-vulkan-drivers (software Vulkan)" >&2
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq mesa-vulkan-drivers libvulkan1 >/dev/null
