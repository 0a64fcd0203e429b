//! `Device`: one GPU device (the library's `Gpu`), chosen as the CLI chooses it (`--adapter`,
//! `--backend`, `OBSCURA_BACKEND`), and the module's lazily made default.

use crate::errors::GpuError;
use obscura::{Gpu, GpuOptions};
use pyo3::prelude::*;
use std::sync::OnceLock;

/// A GPU device. Every call that takes ``device=`` runs on it; without one, the module's default
/// device (the first adapter, as the CLI picks it; ``OBSCURA_BACKEND`` respected) is made on
/// first use and kept.
///
/// ``adapter``: use the first adapter whose name contains this (case-insensitive), as
/// ``obscura --adapter``. ``backend``: ``"vulkan"``, ``"metal"``, ``"dx12"`` or ``"gl"``, as
/// ``obscura --backend``. ``ordinal``: the N-th GPU (from 0) in PCI bus order, as ``nvidia-smi``
/// and NVML number them, so as Ray's GPU ids do (``obscura --gpu-index``). Raises ``GpuError`` when no
/// such adapter exists.
#[pyclass(module = "obscura._native", frozen)]
pub struct Device {
    pub gpu: Gpu,
}

#[pymethods]
impl Device {
    #[new]
    #[pyo3(signature = (adapter=None, backend=None, ordinal=None))]
    fn new(
        py: Python<'_>,
        adapter: Option<String>,
        backend: Option<String>,
        ordinal: Option<usize>,
    ) -> PyResult<Self> {
        let options = GpuOptions {
            adapter,
            backend,
            ordinal,
        };
        let gpu = py
            .detach(|| Gpu::new(&options))
            .map_err(|e| GpuError::new_err(e.to_string()))?;
        Ok(Device { gpu })
    }

    /// The adapter's name (``obscura info`` shows the same).
    #[getter]
    fn name(&self) -> String {
        self.gpu.summary.name.clone()
    }

    /// The backend: ``"Vulkan"``, ``"Metal"``, ``"Dx12"`` or ``"Gl"``.
    #[getter]
    fn backend(&self) -> String {
        self.gpu.summary.backend.clone()
    }

    /// Whether the adapter is a software (CPU) device such as Mesa's lavapipe: its timings are
    /// the CPU's, and ``reference(tracer="auto")`` traces on the CPU there.
    #[getter]
    fn is_software(&self) -> bool {
        obscura::reference::cpu_tracer_by_default(&self.gpu)
    }

    fn __repr__(&self) -> String {
        format!(
            "Device(name={:?}, backend={:?})",
            self.gpu.summary.name, self.gpu.summary.backend
        )
    }
}

/// The default device, made on first use (`Device()`'s choice).
fn default_device(py: Python<'_>) -> PyResult<Py<Device>> {
    static DEFAULT: OnceLock<Py<Device>> = OnceLock::new();
    if let Some(d) = DEFAULT.get() {
        return Ok(d.clone_ref(py));
    }
    let device = Py::new(py, Device::new(py, None, None, None)?)?;
    // Two threads may both make one; the first stored is kept by everyone.
    Ok(DEFAULT.get_or_init(|| device).clone_ref(py))
}

/// The GPU of `device`, or of the default device.
pub fn gpu_of(py: Python<'_>, device: Option<&Bound<'_, Device>>) -> PyResult<Gpu> {
    match device {
        Some(d) => Ok(d.get().gpu.clone()),
        None => Ok(default_device(py)?.get().gpu.clone()),
    }
}

/// The module's default device: made on first call (the first adapter, as the CLI picks it).
#[pyfunction]
pub fn default(py: Python<'_>) -> PyResult<Py<Device>> {
    default_device(py)
}
