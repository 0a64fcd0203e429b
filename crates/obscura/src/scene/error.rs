//! Errors of the scene module.
//!
//! Every message names the offending input (path, scene, camera, value) and says what to do,
//! because these strings reach the command line unchanged (DESIGN.md "Errors and bad input").

use std::path::PathBuf;

use glam::Vec3;

/// The list of built-in names as shown in messages ("stairs, colonnade, …").
pub(crate) fn builtin_list() -> String {
    super::builtin_names().join(", ")
}

/// The available camera names as shown in messages.
fn camera_list(available: &[String]) -> String {
    if available.is_empty() {
        "none (leave the camera name out to frame the whole scene)".to_string()
    } else {
        available.join(", ")
    }
}

/// Why a scene could not be loaded, or why a loaded scene is unusable.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    #[error(
        "unknown scene '{spec}': use a built-in name ({}) or a path to a .gltf/.glb/.obj file",
        builtin_list()
    )]
    UnknownScene { spec: String },

    #[error(
        "scene file '{}' has an unsupported type: load a .gltf, .glb or .obj file, or use a \
         built-in scene name ({})",
        path.display(),
        builtin_list()
    )]
    UnsupportedFormat { path: PathBuf },

    #[error(
        "scene file '{}' does not exist: check the path (or use a built-in scene name: {})",
        path.display(),
        builtin_list()
    )]
    NotFound { path: PathBuf },

    #[error(
        "cannot read scene file '{}': {source}: check that it is a readable file",
        path.display()
    )]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },

    #[error(
        "'{}' is not a usable glTF 2.0 file: {message}: re-export it (glTF 2.0, .gltf or .glb) or \
         check it with the Khronos glTF validator",
        path.display()
    )]
    Gltf { path: PathBuf, message: String },

    #[error(
        "'{}' is not a usable OBJ file: {message}: re-export it as a Wavefront OBJ with 1-based \
         face indices",
        path.display()
    )]
    Obj { path: PathBuf, message: String },

    #[error("scene '{scene}' is invalid: {problem}")]
    Invalid { scene: String, problem: String },

    #[error(
        "scene '{scene}' has no camera named '{name}': available cameras: {}",
        camera_list(available)
    )]
    UnknownCamera {
        scene: String,
        name: String,
        available: Vec<String>,
    },
}

/// Coordinates beyond which squared distances overflow 32-bit floats in cameras, depth and AO
/// (f32::MAX ≈ 3.4e38 ≈ (1.8e19)²), with margin.
pub const MAX_EXTENT: f32 = 1e18;

/// A scene whose coordinates obscura cannot work with.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error(
    "scene '{name}' spans {} to {}: coordinates beyond ±{MAX_EXTENT:e} (or not finite) \
     overflow the 32-bit floats of cameras, depth and AO; scale the scene down (e.g. its root \
     node's scale) or fix the non-finite vertices",
    point(*min),
    point(*max)
)]
pub struct ExtentError {
    pub name: String,
    pub min: Vec3,
    pub max: Vec3,
}

/// `(x, y, z)` in scientific notation, readable at any magnitude.
fn point(p: Vec3) -> String {
    format!("({:.3e}, {:.3e}, {:.3e})", p.x, p.y, p.z)
}

/// Why a camera is unusable.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CameraError {
    #[error("camera {what} is not finite ({value}): give finite numbers")]
    NonFinite { what: &'static str, value: String },

    #[error(
        "camera field of view {fov_y_deg}° is outside (0°, 180°): use a vertical field of view \
         strictly between 0 and 180 degrees, e.g. 60"
    )]
    FieldOfView { fov_y_deg: f32 },

    #[error(
        "camera eye {eye} and target {target} are (almost) the same point: move the eye away from \
         the target"
    )]
    EyeAtTarget { eye: Vec3, target: Vec3 },

    #[error(
        "camera up vector {up} is zero or parallel to the view direction {forward}: choose an up \
         vector that is not along the view direction"
    )]
    UpParallel { up: Vec3, forward: Vec3 },
}
