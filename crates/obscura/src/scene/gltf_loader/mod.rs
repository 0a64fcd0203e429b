//! glTF 2.0 loader (`.gltf` with external or embedded buffers, `.glb`), through the `gltf` crate.
//!
//! The node hierarchy of the default scene (else the first scene, else all root nodes) is
//! flattened into one world-space triangle soup; perspective cameras on nodes become named
//! cameras. `gltf::import` is used in its three steps (parse, buffers, images) so that the checks
//! in [`checks`] can run between them: some malformed files otherwise panic inside the crate.

mod attributes;
mod budget;
#[cfg(test)]
mod budget_tests;
mod camera_path;
mod checks;
mod instancing;
#[cfg(test)]
mod instancing_tests;
mod materials;
#[cfg(test)]
mod quantization_tests;
mod skinning;
#[cfg(test)]
mod skinning_tests;
mod spec;
#[cfg(test)]
mod tests;

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::Path;

use glam::{Mat4, Vec2, Vec3};
use gltf::accessor::{DataType, Dimensions};
use gltf::mesh::{Mode, Semantic};
use gltf::{buffer, Document, Node};

use super::files::{self, LoadOptions};
use super::{Camera, Material, NamedCamera, Scene, SceneError};
use attributes::Attribute;
use materials::BaseColorUv;
use skinning::VertexPlacement;

/// Loads a `.gltf` or `.glb` file. The result is not yet validated (the caller does that). What
/// the file gets wrong against the glTF specification without keeping it from loading is logged
/// as warnings, [`spec::MAX_PRINTED`] at most.
pub(crate) fn load(path: &Path, options: &LoadOptions) -> Result<Scene, SceneError> {
    let (scene, problems) = load_with_problems(path, options)?;
    log_problems(path, &problems);
    Ok(scene)
}

/// [`load`] of a file's bytes already in memory (a browser's dropped file), named `name` in
/// messages: a `.glb` or a `.gltf` whose buffers and images are embedded (`data:` URIs), since
/// there is no folder to read others from.
pub(crate) fn load_bytes(name: &Path, bytes: &[u8]) -> Result<Scene, SceneError> {
    let (scene, problems) = parse(name, bytes, None)?;
    log_problems(name, &problems);
    Ok(scene)
}

fn log_problems(path: &Path, problems: &[String]) {
    for problem in problems.iter().take(spec::MAX_PRINTED) {
        log::warn!(
            "{}: not valid glTF 2.0 (loaded anyway): {problem}",
            path.display()
        );
    }
    if problems.len() > spec::MAX_PRINTED {
        log::warn!(
            "{}: {} more problems against the glTF 2.0 specification (the Khronos glTF \
             validator lists them all)",
            path.display(),
            problems.len() - spec::MAX_PRINTED
        );
    }
}

/// [`load`], returning the problems against the specification ([`spec::problems`]) instead of
/// logging them.
fn load_with_problems(
    path: &Path,
    options: &LoadOptions,
) -> Result<(Scene, Vec<String>), SceneError> {
    let bytes = super::read_file(path)?;
    parse(path, &bytes, Some(options))
}

/// The scene in `bytes`; `files` says how referenced files are read (`None`: none can be, the
/// bytes came from memory).
fn parse(
    path: &Path,
    bytes: &[u8],
    files: Option<&LoadOptions>,
) -> Result<(Scene, Vec<String>), SceneError> {
    let error = |message: String| SceneError::Gltf {
        path: path.to_path_buf(),
        message,
    };
    // Backstop only: the checks are meant to keep the `gltf` crate from panicking, but a panic in
    // a dependency on some input nobody thought of must still end as an error, not a crash.
    match catch_unwind(AssertUnwindSafe(|| from_bytes(path, bytes, files))) {
        Ok(Ok(scene)) => Ok(scene),
        Ok(Err(Failure::Message(message))) => Err(error(message)),
        Ok(Err(Failure::Scene(e))) => Err(e),
        Err(_) => Err(error(
            "internal error in the glTF reader (it panicked on this input)".into(),
        )),
    }
}

/// Why [`from_bytes`] failed: the file itself (a message for [`SceneError::Gltf`]), or a file
/// it refers to (an error of its own, with its own fix).
enum Failure {
    Message(String),
    Scene(SceneError),
}

impl From<String> for Failure {
    fn from(message: String) -> Self {
        Failure::Message(message)
    }
}

/// Every buffer and image file `doc` refers to passes [`files::check`], before the `gltf` crate
/// opens any of them.
fn check_referenced_files(
    path: &Path,
    doc: &Document,
    files: Option<&LoadOptions>,
) -> Result<(), SceneError> {
    let base = files::folder(path);
    let json = doc.as_json();
    let uris = json
        .buffers
        .iter()
        .filter_map(|b| b.uri.as_deref())
        .chain(json.images.iter().filter_map(|i| i.uri.as_deref()));
    for uri in uris {
        if let Some(file) = files::gltf_uri_file(base, uri) {
            match files {
                Some(options) => files::check(path, uri, &file, options)?,
                None => {
                    return Err(SceneError::NoFolder {
                        scene: path.to_path_buf(),
                        uri: uri.to_string(),
                    })
                }
            }
        }
    }
    Ok(())
}

fn from_bytes(
    path: &Path,
    bytes: &[u8],
    files: Option<&LoadOptions>,
) -> Result<(Scene, Vec<String>), Failure> {
    checks::glb_header(bytes)?;
    // Parse, check what gltf-json's validation itself would index blindly, then validate.
    let gltf = gltf::Gltf::from_slice_without_validation(bytes).map_err(|e| e.to_string())?;
    let mut json = gltf.document.into_json();
    checks::before_validation(&json)?;
    let quantized = take_extension(&mut json, "KHR_mesh_quantization");
    // Read by instancing.rs from each node's JSON.
    take_extension(&mut json, instancing::NAME);
    let doc = Document::from_json(json).map_err(|e| e.to_string())?;
    checks::document(&doc)?;
    let problems = spec::problems(&doc);
    // Before any data is read: what the file would make must fit (budget.rs).
    budget::check(path, budget::count(&doc, roots(&doc))).map_err(Failure::Scene)?;
    check_referenced_files(path, &doc, files).map_err(Failure::Scene)?;
    let base = files::folder(path);
    let buffers = gltf::import_buffers(&doc, Some(base), gltf.blob)
        .map_err(|e| format!("loading buffers: {e}"))?;
    checks::views(&doc, &buffers)?;
    let images = gltf::import_images(&doc, Some(base), &buffers)
        .map_err(|e| format!("loading images: {e}"))?;

    let mut scene = Scene {
        name: path.display().to_string(),
        ..Scene::default()
    };
    let base_color_uvs = materials::convert(&doc, &images, &mut scene)?;
    let mut loader = Loader {
        path,
        buffers: &buffers,
        doc: &doc,
        base_color_uvs,
        quantized,
        default_material: None,
        scene,
    };
    loader.traverse()?;
    let mut scene = loader.scene;
    scene.recentre();
    scene.cameras.retain(|c| match c.camera.validate() {
        Ok(()) => true,
        Err(e) => {
            log::warn!("{}: camera '{}' skipped: {e}", path.display(), c.name);
            false
        }
    });
    Ok((scene, problems))
}

struct Loader<'a> {
    path: &'a Path,
    buffers: &'a [buffer::Data],
    doc: &'a Document,
    /// Where each material's base-colour texture is read (set and texture transform).
    base_color_uvs: Vec<BaseColorUv>,
    /// The file uses `KHR_mesh_quantization` (integer vertex attributes; attributes.rs).
    quantized: bool,
    /// Index of the appended default material, once a primitive without material needs it.
    default_material: Option<u32>,
    scene: Scene,
}

impl Loader<'_> {
    /// Depth-first walk from the root nodes, accumulating world transforms.
    fn traverse(&mut self) -> Result<(), String> {
        let doc = self.doc;
        let roots = roots(doc);
        let worlds = node_worlds(doc);
        let mut visited = vec![false; doc.nodes().len()];
        let mut stack: Vec<(Node, Mat4)> = roots
            .into_iter()
            .rev()
            .map(|n| (n, Mat4::IDENTITY))
            .collect();
        while let Some((node, parent)) = stack.pop() {
            // glTF requires a tree; a node reached twice (shared child or cycle) is skipped so a
            // cyclic file cannot loop forever.
            if std::mem::replace(&mut visited[node.index()], true) {
                log::warn!(
                    "{}: node {} is reached twice (the node hierarchy must be a tree); skipped",
                    self.path.display(),
                    node.index()
                );
                continue;
            }
            let world = parent * Mat4::from_cols_array_2d(&node.transform().matrix());
            if let Some(mesh) = node.mesh() {
                let joints = match node.skin() {
                    Some(skin) => Some(skinning::joint_matrices(&skin, &worlds, self.buffers)?),
                    None => None,
                };
                // A skinned mesh stands where its joints put it, whatever its node's
                // transform or instances (which would all coincide).
                let instances = match joints {
                    Some(_) => None,
                    None => instancing::instances(doc, &node, self.buffers)
                        .map_err(|e| format!("node {}: {e}", node.index()))?,
                };
                let placements = instances.map_or(vec![world], |local| {
                    local.iter().map(|&l| world * l).collect()
                });
                for placement in placements {
                    for prim in mesh.primitives() {
                        let context = format!(
                            "mesh {} ('{}') primitive {}",
                            mesh.index(),
                            mesh.name().unwrap_or(""),
                            prim.index()
                        );
                        self.add_primitive(&prim, placement, joints.as_deref())
                            .map_err(|e| format!("{context}: {e}"))?;
                    }
                }
            }
            if node.camera().is_some() {
                self.add_camera(&node, parent, world);
            }
            let children: Vec<Node> = node.children().collect();
            stack.extend(children.into_iter().rev().map(|c| (c, world)));
        }
        Ok(())
    }

    /// Adds a primitive placed by its node's `world` transform, or by `joints` (the skin's joint
    /// matrices) where its node has a skin (skinning.rs).
    fn add_primitive(
        &mut self,
        prim: &gltf::Primitive,
        world: Mat4,
        joints: Option<&[Mat4]>,
    ) -> Result<(), String> {
        let mode = prim.mode();
        if !matches!(
            mode,
            Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
        ) {
            log::warn!(
                "{}: a primitive with mode {mode:?} is skipped (only triangles occlude)",
                self.path.display()
            );
            return Ok(());
        }
        let buffers = self.buffers;
        let reader = prim.reader(|b| buffers.get(b.index()).map(|d| d.0.as_slice()));

        let pos_acc = prim
            .get(&Semantic::Positions)
            .ok_or("it has no POSITION attribute")?;
        let positions: Vec<[f32; 3]> =
            attributes::read(&pos_acc, buffers, Attribute::Position, self.quantized)?;
        let n = positions.len();
        let skinned = match joints {
            Some(joints) => skinning::vertex_matrices(prim, buffers, joints, n)?,
            None => None,
        };
        let placement =
            skinned.map_or_else(|| VertexPlacement::node(world), VertexPlacement::Skinned);

        let material = match prim.material().index() {
            Some(i) if i < self.scene.materials.len() => i as u32,
            Some(i) => return Err(format!("it uses material {i}, which does not exist")),
            None => self.default_material(),
        };
        let uv_map = self
            .base_color_uvs
            .get(material as usize)
            .copied()
            .unwrap_or_default();
        let set = uv_map.set;
        let uvs: Vec<Vec2> = match prim.get(&Semantic::TexCoords(set)) {
            Some(acc) => {
                let uvs: Vec<[f32; 2]> =
                    attributes::read(&acc, buffers, Attribute::TexCoord, self.quantized)?;
                if uvs.len() != n {
                    return Err(format!(
                        "it has {} TEXCOORD_{set} values for {n} positions",
                        uvs.len()
                    ));
                }
                uvs.into_iter()
                    .map(|uv| uv_map.apply(Vec2::from(uv)))
                    .collect()
            }
            None => vec![Vec2::ZERO; n],
        };

        // Vertex normals (glTF: unit length, or absent: then flat shading, which is our default).
        let normals: Vec<Vec3> = match prim.get(&Semantic::Normals) {
            Some(acc) => {
                let normals: Vec<[f32; 3]> =
                    attributes::read(&acc, buffers, Attribute::Normal, self.quantized)?;
                if normals.len() != n {
                    return Err(format!(
                        "it has {} NORMAL values for {n} positions",
                        normals.len()
                    ));
                }
                normals
                    .into_iter()
                    .enumerate()
                    .map(|(v, n)| placement.normal(v, Vec3::from(n)))
                    .collect()
            }
            None => vec![Vec3::ZERO; n],
        };

        let indices: Vec<u32> = match prim.indices() {
            Some(acc) => {
                let types = [DataType::U8, DataType::U16, DataType::U32];
                checks::accessor(&acc, Dimensions::Scalar, &types, "index")?;
                reader
                    .read_indices()
                    .ok_or("its index data cannot be read")?
                    .into_u32()
                    .collect()
            }
            None => (0..n as u32).collect(),
        };
        if let Some(&bad) = indices.iter().find(|&&i| i as usize >= n) {
            return Err(format!(
                "index {bad} is out of range (the primitive has {n} vertices)"
            ));
        }

        let base = self.scene.positions.len();
        if base + n > u32::MAX as usize {
            return Err("the scene has more than 2^32 vertices".into());
        }
        let base = base as u32;
        for tri in assemble(mode, &indices) {
            // A mirroring transform turns counter-clockwise into clockwise: swap two corners back.
            let flip = placement.mirrors(tri[0] as usize);
            let [a, b, c] = tri.map(|i| i + base);
            self.scene
                .triangles
                .push(if flip { [a, c, b] } else { [a, b, c] });
            self.scene.triangle_materials.push(material);
        }
        self.scene.positions.extend(
            positions
                .iter()
                .enumerate()
                .map(|(v, &p)| placement.position(v, Vec3::from(p))),
        );
        self.scene.uvs.extend(uvs);
        self.scene.normals.extend(normals);
        Ok(())
    }

    fn default_material(&mut self) -> u32 {
        *self.default_material.get_or_insert_with(|| {
            self.scene.materials.push(Material::default());
            self.base_color_uvs.push(BaseColorUv::default());
            (self.scene.materials.len() - 1) as u32
        })
    }

    /// A perspective camera on a node: eye at the node's origin, looking down its -Z, up its +Y;
    /// and its camera path where an animation moves the node ([`camera_path`]).
    fn add_camera(&mut self, node: &Node, parent: Mat4, world: Mat4) {
        let index = self.scene.cameras.len();
        let name = node
            .name()
            .map_or_else(|| format!("camera{index}"), str::to_string);
        let camera_index = node.camera().map(|c| c.index());
        let json = camera_index.and_then(|i| self.doc.as_json().cameras.get(i));
        let Some(perspective) = json.and_then(|c| c.perspective.as_ref()) else {
            log::warn!(
                "{}: camera '{name}' is not perspective; skipped",
                self.path.display()
            );
            return;
        };
        let eye = world.transform_point3(Vec3::ZERO);
        let camera = Camera {
            eye,
            target: eye + world.transform_vector3(Vec3::NEG_Z).normalize_or_zero(),
            up: world.transform_vector3(Vec3::Y).normalize_or_zero(),
            fov_y_deg: perspective.yfov.to_degrees(),
        };
        let fov_y_deg = camera.fov_y_deg;
        // Validated once the scene is re-centred (`from_bytes`): far from the origin, f32 may
        // not tell its eye from its target before.
        self.scene.cameras.push(NamedCamera {
            name: name.clone(),
            camera,
        });
        match camera_path::camera_path(self.doc, self.buffers, node, parent, &name, fov_y_deg) {
            Some(Ok(path)) => self.scene.paths.push(path),
            Some(Err(e)) => log::warn!(
                "{}: the animation of camera '{name}' is not used as a camera path: {e}",
                self.path.display()
            ),
            None => {}
        }
    }
}

/// The nodes the scene starts from: the default scene's, else the first scene's, else every node
/// that is no node's child.
fn roots(doc: &Document) -> Vec<Node<'_>> {
    match doc.default_scene().or_else(|| doc.scenes().next()) {
        Some(s) => s.nodes().collect(),
        None => {
            let mut is_child = vec![false; doc.nodes().len()];
            for child in doc.nodes().flat_map(|n| n.children()) {
                is_child[child.index()] = true;
            }
            doc.nodes().filter(|n| !is_child[n.index()]).collect()
        }
    }
}

/// Every node's world transform, through its parents whether or not a scene reaches it (a
/// skin's joints are placed so); `None` for a node whose parent chain loops.
fn node_worlds(doc: &Document) -> Vec<Option<Mat4>> {
    let count = doc.nodes().len();
    let mut parent = vec![None; count];
    for node in doc.nodes() {
        for child in node.children() {
            parent[child.index()] = Some(node.index());
        }
    }
    let locals: Vec<Mat4> = doc
        .nodes()
        .map(|n| Mat4::from_cols_array_2d(&n.transform().matrix()))
        .collect();
    // Each node's world once: walk up to a node already known (or a root), then down again.
    let mut worlds: Vec<Option<Mat4>> = vec![None; count];
    let mut known = vec![false; count];
    for start in 0..count {
        let mut chain = Vec::new();
        let mut at = Some(start);
        while let Some(n) = at.filter(|&n| !known[n]) {
            if chain.len() > count {
                break; // the parent chain loops: its nodes stay None
            }
            chain.push(n);
            at = parent[n];
        }
        let looped = chain.len() > count;
        let mut world = at.map_or(Some(Mat4::IDENTITY), |n| worlds[n]);
        for &n in chain.iter().rev() {
            world = world.filter(|_| !looped).map(|w| w * locals[n]);
            worlds[n] = world;
            known[n] = true;
        }
    }
    worlds
}

/// Whether the file uses extension `name`, one that this loader implements and the `gltf`
/// crate's validation does not know (`KHR_mesh_quantization`: attributes.rs;
/// `EXT_mesh_gpu_instancing`: instancing.rs): removed from the file's extension lists before
/// that validation, which refuses any required extension it does not know.
fn take_extension(json: &mut gltf::json::Root, name: &str) -> bool {
    let listed = json.extensions_used.iter().any(|e| e == name)
        || json.extensions_required.iter().any(|e| e == name);
    json.extensions_used.retain(|e| e != name);
    json.extensions_required.retain(|e| e != name);
    listed
}

/// Triangle corner indices for a triangle list, strip or fan (glTF 2.0 §3.7.2.1), keeping the
/// counter-clockwise winding of the first triangle. Trailing indices that form no triangle are
/// ignored.
fn assemble(mode: Mode, idx: &[u32]) -> Vec<[u32; 3]> {
    match mode {
        Mode::TriangleStrip => (0..idx.len().saturating_sub(2))
            .map(|i| {
                if i % 2 == 0 {
                    [idx[i], idx[i + 1], idx[i + 2]]
                } else {
                    [idx[i + 1], idx[i], idx[i + 2]]
                }
            })
            .collect(),
        Mode::TriangleFan => (1..idx.len().saturating_sub(1))
            .map(|i| [idx[i], idx[i + 1], idx[0]])
            .collect(),
        _ => idx.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect(),
    }
}
