//! Errors of the scene module.
//!
//! Every message names the offending input (path, scene, camera, value) and says what to do,
//! because these strings reach the command line unchanged (docs/ARCHITECTURE.md, "Conventions").

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
    /// Not a built-in scene name, and no file of that name (most likely a mistyped built-in).
    #[error(
        "unknown scene '{spec}': use a built-in name ({}) or a path to a .gltf/.glb/.obj file",
        builtin_list()
    )]
    UnknownScene {
        /// What was asked for, as given.
        spec: String,
    },

    /// A path whose extension is not `.gltf`, `.glb` or `.obj` (or an existing file with none).
    #[error(
        "scene file '{}' has an unsupported type: load a .gltf, .glb or .obj file, or use a \
         built-in scene name ({})",
        path.display(),
        builtin_list()
    )]
    UnsupportedFormat {
        /// The scene file.
        path: PathBuf,
    },

    /// A `.gltf`, `.glb` or `.obj` path that does not exist.
    #[error(
        "scene file '{}' does not exist: check the path (or use a built-in scene name: {})",
        path.display(),
        builtin_list()
    )]
    NotFound {
        /// The scene file.
        path: PathBuf,
    },

    /// The scene file exists but cannot be read.
    #[error(
        "cannot read scene file '{}': {source}: check that it is a readable file",
        path.display()
    )]
    Io {
        /// The scene file.
        path: PathBuf,
        /// The operating system's error.
        #[source]
        source: std::io::Error,
    },

    /// A scene given as bytes (a browser's dropped file) refers to another file, and there is no
    /// folder to read it from.
    #[error(
        "'{}' refers to the file '{uri}', which cannot be read: it was loaded from memory, with no \
         folder around it. Use a .glb, or a .gltf whose buffers and images are embedded (data: URIs)",
        scene.display()
    )]
    NoFolder {
        /// The scene's name.
        scene: PathBuf,
        /// The reference, as the file writes it.
        uri: String,
    },

    /// The glTF loader rejected the file.
    #[error(
        "'{}' is not a usable glTF 2.0 file: {message}: re-export it (glTF 2.0, .gltf or .glb) or \
         check it with the Khronos glTF validator",
        path.display()
    )]
    Gltf {
        /// The scene file.
        path: PathBuf,
        /// What is wrong with it.
        message: String,
    },

    /// The OBJ loader rejected the file.
    #[error(
        "'{}' is not a usable OBJ file: {message}: re-export it as a Wavefront OBJ with 1-based \
         face indices",
        path.display()
    )]
    Obj {
        /// The scene file.
        path: PathBuf,
        /// What is wrong with it.
        message: String,
    },

    /// A scene file refers to a file (glTF buffer or image, OBJ material library or texture)
    /// outside its own folder, and [`crate::scene::LoadOptions::allow_outside_files`] is off.
    #[error(
        "scene '{}' refers to '{uri}' outside the scene's folder '{}'; copy the file into the \
         folder (or pass --allow-outside-files)",
        scene.display(),
        dir.display()
    )]
    OutsideFolder {
        /// The scene file.
        scene: PathBuf,
        /// The reference as the file writes it.
        uri: String,
        /// The scene file's folder.
        dir: PathBuf,
    },

    /// A scene file refers to something that is not a regular file (a folder, FIFO, device or
    /// socket): reading it could block forever or never end.
    #[error(
        "scene '{}' refers to '{uri}', which is not a regular file (a folder, FIFO, device or \
         socket); point it at a regular file in the scene's folder",
        scene.display()
    )]
    NotRegularFile {
        /// The scene file.
        scene: PathBuf,
        /// The reference as the file writes it.
        uri: String,
    },

    /// A scene file that would make more than obscura loads ([`crate::scene::MAX_TRIANGLES`]),
    /// refused before its data is read.
    #[error("scene '{}' {message}", path.display())]
    TooBig {
        /// The scene file.
        path: PathBuf,
        /// What it would hold, the limit it exceeds and the fix.
        message: String,
    },

    /// A loaded or hand-built scene that fails [`crate::scene::Scene::validate`].
    #[error("scene '{scene}' is invalid: {problem}")]
    Invalid {
        /// The scene's name.
        scene: String,
        /// The first rule it breaks (no triangles, an index out of range, …) and the fix.
        problem: String,
    },

    /// [`crate::scene::Scene::camera`] asked for a name the scene has no camera of.
    #[error(
        "scene '{scene}' has no camera named '{name}': available cameras: {}",
        camera_list(available)
    )]
    UnknownCamera {
        /// The scene's name.
        scene: String,
        /// The camera name asked for.
        name: String,
        /// The names of the scene's cameras (may be empty).
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
    /// The scene's name.
    pub name: String,
    /// The lower corner of the scene's bounds, world units.
    pub min: Vec3,
    /// The upper corner of the scene's bounds, world units.
    pub max: Vec3,
}

/// `(x, y, z)` in scientific notation, readable at any magnitude.
fn point(p: Vec3) -> String {
    format!("({:.3e}, {:.3e}, {:.3e})", p.x, p.y, p.z)
}

/// Why a camera is unusable.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CameraError {
    /// A position, the up vector or the field of view is NaN or infinite.
    #[error("camera {what} is not finite ({value}): give finite numbers")]
    NonFinite {
        /// Which: `eye`, `target`, `up` or `field of view`.
        what: &'static str,
        /// The offending value, formatted.
        value: String,
    },

    /// A vertical field of view not strictly between 0° and 180°.
    #[error(
        "camera field of view {fov_y_deg}° is outside (0°, 180°): use a vertical field of view \
         strictly between 0 and 180 degrees, e.g. 60"
    )]
    FieldOfView {
        /// The vertical field of view given, degrees.
        fov_y_deg: f32,
    },

    /// Eye and target (almost) the same point, relative to their magnitude: no view direction.
    #[error(
        "camera eye {eye} and target {target} are (almost) the same point: move the eye away from \
         the target"
    )]
    EyeAtTarget {
        /// The camera position, world space.
        eye: Vec3,
        /// The point looked at, world space.
        target: Vec3,
    },

    /// An up vector that is zero or within about 0.8° of the view direction.
    #[error(
        "camera up vector {up} is zero or parallel to the view direction {forward}: choose an up \
         vector that is not along the view direction"
    )]
    UpParallel {
        /// The up vector given.
        up: Vec3,
        /// The unit view direction, eye towards target.
        forward: Vec3,
    },
}
