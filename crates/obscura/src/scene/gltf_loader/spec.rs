//! Rules of the glTF 2.0 specification that the `gltf` crate's validation does not check and
//! that the loader does not need: a file breaking them still loads, with a warning per problem
//! (issue 62: spec-invalid files rendered silently). What the loader cannot read is an error
//! elsewhere (checks.rs); these are what a file may get wrong and still mean something.

use gltf::mesh::{Mode, Semantic};
use gltf::Document;

/// Warnings printed per file at most; the rest are counted in one more line.
pub(super) const MAX_PRINTED: usize = 5;

/// Every problem found, one sentence each.
pub(super) fn problems(doc: &Document) -> Vec<String> {
    let mut out = Vec::new();
    for acc in doc.accessors() {
        let i = acc.index();
        let components = acc.dimensions().multiplicity();
        for (name, value) in [("min", acc.min()), ("max", acc.max())] {
            let Some(value) = value else { continue };
            let len = value.as_array().map(Vec::len);
            if len != Some(components) {
                out.push(format!(
                    "accessor {i}: {name} has {} values, but its type {:?} has {components} \
                     components (§5.1.{})",
                    len.map_or("no array of".into(), |n| n.to_string()),
                    acc.dimensions(),
                    if name == "min" { 8 } else { 7 }
                ));
            }
        }
        let component = acc.data_type().size();
        if let Some(view) = acc.view() {
            if !(acc.offset() + view.offset()).is_multiple_of(component) {
                out.push(format!(
                    "accessor {i}: its data starts at byte {} of its buffer, not a multiple of its \
                     {component}-byte component",
                    acc.offset() + view.offset()
                ));
            }
            if let Some(stride) = view.stride().filter(|s| !s.is_multiple_of(4)) {
                out.push(format!(
                    "buffer view {}: byteStride {stride} is not a multiple of 4",
                    view.index()
                ));
            }
        }
    }
    for (n, node) in doc.as_json().nodes.iter().enumerate() {
        let trs = node.translation.is_some() || node.rotation.is_some() || node.scale.is_some();
        if node.matrix.is_some() && trs {
            out.push(format!(
                "node {n} has both a matrix and translation, rotation or scale"
            ));
        }
        if let Some(q) = &node.rotation {
            let length = q.0.iter().map(|c| c * c).sum::<f32>().sqrt();
            if (length - 1.0).abs() > 1e-3 {
                out.push(format!(
                    "node {n}: rotation {:?} is not a unit quaternion (length {length})",
                    q.0
                ));
            }
        }
    }
    for mesh in doc.meshes() {
        for prim in mesh.primitives() {
            let corners = prim
                .indices()
                .or_else(|| prim.get(&Semantic::Positions))
                .map(|a| a.count());
            if let (Mode::Triangles, Some(corners)) = (prim.mode(), corners) {
                if !corners.is_multiple_of(3) {
                    out.push(format!(
                        "mesh {} primitive {}: {corners} triangle corners, not a multiple of 3 \
                        ",
                        mesh.index(),
                        prim.index()
                    ));
                }
            }
        }
    }
    out
}
