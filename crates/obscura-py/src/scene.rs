//! `Scene` and `Camera`: a scene loaded as the CLI loads one (built-in name or glTF/GLB/OBJ
//! file, with its sides and normals options), and cameras named or built by the library's rule
//! (`CameraChoice`, the CLI's `--camera`/`--eye`/`--target`/`--up`/`--fov`).

use crate::errors::{from_camera_choice, from_scene, input};
use glam::{DVec3, Vec3};
use obscura::bvh::camera_choice::CameraChoice;
use obscura::scene::{self, LoadOptions, Normals, Sidedness};
use pyo3::prelude::*;
use std::sync::Arc;

/// A loaded scene: one triangle soup with materials and named cameras. Immutable; share it
/// between calls and threads freely.
#[pyclass(module = "obscura._native", frozen)]
pub struct Scene {
    pub scene: Arc<scene::Scene>,
}

/// `sides=`: which faces count, as the CLI's `--double-sided` / `--cull-back-faces`.
fn sidedness(sides: &str) -> PyResult<Sidedness> {
    match sides {
        "authored" => Ok(Sidedness::AsAuthored),
        "double" => Ok(Sidedness::DoubleSided),
        "cull-back" => Ok(Sidedness::CullBackFaces),
        other => Err(input(format!(
            "sides '{other}' is not one of 'authored' (what the file says: glTF's doubleSided, \
             OBJ double-sided), 'double' (every face both sides) or 'cull-back' (back faces \
             culled but where alpha-tested)"
        ))),
    }
}

#[pymethods]
impl Scene {
    /// Loads a scene: a built-in name (``builtin_scenes()``) or a ``.gltf``/``.glb``/``.obj``
    /// path. ``normals``: ``"shading"`` (the file's vertex normals, the default) or ``"face"``
    /// (the papers'); ``sides``: ``"authored"``, ``"double"`` or ``"cull-back"``;
    /// ``allow_outside_files``: let the file read what it refers to outside its folder. The
    /// GIL is released while it loads. Raises ``SceneError`` (``InputError`` for a bad option).
    #[new]
    #[pyo3(signature = (spec, *, normals="shading", sides="authored", allow_outside_files=false))]
    fn new(
        py: Python<'_>,
        spec: &Bound<'_, PyAny>,
        normals: &str,
        sides: &str,
        allow_outside_files: bool,
    ) -> PyResult<Self> {
        // A str or an os.PathLike, as the CLI's --scene text.
        let spec: String = match spec.extract::<String>() {
            Ok(s) => s,
            Err(_) => spec
                .extract::<std::path::PathBuf>()
                .map_err(|_| input("scene must be a built-in name or a file path"))?
                .to_string_lossy()
                .into_owned(),
        };
        let normals: Normals = normals.parse().map_err(input)?;
        let sides = sidedness(sides)?;
        let options = LoadOptions {
            allow_outside_files,
        };
        let loaded = py.detach(|| scene::load_with(&spec, &options));
        let mut scene = loaded.map_err(from_scene)?;
        scene.set_sidedness(sides);
        scene.set_normals(normals);
        Ok(Scene {
            scene: Arc::new(scene),
        })
    }

    /// The scene's name: a built-in's name or the file's path.
    #[getter]
    fn name(&self) -> String {
        self.scene.name.clone()
    }

    /// The names of the cameras the scene names, the default first.
    #[getter]
    fn cameras(&self) -> Vec<String> {
        self.scene.cameras.iter().map(|c| c.name.clone()).collect()
    }

    /// Number of triangles.
    #[getter]
    fn triangle_count(&self) -> usize {
        self.scene.triangle_count()
    }

    /// A camera of this scene, by the CLI's rule: ``name`` (one of ``cameras``), or ``eye`` and
    /// ``target`` (in the file's coordinates) with ``up``, or neither: the first named camera,
    /// else an automatic one for an image of ``aspect`` (width / height). ``fov`` (vertical,
    /// degrees, of the visible image) replaces the camera's. Raises ``CameraError``.
    #[pyo3(signature = (name=None, *, eye=None, target=None, up=None, fov=None, aspect=16.0/9.0))]
    #[allow(clippy::too_many_arguments)]
    fn camera(
        &self,
        py: Python<'_>,
        name: Option<String>,
        eye: Option<[f64; 3]>,
        target: Option<[f64; 3]>,
        up: Option<[f32; 3]>,
        fov: Option<f32>,
        aspect: f32,
    ) -> PyResult<Camera> {
        let eye_target = match (eye, target) {
            (Some(e), Some(t)) => Some((DVec3::from_array(e), DVec3::from_array(t))),
            (None, None) => None,
            _ => return Err(input("give eye and target together (or neither)")),
        };
        if name.is_some() && eye_target.is_some() {
            return Err(input("give a camera name or eye and target, not both"));
        }
        if up.is_some() && eye_target.is_none() {
            return Err(input("up goes with eye and target"));
        }
        if !(aspect.is_finite() && aspect > 0.0) {
            return Err(input(format!("aspect {aspect} must be a positive number")));
        }
        let choice = CameraChoice {
            name,
            eye_target,
            up: up.map(Vec3::from_array),
            fov_y_deg: fov,
        };
        let scene = self.scene.clone();
        let chosen = py
            .detach(|| choice.choose(&scene, aspect))
            .map_err(from_camera_choice)?;
        let note = chosen.note(&self.scene, false);
        Ok(Camera {
            camera: chosen.camera,
            name: chosen.name,
            note,
        })
    }

    fn __repr__(&self) -> String {
        format!(
            "Scene({:?}, triangles={}, cameras={:?})",
            self.scene.name,
            self.scene.triangle_count(),
            self.cameras()
        )
    }
}

/// A pinhole camera in world space (``eye``, ``target``, ``up``, vertical ``fov`` of the
/// visible image in degrees). Make one with ``Scene.camera(...)`` (named or built by the CLI's
/// rule) or ``Camera(eye, target, fov=60, up=None)`` (world coordinates of the loaded scene).
#[pyclass(module = "obscura._native", frozen)]
#[derive(Clone)]
pub struct Camera {
    pub camera: scene::Camera,
    /// The name reports use: the scene's camera name, `custom` or `auto`.
    #[pyo3(get)]
    pub name: String,
    /// For an automatic camera: where it was put, as `eye=…, target=…, fov=…`.
    #[pyo3(get)]
    pub note: Option<String>,
}

#[pymethods]
impl Camera {
    #[new]
    #[pyo3(signature = (eye, target, fov=60.0, up=None))]
    fn new(eye: [f32; 3], target: [f32; 3], fov: f32, up: Option<[f32; 3]>) -> PyResult<Self> {
        let mut camera = scene::Camera::new(Vec3::from_array(eye), Vec3::from_array(target), fov)
            .map_err(|e| crate::errors::CameraError::new_err(e.to_string()))?;
        if let Some(up) = up {
            camera.up = Vec3::from_array(up);
        }
        camera
            .validate()
            .map_err(|e| crate::errors::CameraError::new_err(e.to_string()))?;
        Ok(Camera {
            camera,
            name: "custom".into(),
            note: None,
        })
    }

    /// Camera position, world space.
    #[getter]
    fn eye(&self) -> [f32; 3] {
        self.camera.eye.to_array()
    }

    /// The point looked at, world space.
    #[getter]
    fn target(&self) -> [f32; 3] {
        self.camera.target.to_array()
    }

    /// The image's up direction, world space.
    #[getter]
    fn up(&self) -> [f32; 3] {
        self.camera.up.to_array()
    }

    /// Vertical field of view of the visible image, degrees.
    #[getter]
    fn fov(&self) -> f32 {
        self.camera.fov_y_deg
    }

    /// The view matrix (world to view), 4×4 float32, row-major as numpy reads it
    /// (``m @ [x, y, z, 1]``).
    fn view_matrix<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray2<f32>> {
        crate::arrays::matrix(py, self.camera.view_matrix())
    }

    fn __repr__(&self) -> String {
        format!(
            "Camera(eye={:?}, target={:?}, fov={}, up={:?}, name={:?})",
            self.camera.eye.to_array(),
            self.camera.target.to_array(),
            self.camera.fov_y_deg,
            self.camera.up.to_array(),
            self.name
        )
    }
}

/// The built-in procedural scenes' names.
#[pyfunction]
pub fn builtin_scenes() -> Vec<&'static str> {
    scene::builtin_names().to_vec()
}
