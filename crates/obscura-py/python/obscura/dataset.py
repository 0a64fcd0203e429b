"""Ground-truth AO datasets (docs/DATASETS.md), run here or on a Ray cluster.

A spec (TOML) names scenes, cameras, the truth and what to store; the library splits it into
shards whose bytes depend only on the spec and the shard's number. ``run`` writes them with the
local executor (one thread per GPU, as ``obscura dataset``) or as Ray tasks, one task per shard:
Ray schedules, places and retries them, and a retried shard starts over its own leftovers, so
both executors write the same bytes (``timings.jsonl`` and ``summary.json`` aside).

    import obscura.dataset
    summary = obscura.dataset.run("spec.toml", "out/")                 # this machine
    summary = obscura.dataset.run("spec.toml", "out/", executor="ray")  # a Ray cluster
"""

import json
import os
import time
from typing import Any, Callable, Dict, Optional, Union

from . import _native

PathLike = Union[str, "os.PathLike[str]"]


def run(
    spec: PathLike,
    out: PathLike,
    *,
    executor: str = "local",
    address: Optional[str] = None,
    devices: Optional[int] = None,
    num_gpus: Optional[float] = None,
    max_retries: int = 3,
    progress: Optional[Callable[[int], None]] = None,
) -> Dict[str, Any]:
    """Writes the dataset ``spec`` describes into ``out``; returns the summary (``summary.json``).

    ``executor="local"``: this machine's GPUs, at most ``devices`` of them. ``executor="ray"``:
    one Ray task per shard, on the cluster at ``address`` (``None``: the one this process is
    connected to, else a local one started for the call); each task takes ``num_gpus`` GPUs
    (default 1 where the cluster has GPUs, else 0) and is retried up to ``max_retries`` times
    when it fails or its worker dies. Every node must see ``spec`` (and the scene files it
    names) and ``out`` at the same paths: a shared file system.

    Finished shards are skipped and unfinished or damaged ones redone, so a rerun resumes.
    Raises ``DatasetError`` for a bad spec before anything is rendered.
    """
    spec, out = os.fspath(spec), os.fspath(out)
    if executor == "local":
        return json.loads(_native.dataset_run_local(spec, out, devices=devices, progress=progress))
    if executor != "ray":
        raise _native.DatasetError(
            f"unknown executor {executor!r}: use \"local\" or \"ray\""
        )
    return _run_on_ray(spec, out, address, num_gpus, max_retries)


def _run_on_ray(spec, out, address, num_gpus, max_retries):
    try:
        import ray
    except ImportError as e:
        raise _native.DatasetError(
            "executor=\"ray\" needs Ray: pip install ray (docs/DATASETS.md)"
        ) from e
    start = time.monotonic()
    # Checked (and out/dataset.json written) before any task is submitted.
    shards = _native.dataset_init(spec, out)
    if not ray.is_initialized():
        ray.init(address=address, include_dashboard=False, log_to_driver=False)
    if num_gpus is None:
        num_gpus = 1 if ray.cluster_resources().get("GPU", 0) > 0 else 0
    task = ray.remote(_shard_task).options(
        num_gpus=num_gpus, max_retries=max_retries, retry_exceptions=True
    )
    results = ray.get([task.remote(spec, index, out) for index in range(shards)])
    reports = [report for report, _ in results]
    devices = sorted({device for _, device in results})
    return json.loads(
        _native.dataset_finish(spec, out, reports, time.monotonic() - start, devices)
    )


def _shard_task(spec: str, index: int, out: str):
    """One shard in a Ray worker: its report (JSON text) and the device's name."""
    import ray

    device = _worker_device(ray.get_gpu_ids())
    report = _native.dataset_run_shard(
        spec, index, out, device=device, progress=_kill_switch(index)
    )
    return report, device.name


# A Ray worker process runs many shards: each GPU's device (and its adapter's shader cache) is
# made once per process, not once per task.
_WORKER_DEVICES: Dict[Any, Any] = {}


def _worker_device(gpu_ids) -> "_native.Device":
    """The device of the GPU Ray gave this task. Ray's GPU ids count a node's GPUs as
    ``nvidia-smi`` and NVML do (PCI bus order), and the Vulkan adapters are matched in that order
    (``Device(ordinal=…)``): ``CUDA_VISIBLE_DEVICES``, which Ray sets, narrows CUDA, not Vulkan.
    No GPU id (a task with ``num_gpus=0``, a CPU-only cluster): the default device."""
    key = str(gpu_ids[0]) if gpu_ids else None
    if key not in _WORKER_DEVICES:
        if key is None:
            _WORKER_DEVICES[key] = _native.default()
        else:
            try:
                ordinal = int(key)
            except ValueError:
                raise _native.DatasetError(
                    f"Ray gave this task GPU {key!r}, not a GPU number: start the Ray node with "
                    "CUDA_VISIBLE_DEVICES as numbers (0,1,…), not UUIDs"
                ) from None
            _WORKER_DEVICES[key] = _native.Device(ordinal=ordinal)
    return _WORKER_DEVICES[key]


def _kill_switch(index: int):
    """For the test of a worker that dies mid-shard: with ``OBSCURA_DATASET_KILL_SHARD=N:FILE``,
    the first attempt at shard N (FILE absent) makes FILE and ends its process after the
    shard's first view, as a crashed or pre-empted node would; later attempts run normally."""
    setting = os.environ.get("OBSCURA_DATASET_KILL_SHARD")
    if not setting:
        return None
    shard, marker = setting.split(":", 1)
    if int(shard) != index or os.path.exists(marker):
        return None

    def die_after_first_view(views: int) -> None:
        if views >= 1:
            open(marker, "w").close()
            os._exit(1)

    return die_after_first_view
