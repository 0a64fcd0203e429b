//! Scenes: one flat, world-space triangle soup with materials, textures and named cameras.
//!
//! Sources: the built-in procedural scenes ([`builtin`], README.md "Scenes"), glTF 2.0
//! (`.gltf`, `.glb`) and Wavefront OBJ files; [`load`] takes either a built-in name or a path.
//! Whatever the source, the result passes [`Scene::validate`], so downstream code (G-buffer,
//! BVH, AO kernels) may index every array without checks. No user input makes this module panic:
//! corrupt files, random bytes and out-of-range indices all end as a [`SceneError`] that names the
//! input and says what to do.

mod types;
pub use types::*;

mod camera;
mod error;
mod files;
#[cfg(test)]
mod files_tests;
mod gltf_loader;
mod obj_loader;
mod path;
mod procedural;
mod scene_impl;
mod texture;

#[cfg(test)]
mod real_scenes_tests;

use std::path::{Path, PathBuf};

pub use error::{CameraError, ExtentError, SceneError, MAX_EXTENT};
pub use files::LoadOptions;
pub use path::{CameraPath, Interpolation, Keyframe, PathError};
pub use procedural::{builtin, builtin_names, layers_with_shells};
pub use texture::MAX_TEXTURE_SIZE;

/// Loads a scene: a built-in name (see [`builtin_names`]) or a path to a `.gltf`, `.glb` or `.obj`
/// file (extension matched case-insensitively). The result is validated.
///
/// ```
/// use obscura::scene::{self, Normals, Sidedness};
///
/// let mut stairs = scene::load("stairs")?;
/// assert!(stairs.triangle_count() > 0);
/// // What a renderer of ground-truth AO (e.g. Blender Cycles) counts: both sides, shading normals.
/// stairs.set_sidedness(Sidedness::DoubleSided);
/// stairs.set_normals(Normals::Shading);
/// assert!(stairs.materials.iter().all(|m| m.double_sided));
///
/// let err = scene::load("stair").unwrap_err().to_string();
/// assert!(err.contains("stair"), "{err}"); // names the input and the built-in choices
/// # Ok::<(), obscura::scene::SceneError>(())
/// ```
pub fn load(spec: &str) -> Result<Scene, SceneError> {
    load_with(spec, &LoadOptions::default())
}

/// [`load`] with `options`: whether the files a scene file refers to (glTF buffers and images,
/// OBJ material libraries and textures) may lie outside its folder.
pub fn load_with(spec: &str, options: &LoadOptions) -> Result<Scene, SceneError> {
    if builtin_names().contains(&spec) {
        return builtin(spec);
    }
    let path = Path::new(spec);
    let ext = extension(path);
    let scene = match ext.as_deref() {
        Some("gltf") | Some("glb") => gltf_loader::load(path, options)?,
        Some("obj") => obj_loader::load(path, options)?,
        // No extension and no such file: most likely a mistyped built-in name.
        None if !path.exists() => {
            return Err(SceneError::UnknownScene {
                spec: spec.to_string(),
            })
        }
        _ => {
            return Err(SceneError::UnsupportedFormat {
                path: path.to_path_buf(),
            })
        }
    };
    finish(scene)
}

/// A glTF scene from its bytes (a `.glb`, or a `.gltf` whose buffers and images are embedded):
/// what a browser has of a dropped file. `name` (its file name) chooses the format by its
/// extension and names it in messages. Validated, as [`load`]'s.
pub fn load_bytes(name: &str, bytes: &[u8]) -> Result<Scene, SceneError> {
    let path = Path::new(name);
    let ext = extension(path);
    match ext.as_deref() {
        Some("gltf") | Some("glb") => finish(gltf_loader::load_bytes(path, bytes)?),
        _ => Err(SceneError::UnsupportedFormat {
            path: path.to_path_buf(),
        }),
    }
}

/// `path`'s extension in lower case: formats are matched case-insensitively.
fn extension(path: &Path) -> Option<String> {
    path.extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
}

/// What every loaded scene goes through: normals kept only where the file has some, validation,
/// and the note on re-centred coordinates.
fn finish(mut scene: Scene) -> Result<Scene, SceneError> {
    // Loaders give every vertex a normal slot (zero: none); a file without any keeps none.
    if scene.normals.iter().all(|n| *n == glam::Vec3::ZERO) {
        scene.normals.clear();
    }
    scene.validate()?;
    // Said only of a scene that loads: one that is refused gets its one error.
    if scene.origin != glam::DVec3::ZERO {
        log::warn!(
            "scene '{}' lies {:.3e} units from its file's origin, far for its size: its \
             coordinates are re-centred on ({}, {}, {}) to keep their precision; --eye and \
             --target are still read in the file's coordinates",
            scene.name,
            scene.origin.length(),
            scene.origin.x,
            scene.origin.y,
            scene.origin.z
        );
    }
    Ok(scene)
}

/// The most triangles a scene file may make, counted over every placement of its meshes (glTF
/// nodes and `EXT_mesh_gpu_instancing` instances; an OBJ's polygons as triangulated) before any of
/// its data is read, so that a small
/// file cannot fill memory (issue 62, defect 5). Real scenes pass easily: Sponza has about
/// 260,000 triangles, the largest production scenes tens of millions; a loaded triangle costs
/// about 100 bytes on the CPU (vertices, indices, BVH) before the GPU's copy, so the limit is
/// about 5 GB. Vertices are held to three per triangle of it, mesh instances to one. The
/// environment variable [`MAX_TRIANGLES_VAR`] replaces it ([`max_triangles`]).
pub const MAX_TRIANGLES: u64 = 50_000_000;

/// The environment variable that replaces [`MAX_TRIANGLES`] (a whole number of triangles).
pub const MAX_TRIANGLES_VAR: &str = "OBSCURA_MAX_TRIANGLES";

/// [`MAX_TRIANGLES`], or the value of [`MAX_TRIANGLES_VAR`] where that is set to a whole number
/// (a value that is not one is reported and ignored).
pub fn max_triangles() -> u64 {
    match std::env::var(MAX_TRIANGLES_VAR) {
        Ok(text) => match text.trim().replace(['_', ','], "").parse::<u64>() {
            Ok(n) => n,
            Err(_) => {
                log::warn!(
                    "{MAX_TRIANGLES_VAR}='{text}' is not a whole number of triangles; the limit \
                     stays {}",
                    thousands(MAX_TRIANGLES)
                );
                MAX_TRIANGLES
            }
        },
        Err(_) => MAX_TRIANGLES,
    }
}

/// The error of a scene file that would hold `what`, more than `limit` (say which limit, e.g.
/// "50,000,000 triangles"), with the fix: one message for every loader.
pub(crate) fn too_big(path: &Path, what: &str, limit: &str) -> SceneError {
    SceneError::TooBig {
        path: path.to_path_buf(),
        message: format!(
            "would hold {what}, more than the limit of {limit}: simplify the scene or split it, \
             or raise the limit with the environment variable {MAX_TRIANGLES_VAR}=<triangles> \
             where this machine has the memory (about 100 bytes a triangle)"
        ),
    }
}

/// `n` with its digits grouped by threes (`268,435,456`), for counts in messages.
pub(crate) fn thousands(n: u64) -> String {
    let digits = n.to_string();
    let mut out = String::with_capacity(digits.len() + digits.len() / 3);
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

/// How far from its file's origin, in its own sizes, a scene may lie before it is re-centred: 32-bit
/// floats hold about 7 digits, so at 10^4 sizes away a vertex keeps about 1/1700 of the scene's
/// size (issue 62, defect 4: a 5 m scene 10^7 m away kept nothing).
const FAR_IN_SIZES: f64 = 1e4;
/// How far from its file's origin, in world units, a scene may lie before it is re-centred,
/// whatever its size (at 10^5 a 32-bit float keeps 1/128 of a unit).
const FAR_ABSOLUTE: f64 = 1e5;

/// The origin a scene of vertices `points` (the file's coordinates, f64) is re-centred on: the
/// centre of their bounds where it lies farther from the file's origin than [`FAR_ABSOLUTE`] or
/// [`FAR_IN_SIZES`] times their extent; zero (no change) otherwise and for no or non-finite
/// points.
pub(crate) fn far_origin(points: impl Iterator<Item = glam::DVec3>) -> glam::DVec3 {
    use glam::DVec3;
    let mut finite = true;
    let (lo, hi) = points.fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), p| {
        finite &= p.is_finite();
        (lo.min(p), hi.max(p))
    });
    // Non-finite vertices, scenes of no extent and scenes too large for floats anywhere
    // (`Scene::check_extent`) are refused as they are.
    let too_large = (hi - lo).max_element() > f64::from(MAX_EXTENT);
    if !(finite && lo.is_finite() && hi.is_finite()) || hi == lo || too_large {
        return DVec3::ZERO;
    }
    let centre = (lo + hi) * 0.5;
    let distance = centre.abs().max_element();
    let extent = (hi - lo).max_element();
    if distance > FAR_ABSOLUTE || distance > FAR_IN_SIZES * extent {
        centre
    } else {
        DVec3::ZERO
    }
}

/// Reads a whole file, telling "does not exist" apart from other I/O failures. Only a regular file
/// (or a folder, which fails to read) is opened: a FIFO would block until a writer comes, a device
/// such as `/dev/zero` never ends.
pub(crate) fn read_file(path: &Path) -> Result<Vec<u8>, SceneError> {
    if let Ok(m) = std::fs::metadata(path) {
        if !m.is_file() && !m.is_dir() {
            return Err(SceneError::Io {
                path: path.to_path_buf(),
                source: std::io::Error::other("not a regular file (a FIFO, device or socket)"),
            });
        }
    }
    std::fs::read(path).map_err(|source| {
        if source.kind() == std::io::ErrorKind::NotFound {
            SceneError::NotFound {
                path: path.to_path_buf(),
            }
        } else {
            SceneError::Io {
                path: path.to_path_buf(),
                source,
            }
        }
    })
}

/// The folder of real test scenes (Sponza, Sibenik, Cornell box), if present: the first existing
/// folder of env `OBSCURA_SHARED_SCENES`, `shared/scenes` one to three levels above this crate's
/// manifest folder, and `/work/shared/scenes`. Tests that need it skip (with a printed reason) on
/// `None`.
pub fn shared_scenes_dir() -> Option<PathBuf> {
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR"));
    let env = std::env::var_os("OBSCURA_SHARED_SCENES").map(PathBuf::from);
    let relative = [
        "../shared/scenes",
        "../../shared/scenes",
        "../../../shared/scenes",
    ]
    .iter()
    .map(|rel| manifest.join(rel));
    env.into_iter()
        .chain(relative)
        .chain(std::iter::once(PathBuf::from("/work/shared/scenes")))
        .find(|dir| dir.is_dir())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn load_dispatches_and_reports_bad_specs() {
        let s = load("cornell").unwrap();
        assert_eq!(s.name, "cornell");
        assert_eq!(builtin_names().len(), 7);

        let err = load("stairz").unwrap_err().to_string();
        assert!(
            err.contains("'stairz'") && err.contains("stairs, colonnade"),
            "{err}"
        );
        assert!(err.contains(".gltf/.glb/.obj"), "{err}");
        let err = builtin("foo").unwrap_err().to_string();
        assert!(err.contains("'foo'"), "{err}");

        let err = load("/nonexistent/dir/scene.GLB").unwrap_err();
        assert!(matches!(err, SceneError::NotFound { .. }), "{err}");
        assert!(
            err.to_string().contains("/nonexistent/dir/scene.GLB"),
            "{err}"
        );
        let err = load("/nonexistent/model.obj").unwrap_err();
        assert!(err.to_string().contains("/nonexistent/model.obj"), "{err}");

        let err = load("/nonexistent/model.fbx").unwrap_err();
        assert!(matches!(err, SceneError::UnsupportedFormat { .. }), "{err}");
        assert!(err.to_string().contains("model.fbx"), "{err}");
    }

    #[test]
    fn directories_give_io_errors() {
        let dir =
            std::env::temp_dir().join(format!("obscura-scene-dir-{}.gltf", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let err = load(dir.to_str().unwrap()).unwrap_err();
        assert!(
            err.to_string().contains(&dir.display().to_string()),
            "{err}"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

/// Temporary folders for the loader tests, removed when dropped.
#[cfg(test)]
pub(crate) mod test_dir {
    use std::path::Path;

    /// A temporary folder removed when the test ends; derefs to its path.
    pub struct TestDir(tempfile::TempDir);

    impl TestDir {
        pub fn new(tag: &str) -> Self {
            Self(
                tempfile::Builder::new()
                    .prefix(&format!("obscura-{tag}-"))
                    .tempdir()
                    .expect("a temporary folder"),
            )
        }
    }

    impl std::ops::Deref for TestDir {
        type Target = Path;
        fn deref(&self) -> &Path {
            self.0.path()
        }
    }
}
