//! Issue 62, defect 5: small glTF files that would fill memory are refused before their data is
//! read (budget.rs, checks.rs), with the count and the limit.

use super::tests::{expect_error, push_floats, temp_dir, write_file};

/// A one-triangle mesh on `nodes` root nodes. `instances`: each node's
/// `EXT_mesh_gpu_instancing` count (a sparse TRANSLATION accessor over zeros); `indices`: the
/// count of a sparse index accessor over zeros (each index 0); `positions`: the POSITION
/// accessor's count, sparse over zeros where it is not 3.
fn hostile(nodes: usize, instances: Option<u64>, indices: Option<u64>, positions: u64) -> String {
    let mut b: Vec<u8> = Vec::new();
    push_floats(&mut b, &[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]); // positions @0, 36
    b.extend(0u32.to_le_bytes()); // a sparse index (element 0) @36, 4
    push_floats(&mut b, &[1.0, 0.0, 0.0]); // a sparse value (VEC3, or the index 0) @40, 12
    let sparse = r#""sparse": {"count": 1, "indices": {"bufferView": 1, "componentType": 5125},
        "values": {"bufferView": 2}}"#;
    let instancing = instances.map_or(String::new(), |_| {
        r#", "extensions": {"EXT_mesh_gpu_instancing": {"attributes": {"TRANSLATION": 1}}}"#
            .to_string()
    });
    let node = format!(r#"{{"mesh": 0{instancing}}}"#);
    let node_list: Vec<String> = (0..nodes).map(|_| node.clone()).collect();
    let roots: Vec<String> = (0..nodes).map(|n| n.to_string()).collect();
    let position_accessor = if positions == 3 {
        r#"{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}"#.to_string()
    } else {
        format!(
            r#"{{"componentType": 5126, "count": {positions}, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0], {sparse}}}"#
        )
    };
    let indices_ref = indices.map_or(String::new(), |_| r#", "indices": 2"#.to_string());
    format!(
        r#"{{"asset": {{"version": "2.0"}}, "scene": 0, "scenes": [{{"nodes": [{roots}]}}],
  "extensionsUsed": ["EXT_mesh_gpu_instancing"],
  "nodes": [{nodes}],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}{indices_ref}}}]}}],
  "buffers": [{{"byteLength": {len}, "uri": "data:application/octet-stream;base64,{data}"}}],
  "bufferViews": [
    {{"buffer": 0, "byteOffset": 0, "byteLength": 36}},
    {{"buffer": 0, "byteOffset": 36, "byteLength": 4}},
    {{"buffer": 0, "byteOffset": 40, "byteLength": 12}}
  ],
  "accessors": [
    {position_accessor},
    {{"componentType": 5126, "count": {instances}, "type": "VEC3", {sparse}}},
    {{"componentType": 5125, "count": {indices}, "type": "SCALAR", {sparse}}}
  ]}}"#,
        roots = roots.join(", "),
        nodes = node_list.join(", "),
        len = b.len(),
        data = base64::encode(&b),
        instances = instances.unwrap_or(1),
        indices = indices.unwrap_or(3),
    )
}

#[test]
fn a_mesh_instanced_2_to_the_26_times_is_refused_before_it_is_read() {
    let dir = temp_dir("budget-instances");
    // 4 nodes of 2^24 instances each: 2^26 placements of one triangle, in a 1.5 KB file.
    let text = hostile(4, Some(1 << 24), None, 3);
    assert!(text.len() < 2000, "{}", text.len());
    let path = write_file(&dir, "instances.gltf", &text);
    let e = expect_error(&path, "67,108,864 mesh instances");
    assert!(e.contains("limit of 50,000,000 triangles"), "{e}");
    assert!(e.contains("OBSCURA_MAX_TRIANGLES"), "{e}");
    assert!(e.contains("instances.gltf"), "{e}");
}

#[test]
fn nodes_multiplying_a_mesh_to_4e8_triangles_are_refused() {
    let dir = temp_dir("budget-triangles");
    // 3·2^22 indices (4,194,304 triangles) on 100 nodes: 419,430,400 triangles.
    let path = write_file(&dir, "nodes.gltf", &hostile(100, None, Some(3 << 22), 3));
    let e = expect_error(&path, "419,430,400 triangles");
    assert!(e.contains("100 mesh instances"), "{e}");
    assert!(e.contains("limit of 50,000,000 triangles"), "{e}");
}

#[test]
fn a_zero_filled_accessor_of_2_to_the_26_elements_is_refused_before_it_is_read() {
    let dir = temp_dir("budget-accessor");
    // Within the triangle budget (22 million triangles), but its 2^26 zeros are not in the file.
    let path = write_file(&dir, "zeros.gltf", &hostile(1, None, None, 1 << 26));
    let e = expect_error(&path, "count 67,108,864 without a bufferView");
    assert!(e.contains("limit of 16,777,216"), "{e}");
    // A file's own elements and small sparse accessors still load (sparse_accessors_are_applied).
    let path = write_file(&dir, "small.gltf", &hostile(2, Some(3), None, 3));
    let scene = super::tests::load_path(&path).unwrap();
    assert_eq!(scene.triangle_count(), 6);
}

#[test]
fn counts_are_grouped_by_thousands() {
    use crate::scene::thousands;
    assert_eq!(thousands(0), "0");
    assert_eq!(thousands(999), "999");
    assert_eq!(thousands(1000), "1,000");
    assert_eq!(thousands(268_435_456), "268,435,456");
}
