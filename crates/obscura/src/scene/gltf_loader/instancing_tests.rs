//! `EXT_mesh_gpu_instancing`: a node's mesh once per instance (instancing.rs).

use std::path::{Path, PathBuf};

use glam::Vec3;

use super::tests::{expect_error, load_path, push_floats, temp_dir, write_file};

/// A triangle on a node moved by (0, 0, −1) with two instances: the first where the node puts
/// it, the second moved by (5, 0, 0), turned 90° about +Z and scaled by 2. `rotation_type`:
/// the rotations' component type (5126 float, 5122 normalized shorts); `scales`: how many
/// scales the SCALE accessor claims (2, or another count to test the error).
fn instanced_triangle(dir: &Path, name: &str, rotation_type: u32, scales: usize) -> PathBuf {
    let mut b: Vec<u8> = Vec::new();
    push_floats(&mut b, &[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]); // positions @0, 36
    push_floats(&mut b, &[0.0, 0.0, 0.0, 5.0, 0.0, 0.0]); // translations @36, 24
    push_floats(&mut b, &[1.0, 1.0, 1.0, 2.0, 2.0, 2.0]); // scales @60, 24
    let s = std::f32::consts::FRAC_1_SQRT_2;
    let rotation_bytes = if rotation_type == 5126 {
        push_floats(&mut b, &[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, s, s]); // rotations @84, 32
        32
    } else {
        let half = (s * 32767.0).round() as i16;
        b.extend(
            [0i16, 0, 0, 32767, 0, 0, half, half]
                .iter()
                .flat_map(|c| c.to_le_bytes()),
        );
        16
    };
    let normalized = rotation_type != 5126;
    let json = format!(
        r#"{{"asset": {{"version": "2.0"}}, "scene": 0, "scenes": [{{"nodes": [0]}}],
  "extensionsUsed": ["EXT_mesh_gpu_instancing"], "extensionsRequired": ["EXT_mesh_gpu_instancing"],
  "nodes": [{{"mesh": 0, "translation": [0, 0, -1], "extensions": {{"EXT_mesh_gpu_instancing":
    {{"attributes": {{"TRANSLATION": 1, "SCALE": 2, "ROTATION": 3}}}}}}}}],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}}}]}}],
  "buffers": [{{"byteLength": {len}, "uri": "data:application/octet-stream;base64,{data}"}}],
  "bufferViews": [
    {{"buffer": 0, "byteOffset": 0, "byteLength": 36}},
    {{"buffer": 0, "byteOffset": 36, "byteLength": 24}},
    {{"buffer": 0, "byteOffset": 60, "byteLength": 24}},
    {{"buffer": 0, "byteOffset": 84, "byteLength": {rotation_bytes}}}
  ],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}},
    {{"bufferView": 1, "componentType": 5126, "count": 2, "type": "VEC3"}},
    {{"bufferView": 2, "componentType": 5126, "count": {scales}, "type": "VEC3"}},
    {{"bufferView": 3, "componentType": {rotation_type}, "normalized": {normalized}, "count": 2, "type": "VEC4"}}
  ]}}"#,
        len = b.len(),
        data = base64::encode(&b),
    );
    write_file(dir, name, &json)
}

#[test]
fn instanced_meshes_are_placed_once_per_instance() {
    let dir = temp_dir("instancing");
    let expected = [
        Vec3::new(0.0, 0.0, -1.0),
        Vec3::new(1.0, 0.0, -1.0),
        Vec3::new(0.0, 1.0, -1.0),
        // 2 · (x, y) turned to (−y, x), then moved by (5, 0, 0).
        Vec3::new(5.0, 0.0, -1.0),
        Vec3::new(5.0, 2.0, -1.0),
        Vec3::new(3.0, 0.0, -1.0),
    ];
    for rotation_type in [5126, 5122] {
        let path = instanced_triangle(&dir, "instanced.gltf", rotation_type, 2);
        let scene = load_path(&path).unwrap();
        assert_eq!(scene.triangle_count(), 2);
        for (p, e) in scene.positions.iter().zip(expected) {
            assert!(p.abs_diff_eq(e, 1e-4), "{rotation_type}: {p} against {e}");
        }
    }
}

#[test]
fn instancing_attributes_of_different_counts_are_refused() {
    let dir = temp_dir("instancing-bad");
    let path = instanced_triangle(&dir, "counts.gltf", 5126, 1);
    expect_error(&path, "different counts");
}

/// tests.rs's number fuzzing over an instanced file (no input may reach a panic in the `gltf`
/// crate). `cargo test -- --ignored fuzz_instanced_numbers`.
#[test]
#[ignore]
fn fuzz_instanced_numbers() {
    let dir = temp_dir("instancing-fuzz");
    let path = instanced_triangle(&dir, "fuzz-source.gltf", 5122, 2);
    super::tests::fuzz_numbers(&path, 20000);
}
