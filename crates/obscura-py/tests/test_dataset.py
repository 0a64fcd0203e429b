"""Datasets from Python (docs/DATASETS.md): the local executor is the CLI's, and the Ray executor
(a local Ray cluster started by the test) writes the same bytes, retries a worker killed
mid-shard without leaving a partial file, and a resumed run writes only the missing shards."""

import hashlib
import json
import pathlib

import pytest

import obscura
import obscura.dataset
from conftest import ROOT

SPEC = ROOT / "examples" / "datasets" / "small.toml"
# Files whose bytes vary between runs by design (times).
VARYING = {"timings.jsonl", "summary.json"}


def digests(folder: pathlib.Path):
    """Every file's sha256 under `folder`, by relative path, but the ones holding times."""
    return {
        str(p.relative_to(folder)): hashlib.sha256(p.read_bytes()).hexdigest()
        for p in sorted(folder.rglob("*"))
        if p.is_file() and p.name not in VARYING
    }


def manifest_ids(folder: pathlib.Path):
    return [json.loads(line)["id"] for line in (folder / "manifest.jsonl").read_text().splitlines()]


@pytest.fixture(scope="module")
def local_run(tmp_path_factory, cli):
    """The example spec (2 scenes × 4 views, 4 shards) by the CLI and by Python's local executor."""
    by_cli = tmp_path_factory.mktemp("cli")
    run = cli("dataset", SPEC, "--out", by_cli)
    assert run.returncode == 0, run.stderr
    by_python = tmp_path_factory.mktemp("local")
    summary = obscura.dataset.run(SPEC, by_python)
    return by_cli, by_python, summary


def test_the_local_executor_writes_the_clis_bytes(local_run):
    by_cli, by_python, summary = local_run
    assert summary["shards"] == 4 and summary["written"] == 4
    files = digests(by_python)
    assert len([f for f in files if f.endswith(".exr")]) == 8
    assert files == digests(by_cli)
    assert sorted(manifest_ids(by_python)) == list(range(8))


def test_a_bad_spec_raises_before_anything_is_written(tmp_path):
    spec = tmp_path / "bad.toml"
    spec.write_text(SPEC.read_text().replace("spp = 16", "spp = 0"))
    out = tmp_path / "out"
    with pytest.raises(obscura.DatasetError, match=r"truth\.spp"):
        obscura.dataset.run(spec, out)
    assert not out.exists()
    with pytest.raises(obscura.DatasetError, match="executor"):
        obscura.dataset.run(SPEC, out, executor="slurm")


def test_a_resumed_run_writes_only_the_missing_shards(local_run, tmp_path):
    _, by_python, _ = local_run
    out = tmp_path / "resumed"
    obscura.dataset.run(SPEC, out)
    # An interrupted run: one shard's manifest (written last) never made it.
    (out / "shard-00002" / "manifest.jsonl").unlink()
    kept = (out / "shard-00000" / "manifest.jsonl").stat().st_mtime_ns
    summary = obscura.dataset.run(SPEC, out)
    assert (summary["skipped"], summary["redone"], summary["written"]) == (3, 1, 0)
    assert (out / "shard-00000" / "manifest.jsonl").stat().st_mtime_ns == kept
    assert digests(out) == digests(by_python)


@pytest.fixture(scope="module")
def ray_cluster():
    import ray

    ray.init(num_cpus=2, include_dashboard=False, log_to_driver=False)
    yield ray
    ray.shutdown()


def test_ray_writes_the_local_bytes_and_retries_a_killed_worker(
    local_run, ray_cluster, tmp_path, monkeypatch
):
    _, by_python, _ = local_run
    # Shard 1's first attempt ends its worker process after one view (dataset._kill_switch).
    marker = tmp_path / "killed-once"
    monkeypatch.setenv("OBSCURA_DATASET_KILL_SHARD", f"1:{marker}")
    # Workers inherit the environment when they start: start them after setting it.
    ray_cluster.shutdown()
    ray_cluster.init(num_cpus=2, include_dashboard=False, log_to_driver=False)
    out = tmp_path / "ray"
    summary = obscura.dataset.run(SPEC, out, executor="ray")
    assert marker.exists(), "the kill switch never fired"
    # The retried shard started over its killed attempt's leftovers: none remain.
    assert not [p for p in out.rglob("*") if p.name.startswith(".")]
    assert summary["shards"] == 4 and summary["skipped"] == 0
    assert sorted(manifest_ids(out)) == list(range(8))
    assert digests(out) == digests(by_python)


def test_a_ray_gpu_id_picks_that_gpu_in_bus_order():
    from obscura import dataset

    default = obscura.default_device()
    # No id (num_gpus=0): the default device; GPU 0: the first GPU in PCI bus order, which on a
    # one-adapter machine is the default one; made once per worker process.
    assert dataset._worker_device([]).name == default.name
    first = dataset._worker_device([0])
    assert first.name == default.name and dataset._worker_device(["0"]) is first
    # An id past this machine's GPUs: one error naming the GPUs there are.
    with pytest.raises(obscura.GpuError, match="GPU 9 was asked for") as e:
        dataset._worker_device([9])
    assert default.name in str(e.value)
    with pytest.raises(obscura.DatasetError, match="not a GPU number"):
        dataset._worker_device(["GPU-5a1b"])
