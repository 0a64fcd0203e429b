//! `EXT_mesh_gpu_instancing` (gltfpack's `-mi`, glTF-Transform's `instance`, and engines'
//! exports of foliage and props): a node's mesh drawn once per instance, instance i placed by
//! the node's world transform times the translation, rotation and scale of its attributes
//! (the extension's README: T · R · S per instance, like a node's own TRS).

use glam::{Mat4, Quat, Vec3};
use gltf::{buffer, Document, Node};

use super::attributes::{self, Attribute};

pub(super) const NAME: &str = "EXT_mesh_gpu_instancing";

/// The local transforms of the node's instances, `None` where the node has no instancing.
pub(super) fn instances(
    doc: &Document,
    node: &Node,
    buffers: &[buffer::Data],
) -> Result<Option<Vec<Mat4>>, String> {
    let Some(ext) = node.extension_value(NAME).map(|v| &v["attributes"]) else {
        return Ok(None);
    };
    let attribute = |key: &str, what: Attribute| -> Result<Option<Vec<[f32; 4]>>, String> {
        let Some(index) = ext.get(key) else {
            return Ok(None);
        };
        let accessor = index
            .as_u64()
            .and_then(|i| doc.accessors().nth(i as usize))
            .ok_or_else(|| format!("its {key} names no accessor ({index})"))?;
        let values = if what == Attribute::InstanceRotation {
            attributes::read::<4>(&accessor, buffers, what, false)?
        } else {
            let xyz: Vec<[f32; 3]> = attributes::read(&accessor, buffers, what, false)?;
            xyz.into_iter().map(|[x, y, z]| [x, y, z, 0.0]).collect()
        };
        Ok(Some(values))
    };
    let translations = attribute("TRANSLATION", Attribute::InstanceTranslation)?;
    let rotations = attribute("ROTATION", Attribute::InstanceRotation)?;
    let scales = attribute("SCALE", Attribute::InstanceScale)?;
    let counts: Vec<usize> = [&translations, &rotations, &scales]
        .iter()
        .filter_map(|a| a.as_ref().map(Vec::len))
        .collect();
    let Some(&count) = counts.first() else {
        return Err(format!(
            "{NAME} has none of TRANSLATION, ROTATION and SCALE"
        ));
    };
    if counts.iter().any(|&c| c != count) {
        return Err(format!(
            "{NAME}'s attributes have different counts ({counts:?})"
        ));
    }
    let get = |a: &Option<Vec<[f32; 4]>>, i: usize, default: [f32; 4]| {
        a.as_ref().map_or(default, |v| v[i])
    };
    Ok(Some(
        (0..count)
            .map(|i| {
                let t = get(&translations, i, [0.0; 4]);
                let r = get(&rotations, i, [0.0, 0.0, 0.0, 1.0]);
                let s = get(&scales, i, [1.0; 4]);
                Mat4::from_scale_rotation_translation(
                    Vec3::new(s[0], s[1], s[2]),
                    Quat::from_array(r).normalize(),
                    Vec3::new(t[0], t[1], t[2]),
                )
            })
            .collect(),
    ))
}
