#!/usr/bin/env bash
# Make sure a Vulkan driver is installed: on a machine without one (no GPU, fresh Debian/Ubuntu),
# install Mesa's software Vulkan driver (lavapipe: slow but real, enough for the demo and tests).
# With --for-tests, also what the viewer's test (crates/obscura-cli/tests/it/view.rs) needs to
# open a window without a screen: Xvfb (a virtual X display) and the X libraries winit loads at
# run time; and Python's venv module, with which scripts/python-tests.sh makes the Python package's
# virtual environment (Debian's python3 leaves it to the python3-venv package). The demo needs
# none of these. With --for-web, what the browser tests (scripts/web-tests.sh) need: Debian's
# Chromium (its headless mode runs WebGPU on the CPU, SwiftShader) and Node.js with npm (the test
# driver); no browser is ever downloaded.
#
# Only what is missing is installed, and nothing at all (no root needed) when everything is
# there. Installing needs root or sudo; without them the script says what to install and how.
# A busy package manager (unattended upgrades on a fresh machine) is waited for, up to
# ENSURE_VULKAN_LOCK_WAIT seconds (default 600).
#
# Usage: ensure-vulkan.sh [--for-tests] [--for-web] [--dry-run]
#   --dry-run  print the install command instead of running it (tests/it/ensure_vulkan.rs).
# ENSURE_VULKAN_ICD_DIRS (space-separated folders) replaces the folders searched for a Vulkan
# driver manifest, for that test.
set -euo pipefail
for_tests=no
for_web=no
dry_run=no
for arg in "$@"; do
  case "$arg" in
    --for-tests) for_tests=yes ;;
    --for-web) for_web=yes ;;
    --dry-run) dry_run=yes ;;
    *)
      echo "ensure-vulkan: unknown argument '$arg': use --for-tests (also what the tests need), --for-web (also what the browser tests need) and/or --dry-run" >&2
      exit 2
      ;;
  esac
done
need=()
# Any one of the usual ICD folders holding a manifest will do (`ls` of all three would fail as soon
# as one folder is missing).
have_icd=no
for dir in ${ENSURE_VULKAN_ICD_DIRS:-/usr/share/vulkan/icd.d /etc/vulkan/icd.d /usr/local/share/vulkan/icd.d}; do
  for icd in "$dir"/*.json; do
    if [ -e "$icd" ]; then have_icd=yes; break 2; fi
  done
done
if [ "$have_icd" = no ]; then
  echo "ensure-vulkan: no Vulkan driver found; mesa-vulkan-drivers (software Vulkan) is needed" >&2
  need+=(mesa-vulkan-drivers libvulkan1)
fi
if [ "$for_tests" = yes ]; then
  if ! command -v Xvfb >/dev/null 2>&1; then
    echo "ensure-vulkan: no Xvfb found; xvfb is needed (the viewer's test runs it)" >&2
    need+=(xvfb)
  fi
  # The libraries winit opens at run time for an X11 window (library, Debian package).
  ldconfig_bin="$(command -v ldconfig || echo /sbin/ldconfig)"
  libs="$("$ldconfig_bin" -p 2>/dev/null || true)"
  for pair in libX11.so.6:libx11-6 libX11-xcb.so.1:libx11-xcb1 libxkbcommon-x11.so.0:libxkbcommon-x11-0 \
    libXcursor.so.1:libxcursor1 libXrandr.so.2:libxrandr2 libXi.so.6:libxi6; do
    if ! grep -qF "${pair%%:*}" <<<"$libs"; then need+=("${pair#*:}"); fi
  done
fi
if [ "$for_tests" = yes ]; then
  if ! command -v python3 >/dev/null 2>&1; then
    echo "ensure-vulkan: no python3 found; python3 and python3-venv are needed (the Python package's tests)" >&2
    need+=(python3 python3-venv)
  elif ! python3 -c 'import venv, ensurepip' >/dev/null 2>&1; then
    echo "ensure-vulkan: python3 cannot make virtual environments; python3-venv is needed (the Python package's tests)" >&2
    need+=(python3-venv)
  fi
fi
if [ "$for_web" = yes ]; then
  # Program, Debian package.
  for pair in chromium:chromium node:nodejs npm:npm; do
    if ! command -v "${pair%%:*}" >/dev/null 2>&1; then
      echo "ensure-vulkan: no ${pair%%:*} found; ${pair#*:} is needed (the browser tests)" >&2
      need+=("${pair#*:}")
    fi
  done
fi
if [ "${#need[@]}" -eq 0 ]; then exit 0; fi

wait_s="${ENSURE_VULKAN_LOCK_WAIT:-600}"
apt=(apt-get -o "DPkg::Lock::Timeout=$wait_s")
if ! command -v apt-get >/dev/null 2>&1; then
  echo "ensure-vulkan: missing ${need[*]} (Debian package names), and this machine has no apt-get: install the equivalent packages (a Vulkan driver, e.g. Mesa's lavapipe) with its package manager" >&2
  exit 1
fi
sudo=()
if [ "$(id -u)" -ne 0 ]; then
  # sudo that would ask for a password with no terminal to ask on fails unclearly: say it here.
  if command -v sudo >/dev/null 2>&1 && { [ -t 0 ] || sudo -n true 2>/dev/null; }; then
    sudo=(sudo)
  else
    echo "ensure-vulkan: missing ${need[*]}, and installing needs root: run as root 'apt-get update && apt-get install -y ${need[*]}' (or this script with sudo), then this command again" >&2
    exit 1
  fi
fi
if [ "$dry_run" = yes ]; then
  echo "ensure-vulkan: would run: ${sudo[*]}${sudo:+ }${apt[*]} update -qq && ${sudo[*]}${sudo:+ }${apt[*]} install -y -qq ${need[*]}"
  exit 0
fi
# Say what apt-get will wait for, if anything holds the package database now.
busy="$(pgrep -a -x 'apt|apt-get|aptitude|dpkg|unattended-upgr|packagekitd' 2>/dev/null || true)"
if [ -n "$busy" ]; then
  echo "ensure-vulkan: the package manager is busy (${busy//$'\n'/; }): waiting up to $wait_s s for its lock" >&2
fi
echo "ensure-vulkan: installing ${need[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" "${apt[@]}" update -qq
"${sudo[@]}" "${apt[@]}" install -y -qq "${need[@]}" >/dev/null
