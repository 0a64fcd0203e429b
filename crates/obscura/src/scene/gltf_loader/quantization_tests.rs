//! `KHR_mesh_quantization`: integer vertex attributes load as the floats they stand for, and
//! files that break the extension's rules are refused by name.

use std::path::{Path, PathBuf};

use glam::{Vec2, Vec3};

use super::tests::{expect_error, load_path, temp_dir, write_file};

/// One attribute's data: its glTF component type, whether normalized, its element size in
/// bytes before padding, and the bytes of its three elements, each padded to 4 bytes (vertex
/// attributes are 4-byte aligned, glTF 2.0 §3.6.2.4).
struct Data {
    component_type: u32,
    normalized: bool,
    stride: usize,
    bytes: Vec<u8>,
}

fn elements<T: Copy, const N: usize>(
    component_type: u32,
    normalized: bool,
    values: [[T; N]; 3],
    to_bytes: impl Fn(T) -> Vec<u8>,
) -> Data {
    let size = values[0].iter().flat_map(|&c| to_bytes(c)).count();
    let stride = size.div_ceil(4) * 4;
    let mut bytes = Vec::new();
    for v in values {
        let mut element: Vec<u8> = v.iter().flat_map(|&c| to_bytes(c)).collect();
        element.resize(stride, 0);
        bytes.extend(element);
    }
    Data {
        component_type,
        normalized,
        stride,
        bytes,
    }
}

fn floats<const N: usize>(values: [[f32; N]; 3]) -> Data {
    elements(5126, false, values, |c| c.to_le_bytes().to_vec())
}

fn shorts<const N: usize>(normalized: bool, values: [[i16; N]; 3]) -> Data {
    elements(5122, normalized, values, |c| c.to_le_bytes().to_vec())
}

fn unsigned_shorts<const N: usize>(normalized: bool, values: [[u16; N]; 3]) -> Data {
    elements(5123, normalized, values, |c| c.to_le_bytes().to_vec())
}

fn bytes<const N: usize>(normalized: bool, values: [[i8; N]; 3]) -> Data {
    elements(5120, normalized, values, |c| c.to_le_bytes().to_vec())
}

fn unsigned_bytes<const N: usize>(normalized: bool, values: [[u8; N]; 3]) -> Data {
    elements(5121, normalized, values, |c| vec![c])
}

/// A one-triangle file with POSITION (its min/max `bounds`), NORMAL and TEXCOORD_0 as given,
/// the node placed by `node` (JSON fields), listing `extensions` as used and required.
fn triangle(
    dir: &Path,
    name: &str,
    [position, normal, uv]: [Data; 3],
    bounds: &str,
    node: &str,
    extensions: &str,
) -> PathBuf {
    let mut buffer = Vec::new();
    let mut views = Vec::new();
    let mut accessors = Vec::new();
    for (i, (data, kind)) in [(position, "VEC3"), (normal, "VEC3"), (uv, "VEC2")]
        .into_iter()
        .enumerate()
    {
        views.push(format!(
            r#"{{"buffer": 0, "byteOffset": {}, "byteLength": {}, "byteStride": {}}}"#,
            buffer.len(),
            data.bytes.len(),
            data.stride
        ));
        accessors.push(format!(
            r#"{{"bufferView": {i}, "componentType": {}, "normalized": {}, "count": 3, "type": "{kind}"{}}}"#,
            data.component_type,
            data.normalized,
            if i == 0 { bounds } else { "" }
        ));
        buffer.extend(data.bytes);
    }
    let json = format!(
        r#"{{"asset": {{"version": "2.0"}}, "scene": 0, "scenes": [{{"nodes": [0]}}],
  "extensionsUsed": [{extensions}], "extensionsRequired": [{extensions}],
  "nodes": [{{"mesh": 0 {node}}}],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}}}}]}}],
  "buffers": [{{"byteLength": {}, "uri": "data:application/octet-stream;base64,{}"}}],
  "bufferViews": [{}],
  "accessors": [{}]}}"#,
        buffer.len(),
        base64::encode(&buffer),
        views.join(", "),
        accessors.join(", ")
    );
    write_file(dir, name, &json)
}

const QUANTIZATION: &str = r#""KHR_mesh_quantization""#;

/// What every variant below stands for: the unit right triangle in z = 0 facing +z.
fn float_triangle(uv: [[f32; 2]; 3]) -> [Data; 3] {
    [
        floats([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]),
        floats([[0.0, 0.0, 1.0]; 3]),
        floats(uv),
    ]
}

const FLOAT_BOUNDS: &str = r#", "min": [0, 0, 0], "max": [1, 1, 0]"#;

#[test]
fn quantized_attributes_load_as_the_floats_they_stand_for() {
    let dir = temp_dir("quantized");
    let uv = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
    let expected = load_path(&triangle(
        &dir,
        "float.gltf",
        float_triangle(uv),
        FLOAT_BOUNDS,
        "",
        "",
    ))
    .unwrap();
    // Integer positions as stored, scaled by the node (gltfpack's way); normals as normalized
    // signed bytes and shorts; texture coordinates normalized or as stored.
    let variants = [
        (
            "shorts.gltf",
            [
                shorts(false, [[0, 0, 0], [1000, 0, 0], [0, 1000, 0]]),
                bytes(true, [[0, 0, 127]; 3]),
                unsigned_shorts(true, [[0, 0], [65535, 0], [0, 65535]]),
            ],
            r#", "min": [0, 0, 0], "max": [1000, 1000, 0]"#,
            r#", "scale": [0.001, 0.001, 0.001]"#,
        ),
        (
            "normalized.gltf",
            [
                unsigned_shorts(true, [[0, 0, 0], [65535, 0, 0], [0, 65535, 0]]),
                shorts(true, [[0, 0, 32767]; 3]),
                unsigned_bytes(true, [[0, 0], [255, 0], [0, 255]]),
            ],
            r#", "min": [0, 0, 0], "max": [1, 1, 0]"#,
            "",
        ),
        (
            "bytes.gltf",
            [
                // −128 normalizes to max(−128 / 127, −1) = −1: moved back by the translation.
                bytes(true, [[-128, 0, 0], [0, 0, 0], [-128, 127, 0]]),
                bytes(true, [[0, 0, 127]; 3]),
                shorts(true, [[0, 0], [32767, 0], [0, 32767]]),
            ],
            r#", "min": [-1, 0, 0], "max": [0, 1, 0]"#,
            r#", "translation": [1, 0, 0]"#,
        ),
    ];
    for (name, data, bounds, node) in variants {
        let path = triangle(&dir, name, data, bounds, node, QUANTIZATION);
        let scene = load_path(&path).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(scene.triangles, expected.triangles, "{name}");
        for (a, b) in scene.positions.iter().zip(&expected.positions) {
            assert!(a.abs_diff_eq(*b, 1e-6), "{name}: position {a} against {b}");
        }
        for n in &scene.normals {
            assert!(n.abs_diff_eq(Vec3::Z, 1e-6), "{name}: normal {n}");
        }
        for (a, b) in scene.uvs.iter().zip(&expected.uvs) {
            assert!(a.abs_diff_eq(*b, 1e-6), "{name}: uv {a} against {b}");
        }
    }
    // Texture coordinates not normalized are used as stored (with KHR_texture_transform a file
    // scales them; without, they repeat the texture).
    let path = triangle(
        &dir,
        "repeat.gltf",
        [
            floats([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]),
            floats([[0.0, 0.0, 1.0]; 3]),
            unsigned_bytes(false, [[0, 0], [3, 0], [0, 2]]),
        ],
        FLOAT_BOUNDS,
        "",
        QUANTIZATION,
    );
    let scene = load_path(&path).unwrap();
    assert_eq!(
        scene.uvs,
        [Vec2::ZERO, Vec2::new(3.0, 0.0), Vec2::new(0.0, 2.0)]
    );
}

#[test]
fn integer_attributes_outside_the_extension_s_rules_are_refused() {
    let dir = temp_dir("quantized-bad");
    let quantized = || {
        [
            shorts(false, [[0, 0, 0], [1000, 0, 0], [0, 1000, 0]]),
            bytes(true, [[0, 0, 127]; 3]),
            unsigned_shorts(true, [[0, 0], [65535, 0], [0, 65535]]),
        ]
    };
    let bounds = r#", "min": [0, 0, 0], "max": [1000, 1000, 0]"#;
    // The file does not declare the extension.
    let path = triangle(&dir, "undeclared.gltf", quantized(), bounds, "", "");
    expect_error(&path, "need KHR_mesh_quantization");
    // Integer normals must be normalized, and signed.
    for (name, normal, needle) in [
        (
            "normals.gltf",
            bytes(false, [[0, 0, 1]; 3]),
            "not normalized",
        ),
        (
            "unsigned-normals.gltf",
            unsigned_bytes(true, [[0, 0, 255]; 3]),
            "NORMAL accessor 1",
        ),
    ] {
        let [position, _, uv] = quantized();
        let data = [position, normal, uv];
        expect_error(
            &triangle(&dir, name, data, bounds, "", QUANTIZATION),
            needle,
        );
    }
    // Core glTF's texture coordinates: integers only as normalized unsigned ones.
    let [position, normal, _] = float_triangle([[0.0; 2]; 3]);
    let uv = shorts(true, [[0, 0], [1, 0], [0, 1]]);
    let path = triangle(
        &dir,
        "signed-uv.gltf",
        [position, normal, uv],
        FLOAT_BOUNDS,
        "",
        "",
    );
    expect_error(&path, "need KHR_mesh_quantization");
}

/// tests.rs's number fuzzing over a quantized file (no input may reach a panic in the `gltf`
/// crate). `cargo test -- --ignored fuzz_quantized_numbers`.
#[test]
#[ignore]
fn fuzz_quantized_numbers() {
    let dir = temp_dir("quantized-fuzz");
    let data = [
        shorts(false, [[0, 0, 0], [1000, 0, 0], [0, 1000, 0]]),
        bytes(true, [[0, 0, 127]; 3]),
        unsigned_bytes(false, [[0, 0], [3, 0], [0, 2]]),
    ];
    let bounds = r#", "min": [0, 0, 0], "max": [1000, 1000, 0]"#;
    let path = triangle(&dir, "fuzz-source.gltf", data, bounds, "", QUANTIZATION);
    super::tests::fuzz_numbers(&path, 20000);
}
