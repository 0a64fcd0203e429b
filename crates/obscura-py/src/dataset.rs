//! Datasets from Python (docs/DATASETS.md): the library's dataset runner, whole
//! (`dataset_run_local`, the CLI's `obscura dataset`) or in the steps a distributed executor
//! takes (`dataset_init` once, `dataset_run_shard` per shard in any process, `dataset_finish`
//! once). The pure-Python `obscura.dataset` drives these, locally or as Ray tasks: the bytes a
//! shard writes depend only on the spec and the shard's number, never on who runs it.

use crate::device::{gpu_of, Device};
use crate::errors::{DatasetError, GpuError};
use obscura::dataset::{self, Spec};
use obscura::GpuOptions;
use pyo3::prelude::*;
use std::path::PathBuf;

/// The spec file, read and checked (every problem one `DatasetError` naming its field).
fn spec(path: &PathBuf) -> PyResult<Spec> {
    Spec::from_path(path).map_err(to_py)
}

fn to_py(e: dataset::DatasetError) -> PyErr {
    match e {
        dataset::DatasetError::Obscura(e) => crate::errors::from_lib(e),
        e => DatasetError::new_err(e.to_string()),
    }
}

/// A Python callable told each finished view's count (`progress(views)`); errors it raises
/// are not the shard's (printed, then ignored).
fn reporter(progress: Option<Py<PyAny>>) -> impl Fn(u64) + Sync {
    move |views| {
        if let Some(f) = &progress {
            Python::attach(|py| {
                if let Err(e) = f.call1(py, (views,)) {
                    e.print(py);
                }
            });
        }
    }
}

/// Checks the spec, its scenes and cameras, and prepares ``out`` (its ``dataset.json``);
/// returns the number of shards. Raises ``DatasetError`` before any rendering.
#[pyfunction]
pub fn dataset_init(py: Python<'_>, spec_path: PathBuf, out: PathBuf) -> PyResult<usize> {
    let spec = spec(&spec_path)?;
    py.detach(|| dataset::init_out_dir(&spec, &out))
        .map(|plan| plan.shards.len())
        .map_err(to_py)
}

/// Runs shard ``index`` into ``out`` (skipped where it is finished and verifies, redone over
/// any leftovers); returns its report as JSON text. ``progress(views)`` is called after each
/// view (the test of a task killed mid-shard uses it).
#[pyfunction]
#[pyo3(signature = (spec_path, index, out, *, device=None, progress=None))]
pub fn dataset_run_shard(
    py: Python<'_>,
    spec_path: PathBuf,
    index: usize,
    out: PathBuf,
    device: Option<&Bound<'_, Device>>,
    progress: Option<Py<PyAny>>,
) -> PyResult<String> {
    let spec = spec(&spec_path)?;
    let gpu = gpu_of(py, device)?;
    let report = reporter(progress);
    let done = py
        .detach(|| dataset::run_shard(&gpu, &spec, index, &out, &report))
        .map_err(to_py)?;
    serde_json::to_string(&done).map_err(|e| DatasetError::new_err(e.to_string()))
}

/// Verifies every shard, writes the merged ``manifest.jsonl`` and ``summary.json``; returns
/// the summary as JSON text. ``reports``: the shards' JSON reports.
#[pyfunction]
pub fn dataset_finish(
    py: Python<'_>,
    spec_path: PathBuf,
    out: PathBuf,
    reports: Vec<String>,
    seconds: f64,
    devices: Vec<String>,
) -> PyResult<String> {
    let spec = spec(&spec_path)?;
    let reports = reports
        .iter()
        .map(|r| serde_json::from_str(r))
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| DatasetError::new_err(format!("a shard's report is not one: {e}")))?;
    let summary = py
        .detach(|| dataset::finish(&spec, &out, reports, seconds, devices))
        .map_err(to_py)?;
    serde_json::to_string(&summary).map_err(|e| DatasetError::new_err(e.to_string()))
}

/// The whole dataset on this machine's GPUs (at most ``devices`` of them), as
/// ``obscura dataset SPEC --out OUT``; returns the summary as JSON text.
#[pyfunction]
#[pyo3(signature = (spec_path, out, *, devices=None, adapter=None, backend=None, progress=None))]
pub fn dataset_run_local(
    py: Python<'_>,
    spec_path: PathBuf,
    out: PathBuf,
    devices: Option<usize>,
    adapter: Option<String>,
    backend: Option<String>,
    progress: Option<Py<PyAny>>,
) -> PyResult<String> {
    let spec = spec(&spec_path)?;
    let options = GpuOptions {
        adapter,
        backend,
        ..Default::default()
    };
    let report = reporter(progress);
    let summary = py
        .detach(|| dataset::run_local(&spec, &out, &options, devices, &report))
        .map_err(|e| match e {
            dataset::DatasetError::Obscura(obscura::Error::Gpu(g)) => {
                GpuError::new_err(g.to_string())
            }
            e => to_py(e),
        })?;
    serde_json::to_string(&summary).map_err(|e| DatasetError::new_err(e.to_string()))
}
