#!/usr/bin/env bash
# The Python package's tests (crates/obscura-py, docs/PYTHON.md): makes the project's own virtual
# environment .venv (git-ignored) if missing, installs the pinned test tools and maturin
# (crates/obscura-py/requirements-dev.txt), builds the package's abi3 wheel with maturin into
# target/wheels, installs that wheel into the venv, then runs pytest on crates/obscura-py/tests.
# The tests run the CLI binary of the same build (target/release/obscura) to hold Python's results
# to the CLI's, bit for bit.
#
# After the README's test command (cargo test --workspace) this compiles little: the CLI is
# already built, and maturin's `-p obscura-py` build resolves every shared dependency with the
# workspace's features (crates/obscura-py/Cargo.toml pins the ones only other members turned on),
# so it reuses those artifacts and compiles only pyo3, numpy and the module's own crate (its
# environment differs from cargo's: pyo3's build script sees maturin's interpreter).
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
# The CLI the tests compare with, with the workspace's features (reused from the test build).
cargo build --release --workspace --bins --quiet
package=crates/obscura-py
# What an older version of this script left: the module copied into the source folder and that
# folder put on the venv's path. Removed, so that only the installed wheel is imported and the
# module is not packed into the wheel a second time.
rm -f "$package/python/obscura/"_native*.so "$package/python/obscura/.native.tmp"
site=$("$venv/bin/python" -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')
rm -f "$site/obscura.pth"
wheels=target/wheels
rm -f "$wheels"/obscura-*.whl
# --strip: the release profile keeps debug information (for profilers), which would make the
# wheel about 90 MB instead of about 20.
"$venv/bin/maturin" build --release --strip --quiet --manifest-path "$package/Cargo.toml" \
  --interpreter "$venv/bin/python" --out "$wheels"
wheel=$(ls "$wheels"/obscura-*.whl)
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check --no-deps \
  --force-reinstall "$wheel"
echo "python-tests: installed $wheel" >&2
"$venv/bin/python" -m pytest -q crates/obscura-py/tests "$@"
