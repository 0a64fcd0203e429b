//! Wavefront OBJ loader, through `tobj` (triangulated, one index per vertex), read as +Y up.
//!
//! A missing or broken `.mtl` only costs the colours: every triangle then gets the default
//! material, with a warning. Texture `v` is flipped (v' = 1 − v) so that all uvs follow glTF,
//! where (0,0) is the top-left of the image. Every material is double-sided: OBJ has no culling
//! flag, and renderers of ground-truth AO count both sides of a triangle
//! ([`Sidedness`](super::Sidedness) overrides it).
//!
//! Face indices are pre-scanned before `tobj` sees them: `tobj` 4.0.5 computes
//! `count + index` and `2 * index` without overflow checks, which panics in debug builds for
//! an index 0 or a relative index reaching before the first vertex.

#[cfg(test)]
mod tests;
mod textures;

use std::cell::RefCell;
use std::io::Cursor;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::Path;

use glam::{Vec2, Vec3};

use super::files::{self, LoadOptions};
use super::{AlphaMode, Material, Scene, SceneError};

/// Largest absolute face index accepted (2^31): keeps `tobj`'s index arithmetic far from overflow.
const MAX_INDEX: i64 = 1 << 31;

/// Loads an `.obj` file. The result is not yet validated (the caller does that).
pub(crate) fn load(path: &Path, options: &LoadOptions) -> Result<Scene, SceneError> {
    let bytes = super::read_file(path)?;
    let triangles = triangle_count(&bytes);
    let limit = super::max_triangles();
    if triangles > limit {
        let what = format!("{} triangles", super::thousands(triangles));
        let limit = format!("{} triangles", super::thousands(limit));
        return Err(super::too_big(path, &what, &limit));
    }
    let error = |message: String| SceneError::Obj {
        path: path.to_path_buf(),
        message,
    };
    let refused = Refused {
        options,
        first: RefCell::new(None),
    };
    // Backstop only (see the module comment): a panic in `tobj` must still end as an error.
    match catch_unwind(AssertUnwindSafe(|| from_bytes(path, &bytes, &refused))) {
        // A refused file wins over what its absence then caused.
        _ if refused.first.borrow().is_some() => Err(refused.first.take().expect("checked")),
        Ok(result) => result.map_err(error),
        Err(_) => Err(error(
            "internal error in the OBJ reader (it panicked on this input)".into(),
        )),
    }
}

/// The files an OBJ refers to pass [`files::check`] before anything opens them; the first refused
/// is kept here, and [`load`] returns it whatever else went wrong.
struct Refused<'a> {
    options: &'a LoadOptions,
    first: RefCell<Option<SceneError>>,
}

impl Refused<'_> {
    /// Whether `file`, named `name` in scene `obj`, may be read; records the refusal otherwise.
    fn allows(&self, obj: &Path, name: &str, file: &Path) -> bool {
        match files::check(obj, name.trim(), file, self.options) {
            Ok(()) => true,
            Err(e) => {
                self.first.borrow_mut().get_or_insert(e);
                false
            }
        }
    }
}

fn from_bytes(path: &Path, bytes: &[u8], refused: &Refused) -> Result<Scene, String> {
    let text = std::str::from_utf8(bytes)
        .map_err(|e| format!("it is not text (invalid UTF-8 at byte {})", e.valid_up_to()))?;
    prescan_faces(text)?;
    let dir = files::folder(path).to_path_buf();
    // `..Default::default()` looks needless with tobj's default features, but another crate in
    // the build may enable `merging`/`reordering`, which add fields.
    #[allow(clippy::needless_update)]
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ignore_points: true,
        ignore_lines: true,
        ..Default::default()
    };
    let mtl_failed = RefCell::new(false);
    // Where names are looked up: the OBJ's folder, then each material library's.
    let dirs = RefCell::new(vec![dir.clone()]);
    let (models, materials) = tobj::load_obj_buf(&mut Cursor::new(text), &options, |mtl| {
        let name = mtl.to_str().unwrap_or_default();
        let mtl_path = textures::resolve(&dirs.borrow(), name);
        if !refused.allows(path, name, &mtl_path) {
            return Err(tobj::LoadError::OpenFileFailed);
        }
        if let Some(folder) = mtl_path
            .parent()
            .filter(|f| !dirs.borrow().iter().any(|d| d == f))
        {
            dirs.borrow_mut().push(folder.to_path_buf());
        }
        let result = tobj::load_mtl(&mtl_path);
        if let Err(e) = &result {
            log::warn!(
                "{}: material library '{}' cannot be loaded ({e}); its materials get the default \
                 grey",
                path.display(),
                mtl_path.display()
            );
            *mtl_failed.borrow_mut() = true;
        }
        result
    })
    .map_err(|e| e.to_string())?;
    let materials = materials.unwrap_or_else(|e| {
        if !*mtl_failed.borrow() {
            log::warn!(
                "{}: materials cannot be loaded ({e}); using defaults",
                path.display()
            );
        }
        Vec::new()
    });

    let mut scene = Scene {
        name: path.display().to_string(),
        ..Scene::default()
    };
    if refused.first.borrow().is_some() {
        return Err(String::new()); // load returns the refusal
    }
    let mut cache = textures::TextureCache::default();
    for m in &materials {
        let texture_file = |name: &Option<String>| -> Result<_, String> {
            let Some(name) = name else { return Ok(None) };
            let file = textures::resolve(&dirs.borrow(), name);
            if refused.allows(path, name, &file) {
                Ok(Some(file))
            } else {
                Err(String::new()) // load returns the refusal
            }
        };
        let color = texture_file(&m.diffuse_texture)?;
        let mask = texture_file(&m.dissolve_texture)?;
        let texture = cache.material_texture(path, color, mask, &mut scene);
        let masked = texture.is_some_and(|t| t.masked);
        // With a mask the mask alone cuts: exporters write any `d` beside it (some 0).
        let alpha = if masked {
            1.0
        } else {
            m.dissolve.map_or(1.0, |d| d as f32)
        };
        let [r, g, b] = m.diffuse.map_or([0.8, 0.8, 0.8], |c| c.map(|x| x as f32));
        scene.materials.push(Material {
            name: m.name.clone(),
            base_color: [r, g, b, alpha],
            base_color_texture: texture.map(|t| t.index),
            alpha_mode: if masked {
                // `map_d`: a cut-out (foliage, fences), tested at the usual half (glTF's
                // default cutoff).
                AlphaMode::Mask { cutoff: 0.5 }
            } else if alpha < 1.0 {
                // glTF's nearest equivalent of a dissolve below 1; AO treats it as opaque.
                AlphaMode::Blend
            } else {
                AlphaMode::Opaque
            },
            double_sided: true,
        });
    }
    let default_material = scene.materials.len() as u32;
    let mut used_default = false;
    // Positions are parsed as f64 (tobj's `use_f64`): a scene far from its origin for its size
    // is re-centred here, before its coordinates become f32 and lose its detail.
    let origin = super::far_origin(
        models
            .iter()
            .flat_map(|m| m.mesh.positions.chunks_exact(3))
            .map(|p| glam::DVec3::new(p[0], p[1], p[2])),
    );
    scene.origin = origin;

    for model in &models {
        let mesh = &model.mesh;
        let n = mesh.positions.len() / 3;
        let base = scene.positions.len();
        if base + n > u32::MAX as usize {
            return Err("more than 2^32 vertices".into());
        }
        if let Some(&bad) = mesh.indices.iter().find(|&&i| i as usize >= n) {
            return Err(format!(
                "object '{}' has face index {bad} but only {n} vertices",
                model.name
            ));
        }
        let material = match mesh.material_id {
            Some(id) if id < materials.len() => id as u32,
            _ => {
                used_default = true;
                default_material
            }
        };
        scene.positions.extend(
            mesh.positions
                .chunks_exact(3)
                .map(|p| (glam::DVec3::new(p[0], p[1], p[2]) - origin).as_vec3()),
        );
        // Vertex normals (`vn`), where every vertex of the object has one (as for uvs below).
        if mesh.normals.len() == 3 * n {
            scene.normals.extend(mesh.normals.chunks_exact(3).map(|v| {
                glam::DVec3::new(v[0], v[1], v[2])
                    .as_vec3()
                    .normalize_or_zero()
            }));
        } else {
            scene.normals.extend(std::iter::repeat_n(Vec3::ZERO, n));
        }
        // Vertices without `vt` leave `texcoords` shorter than `positions`; then no vertex can be
        // matched to its uv and all get zero.
        if mesh.texcoords.len() == 2 * n {
            scene.uvs.extend(
                mesh.texcoords
                    .chunks_exact(2)
                    .map(|t| Vec2::new(t[0] as f32, 1.0 - t[1] as f32)),
            );
        } else {
            if !mesh.texcoords.is_empty() {
                log::warn!(
                    "{}: object '{}' has texture coordinates on only some vertices; all set to 0",
                    path.display(),
                    model.name
                );
            }
            scene.uvs.extend(std::iter::repeat_n(Vec2::ZERO, n));
        }
        for c in mesh.indices.chunks_exact(3) {
            let base = base as u32;
            scene
                .triangles
                .push([c[0] + base, c[1] + base, c[2] + base]);
            scene.triangle_materials.push(material);
        }
    }
    if used_default {
        scene.materials.push(Material {
            double_sided: true,
            ..Material::default()
        });
    }
    Ok(scene)
}

/// The triangles the file's faces make once triangulated (a face of k corners makes k − 2),
/// counted over the raw bytes before anything is parsed, so that the triangle limit
/// ([`super::max_triangles`]) refuses a file before `tobj` fills memory with it. Each corner is at
/// least two bytes, so the count is bounded by the file's size.
fn triangle_count(bytes: &[u8]) -> u64 {
    bytes
        .split(|&b| b == b'\n')
        .filter_map(|line| line.trim_ascii_start().strip_prefix(b"f"))
        .filter(|rest| rest.first().is_some_and(u8::is_ascii_whitespace))
        .map(|rest| {
            let corners = rest
                .split(u8::is_ascii_whitespace)
                .filter(|w| !w.is_empty());
            (corners.count() as u64).saturating_sub(2)
        })
        .sum()
}

/// Rejects face indices that `tobj` cannot handle safely: 0 (OBJ counts from 1), absolute indices
/// beyond 2^31, and relative (negative) indices reaching before the first element.
fn prescan_faces(text: &str) -> Result<(), String> {
    // Elements defined so far: v, vt, vn (relative indices count back from these).
    let mut counts = [0i64; 3];
    for (line_no, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => counts[0] += 1,
            Some("vt") => counts[1] += 1,
            Some("vn") => counts[2] += 1,
            Some("f") | Some("l") => {
                for word in words {
                    check_face_vertex(word, &counts)
                        .map_err(|e| format!("line {}: {e}", line_no + 1))?;
                }
            }
            _ => {}
        }
    }
    Ok(())
}

/// One face vertex `v`, `v/vt`, `v//vn` or `v/vt/vn` against the element counts so far.
fn check_face_vertex(word: &str, counts: &[i64; 3]) -> Result<(), String> {
    for (kind, part) in word.split('/').take(3).enumerate() {
        let Ok(x) = part.parse::<i64>() else {
            continue; // empty (v//vn) or junk: tobj reports junk itself
        };
        if x == 0 || x > MAX_INDEX || x < -counts[kind] {
            let what = ["vertex", "texture coordinate", "normal"][kind];
            return Err(format!(
                "face {what} index {x} is out of range ({} defined before it; OBJ indices \
                 count from 1, negative ones back from the last)",
                counts[kind]
            ));
        }
    }
    Ok(())
}
