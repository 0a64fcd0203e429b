//! The package's exceptions and the one mapping from the library's errors to them: every
//! message is the library's own (what the CLI prints after "error: "), and a settings error
//! carries the settings field's path (`vao.radius`) as `.path`.

use obscura::bvh::camera_choice::CameraChoiceError;
use obscura::scene::SceneError as LibSceneError;
use obscura::settings::SettingsError as LibSettingsError;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;

pyo3::create_exception!(
    _native,
    ObscuraError,
    PyException,
    "Every error obscura raises: the library's message, which names the input and the fix."
);
pyo3::create_exception!(
    _native,
    SettingsError,
    ObscuraError,
    "Invalid settings (a value out of range, an unknown field, technique or preset, a bad \
     settings file). `.path` is the settings field's path (`\"vao.radius\"`), or None."
);
pyo3::create_exception!(
    _native,
    SceneError,
    ObscuraError,
    "A scene that cannot be loaded or used (missing or corrupt file, unknown built-in name)."
);
pyo3::create_exception!(
    _native,
    CameraError,
    SceneError,
    "A camera that cannot be used: an unknown camera name, a degenerate eye/target/up or field \
     of view."
);
pyo3::create_exception!(
    _native,
    GpuError,
    ObscuraError,
    "The GPU failed: no adapter, no device, a validation error or an adapter limit."
);
pyo3::create_exception!(
    _native,
    InputError,
    ObscuraError,
    "An unusable input: an array of the wrong shape, a bad projection matrix, an unreadable \
     image, a bad size or option."
);
pyo3::create_exception!(
    _native,
    DatasetError,
    ObscuraError,
    "A dataset spec that cannot be run (its message names the spec's field and the fix), or a \
     dataset run that failed."
);
pyo3::create_exception!(
    _native,
    OutputError,
    ObscuraError,
    "Writing an output file failed (nothing half-written is left)."
);

/// The settings field a settings error names, if any.
fn field_path(e: &LibSettingsError) -> Option<String> {
    match e {
        LibSettingsError::Invalid { field, .. } | LibSettingsError::Unsupported { field, .. } => {
            Some(field.to_string())
        }
        LibSettingsError::UnknownField { field, .. } => Some(field.clone()),
        LibSettingsError::UnknownTechnique(_) => Some("technique".into()),
        LibSettingsError::InFile { problem, .. } => field_path(problem),
        _ => None,
    }
}

/// `SettingsError(message)` with `.path` set.
pub fn settings_error(message: String, path: Option<String>) -> PyErr {
    let err = SettingsError::new_err(message);
    Python::attach(|py| {
        // Setting an attribute on a fresh exception instance cannot fail in practice; if it
        // did, the exception without `.path` is still the right one to raise.
        let _ = err.value(py).setattr("path", path);
    });
    err
}

/// A library settings error as `SettingsError`.
pub fn from_settings(e: LibSettingsError) -> PyErr {
    let path = field_path(&e);
    settings_error(e.to_string(), path)
}

/// A library error as the matching exception.
pub fn from_lib(e: obscura::Error) -> PyErr {
    match e {
        obscura::Error::Settings(s) => from_settings(s),
        obscura::Error::Gpu(g) => GpuError::new_err(g.to_string()),
        e @ obscura::Error::Input(_) => InputError::new_err(e.to_string()),
        e @ obscura::Error::Output { .. } => OutputError::new_err(e.to_string()),
    }
}

/// A scene error as `SceneError` (`CameraError` for an unknown camera).
pub fn from_scene(e: LibSceneError) -> PyErr {
    match e {
        e @ LibSceneError::UnknownCamera { .. } => CameraError::new_err(e.to_string()),
        e => SceneError::new_err(e.to_string()),
    }
}

/// A camera choice's error: the scene's coordinates (`SceneError`) or the camera's
/// (`CameraError`).
pub fn from_camera_choice(e: CameraChoiceError) -> PyErr {
    match e {
        CameraChoiceError::Scene(s) => from_scene(s),
        e @ CameraChoiceError::Extent(_) => SceneError::new_err(e.to_string()),
        e @ CameraChoiceError::Camera(_) => CameraError::new_err(e.to_string()),
    }
}

/// A bad argument of ours (not the library's): `InputError`.
pub fn input(message: impl Into<String>) -> PyErr {
    InputError::new_err(message.into())
}

/// Adds the exception types to the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("ObscuraError", py.get_type::<ObscuraError>())?;
    m.add("SettingsError", py.get_type::<SettingsError>())?;
    m.add("SceneError", py.get_type::<SceneError>())?;
    m.add("CameraError", py.get_type::<CameraError>())?;
    m.add("GpuError", py.get_type::<GpuError>())?;
    m.add("InputError", py.get_type::<InputError>())?;
    m.add("OutputError", py.get_type::<OutputError>())?;
    m.add("DatasetError", py.get_type::<DatasetError>())?;
    Ok(())
}
