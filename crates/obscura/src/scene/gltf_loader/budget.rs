//! What a glTF file would make, counted before any of its data is read (issue 62, defect 5): a
//! file of a kilobyte can place one mesh millions of times (`EXT_mesh_gpu_instancing`, many nodes
//! on one mesh) or give an accessor a count its buffer does not hold (a sparse accessor over
//! zeros), and the loader would fill memory before any other check could refuse it. The counts
//! come from the JSON alone: accessor counts, instance counts and the node tree, walked as
//! [`super::Loader::traverse`] walks it (each node once), without expanding anything.

use std::path::Path;

use gltf::mesh::{Mode, Semantic};
use gltf::{Document, Node};

use super::instancing;
use crate::scene::{max_triangles, thousands, too_big, SceneError};

/// What the scene would hold once loaded.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(super) struct Totals {
    /// Meshes placed (a node's mesh once per `EXT_mesh_gpu_instancing` instance).
    pub instances: u64,
    /// Triangles, over every placement.
    pub triangles: u64,
    /// Vertices, over every placement (the loader copies a primitive's vertices per placement).
    pub vertices: u64,
}

/// Counts the default scene's (else the first scene's, else the root nodes') placements,
/// triangles and vertices.
pub(super) fn count(doc: &Document, roots: Vec<Node>) -> Totals {
    let mut totals = Totals::default();
    let mut visited = vec![false; doc.nodes().len()];
    let mut stack = roots;
    while let Some(node) = stack.pop() {
        // As the loader: a node reached twice is skipped (the hierarchy must be a tree), so a
        // file whose nodes share children cannot multiply its meshes.
        if std::mem::replace(&mut visited[node.index()], true) {
            continue;
        }
        if let Some(mesh) = node.mesh() {
            // A skinned mesh is placed once, by its joints (the loader ignores its instances).
            let placements = match node.skin() {
                Some(_) => 1,
                None => instance_count(doc, &node).unwrap_or(1),
            };
            totals.instances = totals.instances.saturating_add(placements);
            for prim in mesh.primitives() {
                let (triangles, vertices) = primitive_size(&prim);
                totals.triangles = totals
                    .triangles
                    .saturating_add(placements.saturating_mul(triangles));
                totals.vertices = totals
                    .vertices
                    .saturating_add(placements.saturating_mul(vertices));
            }
        }
        stack.extend(node.children());
    }
    totals
}

/// The largest count among a node's `EXT_mesh_gpu_instancing` attributes (the loader refuses
/// attributes of different counts when it reads them); `None` without instancing.
fn instance_count(doc: &Document, node: &Node) -> Option<u64> {
    let attributes = node.extension_value(instancing::NAME)?.get("attributes")?;
    ["TRANSLATION", "ROTATION", "SCALE"]
        .iter()
        .filter_map(|key| attributes.get(key)?.as_u64())
        .filter_map(|i| doc.accessors().nth(usize::try_from(i).ok()?))
        .map(|a| a.count() as u64)
        .max()
}

/// Triangles and vertices one placement of a primitive adds (0 for points and lines, which the
/// loader skips).
fn primitive_size(prim: &gltf::Primitive) -> (u64, u64) {
    if !matches!(
        prim.mode(),
        Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
    ) {
        return (0, 0);
    }
    let vertices = prim
        .get(&Semantic::Positions)
        .map_or(0, |a| a.count() as u64);
    let corners = prim.indices().map_or(vertices, |a| a.count() as u64);
    let triangles = match prim.mode() {
        Mode::Triangles => corners / 3,
        _ => corners.saturating_sub(2),
    };
    (triangles, vertices)
}

/// `totals` within the triangle limit ([`max_triangles`]): as many triangles, three vertices
/// per triangle of it (an unindexed mesh has three a triangle), as many placements.
pub(super) fn check(path: &Path, totals: Totals) -> Result<(), SceneError> {
    let limit = max_triangles();
    let too_big = |what: String, limit_text: String| too_big(path, &what, &limit_text);
    let placed = format!(
        "{} mesh instances ({} triangles, {} vertices)",
        thousands(totals.instances),
        thousands(totals.triangles),
        thousands(totals.vertices)
    );
    if totals.triangles > limit {
        return Err(too_big(placed, format!("{} triangles", thousands(limit))));
    }
    let vertex_limit = limit.saturating_mul(3);
    if totals.vertices > vertex_limit {
        return Err(too_big(
            placed,
            format!(
                "{} vertices (three per triangle of the limit of {} triangles)",
                thousands(vertex_limit),
                thousands(limit)
            ),
        ));
    }
    if totals.instances > limit {
        return Err(too_big(
            placed,
            format!(
                "{} mesh instances (one per triangle of the triangle limit)",
                thousands(limit)
            ),
        ));
    }
    Ok(())
}
