//! The Python package's native module, `obscura._native` (docs/PYTHON.md): scenes, cameras,
//! `render`, `reference`, `compare`, the engine path and the devices, each a thin layer over the
//! library calls the CLI makes, so that the same inputs give the same bits. The pure-Python
//! package around it (`python/obscura/`) re-exports these and holds the stubs.
//!
//! Every function checks its arguments and settings before any GPU work and releases the GIL
//! (`Python::detach`) around loading, tracing and rendering. Library errors become the
//! exceptions of `errors` with the library's message; a panic would become pyo3's
//! `PanicException`, never an abort across the boundary.

mod arrays;
mod dataset;
mod device;
mod errors;
mod reference;
mod render;
mod scene;
mod settings;
mod view;

use pyo3::prelude::*;

/// The technique table's row names, in the table's order.
#[pyfunction]
fn techniques() -> Vec<&'static str> {
    obscura::Technique::all().map(|t| t.name()).collect()
}

/// The full settings a call would run with, as ``settings_json`` text (every field, α written
/// out): ``technique``, ``settings`` (dict or file), ``preset`` and ``units`` as for ``render``.
/// Raises ``SettingsError`` exactly where ``render`` would.
#[pyfunction]
#[pyo3(signature = (technique=None, settings=None, *, preset=None, units=None))]
fn settings_json(
    technique: Option<&str>,
    settings: Option<&Bound<'_, PyAny>>,
    preset: Option<&str>,
    units: Option<&str>,
) -> PyResult<String> {
    let given = settings::Given::from_py(settings)?;
    let s = settings::resolve(technique, given.as_ref(), preset, units)?;
    Ok(s.resolved().to_json_string())
}

#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    // Quiet Mesa's headless Vulkan warnings, as the CLI does first thing.
    obscura::gpu::quiet_headless_vulkan();
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    errors::register(m)?;
    m.add_class::<device::Device>()?;
    m.add_class::<scene::Scene>()?;
    m.add_class::<scene::Camera>()?;
    m.add_function(wrap_pyfunction!(device::default, m)?)?;
    m.add_function(wrap_pyfunction!(scene::builtin_scenes, m)?)?;
    m.add_function(wrap_pyfunction!(techniques, m)?)?;
    m.add_function(wrap_pyfunction!(settings_json, m)?)?;
    m.add_function(wrap_pyfunction!(render::render, m)?)?;
    m.add_function(wrap_pyfunction!(render::gbuffer, m)?)?;
    m.add_function(wrap_pyfunction!(render::engine_ao, m)?)?;
    m.add_function(wrap_pyfunction!(render::read_ao, m)?)?;
    m.add_function(wrap_pyfunction!(reference::reference, m)?)?;
    m.add_function(wrap_pyfunction!(reference::compare_json, m)?)?;
    m.add_function(wrap_pyfunction!(dataset::dataset_init, m)?)?;
    m.add_function(wrap_pyfunction!(dataset::dataset_run_shard, m)?)?;
    m.add_function(wrap_pyfunction!(dataset::dataset_finish, m)?)?;
    m.add_function(wrap_pyfunction!(dataset::dataset_run_local, m)?)?;
    Ok(())
}
