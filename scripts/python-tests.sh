#!/usr/bin/env bash
# The Python package's tests (crates/obscura-py, docs/PYTHON.md): makes the project's own virtual
# environment .venv (git-ignored) if missing, installs the pinned test tools
# (crates/obscura-py/requirements-dev.txt), builds the package's native module with cargo and
# installs the package into the venv in development mode, then runs pytest on
# crates/obscura-py/tests. The tests run the CLI binary of the same build
# (target/release/obscura) to hold Python's results to the CLI's, bit for bit.
#
# Why cargo and not maturin here: maturin (how wheels are made, docs/PYTHON.md) resolves the
# features of crates/obscura-py alone, and those differ from the whole workspace's (the CLI's
# eframe turns on more of wgpu's), so it compiled wgpu and the library a second time after the
# test build: minutes of CI's two cores. `cargo build --workspace` resolves them as `cargo test
# --workspace` does, so after the README's test command it compiles only the module's own crate.
# What maturin develop would add is the same thing: the module copied into the package's folder
# (python/obscura/_native.abi3.so) and that folder put on the venv's path (a .pth file).
#
# Needs python3 with its venv module (Debian: python3-venv, which `ensure-vulkan.sh --for-tests`
# installs when missing) and the package index (PyPI) the first time. PYTHON picks another
# interpreter (3.9 or later). Arguments go to pytest (e.g. -k render).
set -euo pipefail
cd "$(dirname "$0")/.."
python="${PYTHON:-python3}"
venv=.venv
if [ ! -x "$venv/bin/python" ]; then
  if ! command -v "$python" >/dev/null 2>&1; then
    echo "python-tests: no $python found: install Python 3.9 or later (Debian: apt-get install python3 python3-venv)" >&2
    exit 1
  fi
  if ! "$python" -c 'import venv, ensurepip' >/dev/null 2>&1; then
    echo "python-tests: $python cannot make a virtual environment: install its venv module (Debian: apt-get install python3-venv; or run scripts/ensure-vulkan.sh --for-tests as root)" >&2
    exit 1
  fi
  echo "python-tests: making $venv" >&2
  "$python" -m venv "$venv"
fi
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check \
  -r crates/obscura-py/requirements-dev.txt
# The CLI the tests compare with and the module, with the workspace's features (above).
cargo build --release --workspace --bins --lib --quiet
package=crates/obscura-py/python
# Copied to a temporary name and renamed: a Python process that has the old module loaded keeps
# its mapping.
cp target/release/libobscura_py.so "$package/obscura/.native.tmp"
mv -f "$package/obscura/.native.tmp" "$package/obscura/_native.abi3.so"
"$venv/bin/python" -m pip uninstall --quiet --yes obscura >/dev/null 2>&1 || true
site=$("$venv/bin/python" -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')
echo "$PWD/$package" >"$site/obscura.pth"
"$venv/bin/python" -m pytest -q crates/obscura-py/tests "$@"
