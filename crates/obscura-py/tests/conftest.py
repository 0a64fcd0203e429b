"""Shared fixtures: the repository, the CLI binary the Python results are held to, a scene."""

import pathlib
import subprocess

import numpy as np
import pytest

import obscura

ROOT = pathlib.Path(__file__).resolve().parents[3]
CLI = ROOT / "target" / "release" / "obscura"


@pytest.fixture(scope="session")
def cli():
    """Runs `obscura ARGS...`; returns the completed process (never raises on failure)."""
    if not CLI.exists():
        pytest.fail(f"{CLI} is missing: build it with cargo build --release --workspace")

    def run(*args):
        return subprocess.run(
            [str(CLI), *map(str, args)], capture_output=True, text=True, timeout=600
        )

    return run


@pytest.fixture(scope="session")
def stairs():
    return obscura.Scene("stairs")


def cli_error(process):
    """The CLI's error message: its stderr line after 'error: '."""
    assert process.returncode != 0, process.stderr
    lines = [l for l in process.stderr.splitlines() if l.startswith("error: ")]
    assert lines, process.stderr
    return lines[-1][len("error: "):]


def same_bits(a, b):
    """Whether two float32 images are equal bit for bit (NaN and -0.0 included)."""
    a = np.ascontiguousarray(a, dtype=np.float32)
    b = np.ascontiguousarray(b, dtype=np.float32)
    return a.shape == b.shape and np.array_equal(a.view(np.uint32), b.view(np.uint32))
