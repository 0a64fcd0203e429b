//! Skinned meshes stand where their joints put them in the rest pose (skinning.rs).

use std::path::{Path, PathBuf};

use glam::{Mat4, Vec3};

use super::tests::{expect_error, load_path, push_floats, temp_dir, write_file};

/// A skinned triangle: vertex 0 bound to joint 0, vertex 1 to joint 1, vertex 2 half to each.
/// The mesh node is moved by (100, 0, 0), which glTF says a skinned mesh ignores; the two joints
/// hang under an armature node moved by (0, 0, −2) and scaled by 2, at (0, 1, 0) and (0, 3, 0).
/// `inverse_bind`: the skin's inverse bind matrices (none: identity); `joint_2`: the second
/// vertex's joint index (1, or out of range to test the error).
fn skinned_triangle(
    dir: &Path,
    name: &str,
    inverse_bind: Option<[Mat4; 2]>,
    joint_1: u8,
) -> PathBuf {
    let mut b: Vec<u8> = Vec::new();
    push_floats(&mut b, &[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]); // positions @0, 36
    push_floats(&mut b, &[0.0, 0.0, 1.0].repeat(3)); // normals @36, 36
    b.extend([0, 0, 0, 0, joint_1, 0, 0, 0, 0, 1, 0, 0]); // joints @72, 12
    let weights = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.5, 0.5, 0.0, 0.0];
    push_floats(&mut b, &weights); // weights @84, 48
    let (skin_ibm, ibm_accessor, ibm_view) = match inverse_bind {
        Some(ms) => {
            for m in ms {
                push_floats(&mut b, &m.to_cols_array()); // @132, 128
            }
            (
                r#", "inverseBindMatrices": 4"#,
                r#", {"bufferView": 4, "componentType": 5126, "count": 2, "type": "MAT4"}"#,
                r#", {"buffer": 0, "byteOffset": 132, "byteLength": 128}"#,
            )
        }
        None => ("", "", ""),
    };
    let json = format!(
        r#"{{"asset": {{"version": "2.0"}}, "scene": 0, "scenes": [{{"nodes": [0, 1]}}],
  "nodes": [
    {{"name": "mesh", "mesh": 0, "skin": 0, "translation": [100, 0, 0]}},
    {{"name": "armature", "translation": [0, 0, -2], "scale": [2, 2, 2], "children": [2, 3]}},
    {{"name": "a", "translation": [0, 1, 0]}},
    {{"name": "b", "translation": [0, 3, 0]}}
  ],
  "skins": [{{"joints": [2, 3]{skin_ibm}}}],
  "meshes": [{{"primitives": [{{"attributes":
    {{"POSITION": 0, "NORMAL": 1, "JOINTS_0": 2, "WEIGHTS_0": 3}}}}]}}],
  "buffers": [{{"byteLength": {len}, "uri": "data:application/octet-stream;base64,{data}"}}],
  "bufferViews": [
    {{"buffer": 0, "byteOffset": 0, "byteLength": 36}},
    {{"buffer": 0, "byteOffset": 36, "byteLength": 36}},
    {{"buffer": 0, "byteOffset": 72, "byteLength": 12}},
    {{"buffer": 0, "byteOffset": 84, "byteLength": 48}}{ibm_view}
  ],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}},
    {{"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"}},
    {{"bufferView": 2, "componentType": 5121, "count": 3, "type": "VEC4"}},
    {{"bufferView": 3, "componentType": 5126, "count": 3, "type": "VEC4"}}{ibm_accessor}
  ]}}"#,
        len = b.len(),
        data = base64::encode(&b),
    );
    write_file(dir, name, &json)
}

fn assert_positions(path: &Path, expected: [Vec3; 3]) {
    let scene = load_path(path).unwrap();
    assert_eq!(scene.positions.len(), 3);
    for (p, e) in scene.positions.iter().zip(expected) {
        assert!(p.abs_diff_eq(e, 1e-5), "{p} against {e}");
    }
    for n in &scene.normals {
        assert!(n.abs_diff_eq(Vec3::Z, 1e-6), "normal {n}");
    }
}

#[test]
fn skinned_meshes_stand_where_their_joints_put_them() {
    let dir = temp_dir("skinned");
    // No inverse bind matrices: each joint's world transform, 2 (p + joint) + (0, 0, −2); the
    // third vertex half way between its two joints' images. The node's (100, 0, 0) is ignored.
    let path = skinned_triangle(&dir, "plain.gltf", None, 1);
    let expected = [
        Vec3::new(0.0, 2.0, -2.0),
        Vec3::new(2.0, 6.0, -2.0),
        Vec3::new(0.0, 6.0, -2.0),
    ];
    assert_positions(&path, expected);
    // Inverse bind matrices that undo the joints' rest transforms (an exporter's bind pose
    // equal to the rest pose): the mesh stands as stored.
    let world = |y: f32| {
        Mat4::from_translation(Vec3::new(0.0, 0.0, -2.0))
            * Mat4::from_scale(Vec3::splat(2.0))
            * Mat4::from_translation(Vec3::new(0.0, y, 0.0))
    };
    let ibm = [world(1.0).inverse(), world(3.0).inverse()];
    let path = skinned_triangle(&dir, "bind.gltf", Some(ibm), 1);
    assert_positions(&path, [Vec3::ZERO, Vec3::X, Vec3::Y]);
}

#[test]
fn skins_that_name_missing_joints_are_refused() {
    let dir = temp_dir("skinned-bad");
    let path = skinned_triangle(&dir, "joint.gltf", None, 5);
    expect_error(&path, "uses joint 5, but the skin has 2");
    let path = skinned_triangle(&dir, "skin.gltf", None, 1);
    let json = std::fs::read_to_string(&path).unwrap();
    std::fs::write(&path, json.replace(r#""skin": 0"#, r#""skin": 3"#)).unwrap();
    expect_error(&path, "uses skin 3");
    let json = std::fs::read_to_string(&path).unwrap();
    let json = json.replace(r#""skin": 3"#, r#""skin": 0"#);
    std::fs::write(
        &path,
        json.replace(r#""joints": [2, 3]"#, r#""joints": [2, 9]"#),
    )
    .unwrap();
    expect_error(&path, "uses node 9 as a joint");
}

/// tests.rs's number fuzzing over a skinned file (no input may reach a panic in the `gltf`
/// crate). `cargo test -- --ignored fuzz_skinned_numbers`.
#[test]
#[ignore]
fn fuzz_skinned_numbers() {
    let dir = temp_dir("skinned-fuzz");
    let ibm = [Mat4::IDENTITY, Mat4::from_scale(Vec3::splat(0.5))];
    let path = skinned_triangle(&dir, "fuzz-source.gltf", Some(ibm), 1);
    super::tests::fuzz_numbers(&path, 20000);
}
