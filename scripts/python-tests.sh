#!/usr/bin/env bash
# The Python package's tests (crates/obscura-py, docs/PYTHON.md): makes the project's own virtual
# environment .venv (git-ignored) if missing, installs the pinned build and test tools
# (crates/obscura-py/requirements-dev.txt), builds the wheel with maturin into it (release
# profile, the workspace's target/ folder: the library is not built again when `cargo test
# --release --workspace` built it with the same features) and runs pytest on
# crates/obscura-py/tests. The tests run the CLI binary the cargo tests built
# (target/release/obscura) to hold Python's results to the CLI's, bit for bit.
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
# The CLI the tests compare with (built by `cargo test --release --workspace`; built here if
# this script runs alone). `--workspace`, not `-p obscura-cli`: features are resolved over the
# whole workspace (this crate's pyo3 included) as the test command resolves them, so this reuses
# its build instead of compiling every dependency again with other features.
cargo build --release --workspace --bins --quiet
# maturin develop: builds the abi3 wheel's module and installs it into the venv (and sets
# PYO3_BUILD_EXTENSION_MODULE, so libpython is not linked).
VIRTUAL_ENV="$PWD/$venv" PATH="$PWD/$venv/bin:$PATH" \
  "$venv/bin/maturin" develop --release --quiet \
  --manifest-path crates/obscura-py/Cargo.toml
"$venv/bin/python" -m pytest -q crates/obscura-py/tests "$@"
