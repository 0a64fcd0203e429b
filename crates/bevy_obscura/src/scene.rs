//! obscura's scenes (the built-in ones, or a file obscura loaded) as Bevy meshes: for tests that
//! compare the plugin with obscura's own renders, and for the example app.

use bevy::asset::RenderAssetUsages;
use bevy::mesh::{Mesh, PrimitiveTopology};

/// The scene's triangles as Bevy meshes with face normals (each triangle its own three vertices,
/// as obscura's default face normals see it): one mesh of the single-sided materials' triangles
/// (give it a material that culls back faces) and one of the double-sided ones, each with its
/// `double_sided` flag; a mesh with no triangles is left out.
pub fn scene_meshes(scene: &obscura::scene::Scene) -> Vec<(Mesh, bool)> {
    [false, true]
        .into_iter()
        .filter_map(|double_sided| {
            let mut positions = Vec::new();
            let mut normals = Vec::new();
            for (t, m) in scene.triangles.iter().zip(&scene.triangle_materials) {
                if scene.materials[*m as usize].double_sided != double_sided {
                    continue;
                }
                let [a, b, c] = t.map(|i| scene.positions[i as usize]);
                let n = (b - a).cross(c - a).normalize_or_zero();
                for p in [a, b, c] {
                    positions.push(p.to_array());
                    normals.push(n.to_array());
                }
            }
            (!positions.is_empty()).then(|| {
                let mut mesh = Mesh::new(
                    PrimitiveTopology::TriangleList,
                    RenderAssetUsages::default(),
                );
                mesh.insert_attribute(Mesh::ATTRIBUTE_POSITION, positions);
                mesh.insert_attribute(Mesh::ATTRIBUTE_NORMAL, normals);
                (mesh, double_sided)
            })
        })
        .collect()
}
