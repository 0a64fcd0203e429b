//! Skinned meshes in their rest pose (glTF 2.0 §3.7.3): a skinned mesh is placed by its joints,
//! not by its node (whose transform glTF says to ignore), each vertex by the weighted sum of its
//! joints' matrices, joint j's being its node's world transform times the skin's inverse bind
//! matrix j. The joints stand as the file's node transforms put them (no animation is played),
//! which is where a viewer that shows the file unanimated draws the mesh. Morph targets are not
//! applied (the base mesh).

use glam::{Mat3, Mat4, Vec3};
use gltf::accessor::{DataType, Dimensions};
use gltf::mesh::Semantic;
use gltf::{buffer, Primitive, Skin};

use super::checks;

/// Joint j's matrix: its node's world transform times inverse bind matrix j (identity where the
/// skin has none). `worlds`: every node's world transform (`None` for a node in a cycle).
pub(super) fn joint_matrices(
    skin: &Skin,
    worlds: &[Option<Mat4>],
    buffers: &[buffer::Data],
) -> Result<Vec<Mat4>, String> {
    let joints: Vec<usize> = skin.joints().map(|j| j.index()).collect();
    let inverse_bind: Vec<Mat4> = match skin.inverse_bind_matrices() {
        Some(acc) => {
            let what = "inverse bind matrix";
            checks::accessor(&acc, Dimensions::Mat4, &[DataType::F32], what)?;
            if acc.count() < joints.len() {
                return Err(format!(
                    "skin {} has {} joints but {} inverse bind matrices",
                    skin.index(),
                    joints.len(),
                    acc.count()
                ));
            }
            skin.reader(|b| buffers.get(b.index()).map(|d| d.0.as_slice()))
                .read_inverse_bind_matrices()
                .ok_or("its inverse bind matrices cannot be read")?
                .map(|m| Mat4::from_cols_array_2d(&m))
                .collect()
        }
        None => vec![Mat4::IDENTITY; joints.len()],
    };
    joints
        .iter()
        .zip(inverse_bind)
        .map(|(&node, inverse)| {
            let world = worlds.get(node).copied().flatten().ok_or_else(|| {
                format!(
                    "skin {} uses node {node} as a joint, which lies in a cycle of nodes",
                    skin.index()
                )
            })?;
            Ok(world * inverse)
        })
        .collect()
}

/// The skinning matrix of each of the primitive's `n` vertices, from its JOINTS_k and WEIGHTS_k
/// sets (every set it has: more than four influences a vertex take several); `None` where it
/// has none (then its node places it). Weights are divided by their sum, which glTF requires
/// to be 1 and exporters round.
pub(super) fn vertex_matrices(
    prim: &Primitive,
    buffers: &[buffer::Data],
    joints: &[Mat4],
    n: usize,
) -> Result<Option<Vec<Mat4>>, String> {
    let reader = prim.reader(|b| buffers.get(b.index()).map(|d| d.0.as_slice()));
    let mut sums = vec![Mat4::ZERO; n];
    let mut totals = vec![0.0f32; n];
    let mut set = 0;
    while let (Some(j_acc), Some(w_acc)) = (
        prim.get(&Semantic::Joints(set)),
        prim.get(&Semantic::Weights(set)),
    ) {
        checks::accessor(
            &j_acc,
            Dimensions::Vec4,
            &[DataType::U8, DataType::U16],
            "JOINTS",
        )?;
        let weight_types = [DataType::F32, DataType::U8, DataType::U16];
        checks::accessor(&w_acc, Dimensions::Vec4, &weight_types, "WEIGHTS")?;
        let indices: Vec<[u16; 4]> = reader
            .read_joints(set)
            .ok_or("its JOINTS data cannot be read")?
            .into_u16()
            .collect();
        let weights: Vec<[f32; 4]> = reader
            .read_weights(set)
            .ok_or("its WEIGHTS data cannot be read")?
            .into_f32()
            .collect();
        if indices.len() != n || weights.len() != n {
            return Err(format!(
                "it has {} JOINTS_{set} and {} WEIGHTS_{set} values for {n} positions",
                indices.len(),
                weights.len()
            ));
        }
        for (v, (index, weight)) in indices.iter().zip(&weights).enumerate() {
            for (&j, &w) in index.iter().zip(weight) {
                if w == 0.0 {
                    continue;
                }
                let joint = joints.get(j as usize).ok_or_else(|| {
                    format!(
                        "vertex {v} uses joint {j}, but the skin has {}",
                        joints.len()
                    )
                })?;
                sums[v] += *joint * w;
                totals[v] += w;
            }
        }
        set += 1;
    }
    if set == 0 {
        return Ok(None);
    }
    sums.iter()
        .zip(&totals)
        .enumerate()
        .map(|(v, (&sum, &total))| {
            if total > 0.0 && total.is_finite() {
                Ok(sum * (1.0 / total))
            } else {
                Err(format!("vertex {v} has no positive joint weight"))
            }
        })
        .collect::<Result<Vec<_>, _>>()
        .map(Some)
}

/// How a primitive's vertices reach world space: its node's transform (with its normal matrix
/// and handedness made once), or one skinning matrix per vertex.
pub(super) enum VertexPlacement {
    Node {
        matrix: Mat4,
        normal_matrix: Mat3,
        mirrors: bool,
    },
    Skinned(Vec<Mat4>),
}

/// Normals transform by the inverse transpose of the linear part.
fn normal_matrix(m: Mat4) -> Mat3 {
    Mat3::from_mat4(m).inverse().transpose()
}

impl VertexPlacement {
    pub fn node(matrix: Mat4) -> Self {
        VertexPlacement::Node {
            matrix,
            normal_matrix: normal_matrix(matrix),
            mirrors: matrix.determinant() < 0.0,
        }
    }

    pub fn position(&self, v: usize, p: Vec3) -> Vec3 {
        match self {
            VertexPlacement::Node { matrix, .. } => matrix.transform_point3(p),
            VertexPlacement::Skinned(ms) => ms[v].transform_point3(p),
        }
    }

    /// The normal at vertex `v` in world space; one that comes out non-finite or zero (a
    /// singular transform, a zero or NaN normal in the file) is "no normal" there.
    pub fn normal(&self, v: usize, n: Vec3) -> Vec3 {
        let to_world = match self {
            VertexPlacement::Node { normal_matrix, .. } => *normal_matrix,
            VertexPlacement::Skinned(ms) => normal_matrix(ms[v]),
        };
        (to_world * n).normalize_or_zero()
    }

    /// Whether the transform at vertex `v` mirrors (turning counter-clockwise into clockwise).
    pub fn mirrors(&self, v: usize) -> bool {
        match self {
            VertexPlacement::Node { mirrors, .. } => *mirrors,
            VertexPlacement::Skinned(ms) => ms[v].determinant() < 0.0,
        }
    }
}
