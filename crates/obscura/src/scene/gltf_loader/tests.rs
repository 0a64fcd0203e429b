//! glTF loader tests on small files written from code (`.gltf` embedded and external, `.glb`).

use std::path::{Path, PathBuf};

use glam::{Vec2, Vec3};

use super::super::{load, AlphaMode, Scene, SceneError};

/// A fresh, empty folder for one test.
pub(super) fn temp_dir(tag: &str) -> crate::scene::test_dir::TestDir {
    crate::scene::test_dir::TestDir::new(&format!("gltf-{tag}"))
}

/// Appends `values` to `bytes` as little-endian f32s (a glTF buffer's layout).
pub(super) fn push_floats(bytes: &mut Vec<u8>, values: &[f32]) {
    bytes.extend(values.iter().flat_map(|f| f.to_le_bytes()));
}

/// Writes `text` to `dir/name` and returns the path.
pub(super) fn write_file(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// 2x2 RGBA texture: alpha 255, 0 (top row), 128, 200 (bottom row).
fn png_2x2() -> Vec<u8> {
    let px = [
        255, 0, 0, 255, 0, 255, 0, 0, 0, 0, 255, 128, 255, 255, 255, 200,
    ];
    let img = image::RgbaImage::from_raw(2, 2, px.to_vec()).unwrap();
    let mut out = std::io::Cursor::new(Vec::new());
    img.write_to(&mut out, image::ImageFormat::Png).unwrap();
    out.into_inner()
}

/// Test asset: an indexed, textured quad and a non-indexed triangle (mesh 0), a triangle without
/// material (mesh 1); mesh 0 is placed twice, once mirrored; one perspective camera.
struct Asset {
    quad: [[f32; 3]; 4],
    indices: [u16; 6],
    /// Replacements applied to the JSON text (to break it in specific ways).
    patches: Vec<(&'static str, &'static str)>,
}

const TRI: [[f32; 3]; 3] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];

impl Default for Asset {
    fn default() -> Self {
        Asset {
            quad: [
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [1.0, 1.0, 0.0],
                [0.0, 1.0, 0.0],
            ],
            indices: [0, 1, 2, 0, 2, 3],
            patches: vec![],
        }
    }
}

enum Kind {
    Embedded,
    External,
    Binary,
}

impl Asset {
    /// Geometry buffer: quad positions @0, quad uvs @48, indices @80, triangle positions @92.
    fn geometry(&self) -> Vec<u8> {
        let mut b = Vec::new();
        let uvs = [[0.0f32, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]];
        let floats = self.quad.iter().flatten().chain(uvs.iter().flatten());
        b.extend(floats.flat_map(|f| f.to_le_bytes()));
        b.extend(self.indices.iter().flat_map(|i| i.to_le_bytes()));
        b.extend(TRI.iter().flatten().flat_map(|f| f.to_le_bytes()));
        assert_eq!(b.len(), 128);
        b
    }

    fn json(&self, buffer: &str, image: &str, extra_view: &str) -> String {
        let json = format!(
            r#"{{
  "asset": {{"version": "2.0"}},
  "scene": 0,
  "scenes": [{{"nodes": [0, 2, 3, 4]}}],
  "nodes": [
    {{"name": "root", "translation": [10, 0, 0], "children": [1]}},
    {{"name": "child", "mesh": 0, "scale": [2, 2, 2]}},
    {{"name": "cam", "camera": 0, "translation": [0, 0, 5]}},
    {{"name": "mirror", "mesh": 0, "scale": [-1, 1, 1], "translation": [0, 0, -3]}},
    {{"name": "plain", "mesh": 1, "translation": [0, 4, 0]}}
  ],
  "cameras": [{{"type": "perspective", "perspective": {{"yfov": 0.8, "znear": 0.1}}}}],
  "meshes": [
    {{"name": "m0", "primitives": [
      {{"attributes": {{"POSITION": 0, "TEXCOORD_0": 1}}, "indices": 2, "material": 0}},
      {{"attributes": {{"POSITION": 3}}, "material": 1}}
    ]}},
    {{"name": "m1", "primitives": [{{"attributes": {{"POSITION": 3}}}}]}}
  ],
  "materials": [
    {{"name": "leaf", "alphaMode": "MASK", "alphaCutoff": 0.6, "doubleSided": true,
      "pbrMetallicRoughness": {{"baseColorFactor": [1, 1, 1, 1], "baseColorTexture": {{"index": 0}}}}}},
    {{"name": "plain", "pbrMetallicRoughness": {{"baseColorFactor": [0.2, 0.4, 0.6, 1]}}}}
  ],
  "textures": [{{"source": 0}}],
  "images": [{image}],
  "buffers": [{buffer}],
  "bufferViews": [
    {{"buffer": 0, "byteOffset": 0, "byteLength": 48}},
    {{"buffer": 0, "byteOffset": 48, "byteLength": 32}},
    {{"buffer": 0, "byteOffset": 80, "byteLength": 12}},
    {{"buffer": 0, "byteOffset": 92, "byteLength": 36}}{extra_view}
  ],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}},
    {{"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"}},
    {{"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}},
    {{"bufferView": 3, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}}
  ]
}}"#
        );
        self.patches.iter().fold(json, |j, (from, to)| {
            assert!(j.contains(from), "patch target {from:?} missing");
            j.replacen(from, to, 1)
        })
    }

    /// Writes the asset into `dir` and returns the path of the main file.
    fn write(&self, dir: &Path, kind: Kind) -> PathBuf {
        let geometry = self.geometry();
        let png = png_2x2();
        match kind {
            Kind::Embedded => {
                let buffer = format!(
                    r#"{{"byteLength": 128, "uri": "data:application/octet-stream;base64,{}"}}"#,
                    base64::encode(&geometry)
                );
                let image = format!(
                    r#"{{"uri": "data:image/png;base64,{}"}}"#,
                    base64::encode(&png)
                );
                let path = dir.join("embedded.gltf");
                std::fs::write(&path, self.json(&buffer, &image, "")).unwrap();
                path
            }
            Kind::External => {
                std::fs::write(dir.join("geometry data.bin"), &geometry).unwrap();
                std::fs::write(dir.join("leaf.png"), &png).unwrap();
                let buffer = r#"{"byteLength": 128, "uri": "geometry%20data.bin"}"#;
                let path = dir.join("external.gltf");
                std::fs::write(&path, self.json(buffer, r#"{"uri": "leaf.png"}"#, "")).unwrap();
                path
            }
            Kind::Binary => {
                let mut bin = geometry;
                bin.extend(&png);
                while !bin.len().is_multiple_of(4) {
                    bin.push(0);
                }
                let buffer = format!(r#"{{"byteLength": {}}}"#, bin.len());
                let view = format!(
                    ",\n    {{\"buffer\": 0, \"byteOffset\": 128, \"byteLength\": {}}}",
                    png.len()
                );
                let image = r#"{"bufferView": 4, "mimeType": "image/png"}"#;
                let path = dir.join("binary.glb");
                std::fs::write(&path, glb(&self.json(&buffer, image, &view), &bin)).unwrap();
                path
            }
        }
    }
}

/// A binary glTF container with a JSON and a BIN chunk.
fn glb(json: &str, bin: &[u8]) -> Vec<u8> {
    let mut json = json.as_bytes().to_vec();
    while !json.len().is_multiple_of(4) {
        json.push(b' ');
    }
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut out = Vec::with_capacity(total);
    out.extend(b"glTF");
    out.extend(2u32.to_le_bytes());
    out.extend((total as u32).to_le_bytes());
    out.extend((json.len() as u32).to_le_bytes());
    out.extend(b"JSON");
    out.extend(&json);
    out.extend((bin.len() as u32).to_le_bytes());
    out.extend(b"BIN\0");
    out.extend(bin);
    out
}

pub(super) fn load_path(path: &Path) -> Result<Scene, SceneError> {
    load(path.to_str().unwrap())
}

fn check_good_scene(s: &Scene) {
    // Mesh 0 twice (quad 2 + triangle 1), mesh 1 once.
    assert_eq!(s.triangle_count(), 7);
    assert_eq!(s.positions.len(), 4 + 3 + 4 + 3 + 3);
    // Quad vertex (1,0,0) through root (translate x+10) and child (scale 2).
    assert_eq!(s.positions[1], Vec3::new(12.0, 0.0, 0.0));
    assert_eq!(s.positions[2], Vec3::new(12.0, 2.0, 0.0));
    assert_eq!(s.uvs[0], Vec2::new(0.0, 1.0));
    // Non-indexed triangle: its three vertices in order, with zero uvs (no TEXCOORD_0).
    assert_eq!(s.triangles[2], [4, 5, 6]);
    assert_eq!(s.uvs[5], Vec2::ZERO);

    // Materials: MASK leaf with its 2x2 texture, plain, then the appended default.
    assert_eq!(s.materials.len(), 3);
    let leaf = &s.materials[0];
    assert_eq!(leaf.name, "leaf");
    assert_eq!(leaf.alpha_mode, AlphaMode::Mask { cutoff: 0.6 });
    assert!(leaf.double_sided);
    assert_eq!(leaf.base_color_texture, Some(0));
    let tex = &s.textures[0];
    assert_eq!((tex.width, tex.height, tex.rgba8.len()), (2, 2, 16));
    assert!(leaf.passes_alpha_test(&s.textures, Vec2::new(0.25, 0.25)));
    assert!(!leaf.passes_alpha_test(&s.textures, Vec2::new(0.75, 0.25)));
    assert!(!leaf.passes_alpha_test(&s.textures, Vec2::new(0.25, 0.75)));
    assert!(leaf.passes_alpha_test(&s.textures, Vec2::new(0.75, 0.75)));
    let plain = &s.materials[1];
    assert_eq!(plain.alpha_mode, AlphaMode::Opaque);
    assert!(!plain.double_sided);
    assert_eq!(plain.base_color, [0.2, 0.4, 0.6, 1.0]);
    assert_eq!(s.materials[2].name, "default");
    assert_eq!(&s.triangle_materials, &[0, 0, 1, 0, 0, 1, 2]);

    // The mirrored instance keeps its faces pointing +Z (winding flipped back).
    let normal = |t: [u32; 3]| {
        let [a, b, c] = t.map(|i| s.positions[i as usize]);
        (b - a).cross(c - a)
    };
    assert!(normal(s.triangles[0]).z > 0.0);
    assert!(normal(s.triangles[3]).z > 0.0, "mirrored quad faces -Z");
    assert!(normal(s.triangles[5]).z > 0.0, "mirrored triangle faces -Z");

    let cam = s.camera("cam").unwrap();
    assert_eq!(cam.eye, Vec3::new(0.0, 0.0, 5.0));
    assert_eq!(cam.target, Vec3::new(0.0, 0.0, 4.0));
    assert_eq!(cam.up, Vec3::Y);
    assert!((cam.fov_y_deg - 0.8f32.to_degrees()).abs() < 1e-4);
    s.validate().unwrap();
}

#[test]
fn loads_embedded_external_and_binary_files_alike() {
    let dir = temp_dir("good");
    for kind in [Kind::Embedded, Kind::External, Kind::Binary] {
        let path = Asset::default().write(&dir, kind);
        let scene = load_path(&path).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(scene.name, path.display().to_string());
        check_good_scene(&scene);
    }
}

#[test]
fn extension_is_case_insensitive() {
    let dir = temp_dir("case");
    let path = Asset::default().write(&dir, Kind::Binary);
    let upper = dir.join("BINARY.GLB");
    std::fs::rename(&path, &upper).unwrap();
    check_good_scene(&load_path(&upper).unwrap());
}

/// Loads `path`, expecting an error that names the path and contains `needle`.
pub(super) fn expect_error(path: &Path, needle: &str) -> String {
    let err = load_path(path).expect_err("bad input loaded").to_string();
    assert!(
        err.contains(&path.display().to_string()) || err.contains("scene '"),
        "{err}"
    );
    assert!(err.contains(needle), "expected {needle:?} in: {err}");
    assert!(
        !err.contains("internal error"),
        "a dependency panicked: {err}"
    );
    err
}

#[test]
fn missing_truncated_and_garbage_files_give_errors() {
    let dir = temp_dir("bad");
    expect_error(&dir.join("missing.gltf"), "does not exist");

    let good = std::fs::read(Asset::default().write(&dir, Kind::Binary)).unwrap();
    for cut in [good.len() - 10, good.len() / 2, 30, 13, 10, 4, 0] {
        let path = dir.join(format!("cut{cut}.glb"));
        std::fs::write(&path, &good[..cut]).unwrap();
        expect_error(&path, "glTF");
    }
    let path = dir.join("bad.gltf");
    std::fs::write(&path, "{ \"asset\": { not json").unwrap();
    expect_error(&path, "glTF");

    let mut rng = super::super::procedural::rng::Pcg32::new(3, 7);
    for i in 0..20 {
        let bytes: Vec<u8> = (0..rng.next_u32() % 2000)
            .map(|_| rng.next_u32() as u8)
            .collect();
        let path = dir.join(format!("random{i}.glb"));
        std::fs::write(&path, &bytes).unwrap();
        expect_error(&path, "");
        // Random bytes after a valid GLB magic and length.
        let mut glb = good.clone();
        let start = 20 + (rng.next_u32() as usize % (glb.len() - 20));
        for b in &mut glb[start..(start + 64).min(good.len())] {
            *b = rng.next_u32() as u8;
        }
        std::fs::write(&path, &glb).unwrap();
        let _ = load_path(&path).map_err(|e| assert!(!e.to_string().contains("internal error")));
    }
}

#[test]
fn out_of_range_data_gives_errors() {
    let dir = temp_dir("range");
    let asset = Asset {
        indices: [0, 1, 2, 0, 2, 9],
        ..Asset::default()
    };
    let path = asset.write(&dir, Kind::Embedded);
    let err = expect_error(&path, "index 9 is out of range");
    assert!(err.contains("mesh 0"), "{err}");

    let asset = Asset {
        quad: [
            [0.0, 0.0, 0.0],
            [f32::NAN, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ],
        ..Asset::default()
    };
    expect_error(&asset.write(&dir, Kind::External), "non-finite position");

    // Each patch breaks the file in one way the gltf crate's readers would not survive alone.
    let cases: [(&str, &str, &str); 6] = [
        (
            r#""count": 4, "type": "VEC3""#,
            r#""count": 40, "type": "VEC3""#,
            "reads 40 elements",
        ),
        (
            r#""count": 4, "type": "VEC3""#,
            r#""count": 0, "type": "VEC3""#,
            "count 0",
        ),
        (
            r#""count": 4, "type": "VEC2""#,
            r#""count": 4, "type": "VEC3""#,
            "expected Vec2",
        ),
        (
            r#""componentType": 5123"#,
            r#""componentType": 5126"#,
            "index accessor",
        ),
        (
            r#""byteOffset": 92, "byteLength": 36"#,
            r#""byteOffset": 92, "byteLength": 360"#,
            "buffer 0 has only",
        ),
        (
            r#""byteLength": 48}"#,
            r#""byteLength": 48, "byteStride": 8}"#,
            "byteStride 8",
        ),
    ];
    for (i, (from, to, needle)) in cases.into_iter().enumerate() {
        let asset = Asset {
            patches: vec![(from, to)],
            ..Asset::default()
        };
        let sub = dir.join(format!("case{i}"));
        std::fs::create_dir_all(&sub).unwrap();
        expect_error(&asset.write(&sub, Kind::Embedded), needle);
    }

    let asset = Asset {
        patches: vec![(r#""POSITION": 3}}]"#, r#""POSITION": 9}}]"#)],
        ..Asset::default()
    };
    expect_error(
        &asset.write(&dir, Kind::Embedded),
        "POSITION uses accessor 9",
    );

    // Images the importer would unwrap: no source at all, or a buffer view without mimeType.
    let path = dir.join("image.glb");
    let asset = Asset {
        patches: vec![(r#""mimeType": "image/png""#, r#""name": "x""#)],
        ..Asset::default()
    };
    std::fs::rename(asset.write(&dir, Kind::Binary), &path).unwrap();
    expect_error(&path, "no mimeType");
    let asset = Asset {
        patches: vec![(r#"{"uri": "leaf.png"}"#, r#"{"name": "nothing"}"#)],
        ..Asset::default()
    };
    expect_error(
        &asset.write(&dir, Kind::External),
        "neither a uri nor a bufferView",
    );
    let asset = Asset {
        patches: vec![("geometry%20data.bin", "geometry%FF.bin")],
        ..Asset::default()
    };
    expect_error(&asset.write(&dir, Kind::External), "percent-decode");
}

#[test]
fn triangle_strips_and_fans_keep_winding_and_points_are_skipped() {
    use gltf::mesh::Mode;
    assert_eq!(
        super::assemble(Mode::TriangleStrip, &[0, 1, 2, 3, 4]),
        vec![[0, 1, 2], [2, 1, 3], [2, 3, 4]]
    );
    assert_eq!(
        super::assemble(Mode::TriangleFan, &[0, 1, 2, 3]),
        vec![[1, 2, 0], [2, 3, 0]]
    );
    assert_eq!(
        super::assemble(Mode::Triangles, &[0, 1, 2, 3]),
        vec![[0, 1, 2]]
    );
    assert!(super::assemble(Mode::TriangleStrip, &[0, 1]).is_empty());

    // A file whose second primitive is a strip (mode 5) and whose quad is points (mode 0).
    let dir = temp_dir("modes");
    let asset = Asset {
        patches: vec![
            (
                r#""indices": 2, "material": 0}"#,
                r#""indices": 2, "material": 0, "mode": 0}"#,
            ),
            (
                r#""POSITION": 3}, "material": 1}"#,
                r#""POSITION": 3}, "material": 1, "mode": 5}"#,
            ),
        ],
        ..Asset::default()
    };
    let s = load_path(&asset.write(&dir, Kind::Embedded)).unwrap();
    // Strip of 3 vertices = 1 triangle per instance (2), plus mesh 1's triangle.
    assert_eq!(s.triangle_count(), 3);
}

#[test]
fn sparse_accessors_are_applied() {
    let dir = temp_dir("sparse");
    // Sparse entry: triangle vertex 1 (index read from the index data at byte 2) takes quad vertex
    // 2's position (1, 1, 0).
    let asset = Asset {
        patches: vec![(
            r#"{"bufferView": 3, "componentType": 5126, "count": 3, "type": "VEC3", "#,
            r#"{"bufferView": 3, "componentType": 5126, "count": 3, "type": "VEC3", "sparse": {"count": 1, "indices": {"bufferView": 2, "byteOffset": 2, "componentType": 5123}, "values": {"bufferView": 0, "byteOffset": 24}}, "#,
        )],
        ..Asset::default()
    };
    let s = load_path(&asset.write(&dir, Kind::Embedded)).unwrap();
    assert_eq!(s.positions[4], Vec3::new(10.0, 0.0, 0.0));
    assert_eq!(s.positions[5], Vec3::new(12.0, 2.0, 0.0));
    assert_eq!(s.positions[15], Vec3::new(1.0, 5.0, 0.0));
}

/// Replaces random numbers in the JSON with hostile values and loads the result many times: no
/// input may reach a panic in the `gltf` crate (the loader's backstop would report it as an
/// "internal error"). Slow; run in a debug build for overflow checks:
/// `cargo test -- --ignored fuzz_gltf_numbers`.
#[test]
#[ignore]
fn fuzz_gltf_numbers() {
    let dir = temp_dir("fuzz");
    for kind in [Kind::Embedded, Kind::Binary] {
        let file = Asset::default().write(&dir, kind);
        fuzz_numbers(&file, 3000);
    }
    let file = dir.join("animated.gltf");
    std::fs::write(&file, animated_camera_gltf("CUBICSPLINE")).unwrap();
    fuzz_numbers(&file, 3000);
}

/// Loads `rounds` variants of `file` (a .gltf, or a .glb whose JSON chunk is mutated).
pub(super) fn fuzz_numbers(file: &Path, rounds: usize) {
    let bytes = std::fs::read(file).unwrap();
    let is_glb = bytes.starts_with(b"glTF");
    let (good, bin) = if is_glb {
        let len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
        let json = String::from_utf8(bytes[20..20 + len].to_vec()).unwrap();
        (json, bytes[20 + len + 8..].to_vec())
    } else {
        (String::from_utf8(bytes).unwrap(), Vec::new())
    };
    let hostile = [
        "0",
        "1",
        "2",
        "3",
        "4",
        "5",
        "6",
        "7",
        "8",
        "12",
        "13",
        "255",
        "5120",
        "5121",
        "5122",
        "5123",
        "5125",
        "5126",
        "65535",
        "4294967295",
        "4294967296",
        "99999999999999",
        "-1",
        "0.5",
        "1e30",
        "18446744073709551615",
    ];
    // Byte ranges of the JSON numbers: digits after a space, '[' or ':' (never inside base64).
    let mut numbers = Vec::new();
    let bytes = good.as_bytes();
    let mut i = 1;
    while i < bytes.len() {
        if bytes[i].is_ascii_digit() && matches!(bytes[i - 1], b' ' | b'[' | b':') {
            let start = i;
            while bytes[i].is_ascii_digit() || bytes[i] == b'.' {
                i += 1;
            }
            numbers.push(start..i);
        }
        i += 1;
    }
    assert!(
        numbers.len() > 20,
        "too few numbers to fuzz: {}",
        numbers.len()
    );
    let mut rng = super::super::procedural::rng::Pcg32::new(5, 5);
    let path = file.with_file_name(if is_glb { "fuzz.glb" } else { "fuzz.gltf" });
    for round in 0..rounds {
        let mut text = good.clone();
        // Up to three replacements, from the back so earlier ranges stay valid.
        let mut picks: Vec<_> = (0..1 + rng.next_u32() % 3)
            .map(|_| numbers[rng.next_u32() as usize % numbers.len()].clone())
            .collect();
        picks.sort_by_key(|r| std::cmp::Reverse(r.start));
        picks.dedup();
        for r in picks {
            text.replace_range(r, hostile[rng.next_u32() as usize % hostile.len()]);
        }
        if is_glb {
            std::fs::write(&path, glb(&text, &bin)).unwrap();
        } else {
            std::fs::write(&path, &text).unwrap();
        }
        if let Err(e) = load_path(&path) {
            let msg = e.to_string();
            assert!(
                !msg.contains("internal error"),
                "round {round}: {msg}\n{text}"
            );
        }
    }
}

/// One triangle in the z = 0 plane with vertex normals, placed by `node` (JSON fields).
fn triangle_with_normals(dir: &Path, normals: [[f32; 3]; 3], node: &str) -> PathBuf {
    let floats = TRI.iter().flatten().chain(normals.iter().flatten());
    let bytes: Vec<u8> = floats.flat_map(|f| f.to_le_bytes()).collect();
    let json = format!(
        r#"{{"asset": {{"version": "2.0"}}, "scene": 0, "scenes": [{{"nodes": [0]}}],
  "nodes": [{{"mesh": 0 {node}}}],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0, "NORMAL": 1}}}}]}}],
  "buffers": [{{"byteLength": 72, "uri": "data:application/octet-stream;base64,{}"}}],
  "bufferViews": [{{"buffer": 0, "byteOffset": 0, "byteLength": 36}},
                  {{"buffer": 0, "byteOffset": 36, "byteLength": 36}}],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}},
    {{"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"}}]}}"#,
        base64::encode(&bytes)
    );
    let path = dir.join("normals.gltf");
    std::fs::write(&path, json).unwrap();
    path
}

#[test]
fn vertex_normals_follow_the_node_transform() {
    let dir = temp_dir("normals");
    let n = Vec3::new(1.0, 0.0, 1.0).normalize();
    // Scaled 4× along x: normals transform by the inverse transpose, so the x component shrinks
    // (the surface leans towards the yz plane), then are renormalised.
    let path = triangle_with_normals(&dir, [n.to_array(); 3], r#", "scale": [4, 1, 1]"#);
    let s = load_path(&path).unwrap();
    let expected = Vec3::new(n.x / 4.0, 0.0, n.z).normalize();
    assert_eq!(s.normals.len(), 3);
    for got in &s.normals {
        assert!(got.distance(expected) < 1e-6, "{got} vs {expected}");
    }
    // A zero or non-finite normal in the file is "none" at that vertex; a file whose every normal
    // is none keeps no normals at all.
    let path = triangle_with_normals(&dir, [[0.0; 3], [0.0, 0.0, 1.0], [0.0; 3]], "");
    let s = load_path(&path).unwrap();
    assert_eq!(s.normals, vec![Vec3::ZERO, Vec3::Z, Vec3::ZERO]);
    let path = triangle_with_normals(&dir, [[0.0; 3]; 3], "");
    assert!(load_path(&path).unwrap().normals.is_empty());
}

/// A triangle and a camera (under a parent moved by (10, 0, 0)) whose node an animation moves:
/// translation keys at 0, 1, 2 s with `interpolation`, rotation keys at 0 and 2 s (90° about +Y).
/// CUBICSPLINE translations get zero tangents.
fn animated_camera_gltf(interpolation: &str) -> String {
    let cubic = interpolation == "CUBICSPLINE";
    let mut b: Vec<u8> = Vec::new();
    push_floats(&mut b, &[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]); // triangle @0, 36
    push_floats(&mut b, &[0.0, 1.0, 2.0]); // translation times @36, 12
    let keys = [[0.0, 1.0, 5.0], [2.0, 1.0, 5.0], [4.0, 1.0, 3.0]];
    for k in keys {
        if cubic {
            push_floats(&mut b, &[0.0; 3]);
        }
        push_floats(&mut b, &k);
        if cubic {
            push_floats(&mut b, &[0.0; 3]);
        }
    }
    let translations = b.len() - 48; // @48
    push_floats(&mut b, &[0.0, 2.0]); // rotation times
    let s = std::f32::consts::FRAC_1_SQRT_2;
    push_floats(&mut b, &[0.0, 0.0, 0.0, 1.0, 0.0, s, 0.0, s]); // rotations
    let count = if cubic { 9 } else { 3 };
    format!(
        r#"{{
  "asset": {{"version": "2.0"}},
  "scene": 0,
  "scenes": [{{"nodes": [0, 1]}}],
  "nodes": [
    {{"name": "tri", "mesh": 0}},
    {{"name": "rig", "translation": [10, 0, 0], "children": [2]}},
    {{"name": "cam", "camera": 0, "translation": [0, 1, 5]}}
  ],
  "cameras": [{{"type": "perspective", "perspective": {{"yfov": 0.8, "znear": 0.1}}}}],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}}}]}}],
  "animations": [{{
    "samplers": [
      {{"input": 1, "output": 2, "interpolation": "{interpolation}"}},
      {{"input": 3, "output": 4, "interpolation": "LINEAR"}}
    ],
    "channels": [
      {{"sampler": 0, "target": {{"node": 2, "path": "translation"}}}},
      {{"sampler": 1, "target": {{"node": 2, "path": "rotation"}}}}
    ]
  }}],
  "buffers": [{{"byteLength": {len}, "uri": "data:application/octet-stream;base64,{data}"}}],
  "bufferViews": [
    {{"buffer": 0, "byteOffset": 0, "byteLength": 36}},
    {{"buffer": 0, "byteOffset": 36, "byteLength": 12}},
    {{"buffer": 0, "byteOffset": 48, "byteLength": {translations}}},
    {{"buffer": 0, "byteOffset": {rot_times}, "byteLength": 8}},
    {{"buffer": 0, "byteOffset": {rots}, "byteLength": 32}}
  ],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}},
    {{"bufferView": 1, "componentType": 5126, "count": 3, "type": "SCALAR", "min": [0], "max": [2]}},
    {{"bufferView": 2, "componentType": 5126, "count": {count}, "type": "VEC3"}},
    {{"bufferView": 3, "componentType": 5126, "count": 2, "type": "SCALAR", "min": [0], "max": [2]}},
    {{"bufferView": 4, "componentType": 5126, "count": 2, "type": "VEC4"}}
  ]
}}"#,
        len = b.len(),
        data = base64::encode(&b),
        rot_times = 48 + translations,
        rots = 48 + translations + 8,
    )
}

#[test]
fn animated_cameras_become_camera_paths() {
    let dir = temp_dir("animated-camera");
    for interpolation in ["LINEAR", "CUBICSPLINE"] {
        let file = dir.join(format!("{interpolation}.gltf"));
        std::fs::write(&file, animated_camera_gltf(interpolation)).unwrap();
        let scene = load(file.to_str().unwrap()).unwrap();
        assert_eq!(scene.path_names(), vec!["cam".to_string()]);
        let path = scene.path("cam", 1.0).unwrap();
        let times: Vec<f32> = path.keyframes().iter().map(|k| k.time).collect();
        let (rig, s) = (Vec3::new(10.0, 0.0, 0.0), std::f32::consts::FRAC_1_SQRT_2);
        // The keys, under the parent's translation; the rotation slerped: 45° at 1 s.
        let at = |t: f32| path.camera_at(t).unwrap();
        assert!((at(0.0).eye - (rig + Vec3::new(0.0, 1.0, 5.0))).length() < 1e-5);
        assert!((at(1.0).eye - (rig + Vec3::new(2.0, 1.0, 5.0))).length() < 1e-5);
        assert!((at(2.0).eye - (rig + Vec3::new(4.0, 1.0, 3.0))).length() < 1e-5);
        assert!((at(0.0).forward() - Vec3::NEG_Z).length() < 1e-5);
        assert!((at(1.0).forward() - Vec3::new(-s, 0.0, -s)).length() < 1e-4);
        assert!((at(2.0).forward() - Vec3::NEG_X).length() < 1e-5);
        assert!((at(1.0).fov_y_deg - 0.8f32.to_degrees()).abs() < 1e-4);
        if interpolation == "LINEAR" {
            assert_eq!(times, vec![0.0, 1.0, 2.0]);
        } else {
            // Zero tangents: the Hermite curve eases in and out, so at a quarter of the first
            // segment the eye has covered h01(0.25) = 0.15625 of it (glTF Appendix C).
            assert_eq!(times.len(), 2 + 1 + 2 * 3);
            let eye = at(0.25).eye - rig;
            assert!((eye.x - 2.0 * 0.15625).abs() < 1e-4, "{eye}");
        }
    }
    // Still cameras give no path; the scene offers its automatic orbit instead.
    let file = Asset::default().write(&dir, Kind::Embedded);
    let scene = load(file.to_str().unwrap()).unwrap();
    assert_eq!(scene.cameras.len(), 1);
    assert!(scene.paths.is_empty());
    assert_eq!(scene.path_names(), vec!["orbit".to_string()]);
}

#[test]
fn camera_animations_of_the_wrong_type_are_not_used_and_the_scene_loads() {
    let dir = temp_dir("animated-camera-types");
    let rotation = r#"{"bufferView": 4, "componentType": 5126, "count": 2, "type": "VEC4"}"#;
    let times = r#"{"bufferView": 1, "componentType": 5126, "count": 3, "type": "SCALAR""#;
    for (from, to) in [
        // Rotations as unsigned ints (glTF allows floats and normalized 8- and 16-bit ones).
        (rotation, rotation.replace("5126", "5125")),
        // Rotations as three-component vectors.
        (rotation, rotation.replace("VEC4", "VEC3")),
        // Key times as integers.
        (times, times.replace("5126", "5125")),
    ] {
        let file = dir.join("bad.gltf");
        let json = animated_camera_gltf("LINEAR");
        assert!(json.contains(from));
        std::fs::write(&file, json.replacen(from, &to, 1)).unwrap();
        let scene = load(file.to_str().unwrap()).unwrap_or_else(|e| panic!("{to}: {e}"));
        assert_eq!(scene.cameras.len(), 1, "{to}");
        assert!(scene.paths.is_empty(), "{to}");
    }
}

#[test]
fn texture_transforms_move_the_alpha_test_s_coordinates() {
    let dir = temp_dir("texture-transform");
    // The extension's own example: the lower left quadrant of the image, turned 90° clockwise.
    let transform = r#""baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform":
        {"offset": [0, 1], "rotation": 1.57079632679, "scale": [0.5, 0.5]}}}"#;
    let asset = Asset {
        patches: vec![
            (r#""baseColorTexture": {"index": 0}"#, transform),
            (
                r#""scene": 0,"#,
                r#""scene": 0, "extensionsUsed": ["KHR_texture_transform"],
                "extensionsRequired": ["KHR_texture_transform"],"#,
            ),
        ],
        ..Asset::default()
    };
    let scene = load_path(&asset.write(&dir, Kind::Embedded)).unwrap();
    // The quad's uvs (0, 1), (1, 1), (1, 0), (0, 0) become (u', v') = (0.5 v, 1 − 0.5 u):
    // u' in [0, 0.5] (left) and v' in [0.5, 1] (lower half, v down), v running along u'.
    let expected = [(0.5, 1.0), (0.5, 0.5), (0.0, 0.5), (0.0, 1.0)];
    for (uv, (u, v)) in scene.uvs.iter().zip(expected) {
        assert!(
            uv.abs_diff_eq(Vec2::new(u, v), 1e-6),
            "{uv} against ({u}, {v})"
        );
    }
}

#[test]
fn specular_glossiness_materials_alpha_test_their_diffuse_texture() {
    let dir = temp_dir("spec-gloss");
    // The leaf material in the specular-glossiness workflow: its diffuse texture and factor
    // stand for the base colour (the metallic-roughness one, left plain, is the fallback).
    let spec_gloss = r#""pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1]},
      "extensions": {"KHR_materials_pbrSpecularGlossiness":
        {"diffuseFactor": [1, 1, 1, 0.5], "diffuseTexture": {"index": 0}}}"#;
    let from = r#""pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1], "baseColorTexture": {"index": 0}}"#;
    let asset = Asset {
        patches: vec![(from, spec_gloss)],
        ..Asset::default()
    };
    let scene = load_path(&asset.write(&dir, Kind::Embedded)).unwrap();
    let leaf = &scene.materials[0];
    assert_eq!(leaf.base_color, [1.0, 1.0, 1.0, 0.5]);
    assert_eq!(leaf.base_color_texture, Some(0));
    assert_eq!(leaf.alpha_mode, AlphaMode::Mask { cutoff: 0.6 });
    // A diffuse texture that does not exist is an error, not a crash.
    let asset = Asset {
        patches: vec![(
            from,
            spec_gloss.replace("\"index\": 0", "\"index\": 7").leak(),
        )],
        ..Asset::default()
    };
    expect_error(&asset.write(&dir, Kind::Embedded), "diffuseTexture");
}

/// Issue 62: a file that breaks rules of the specification the loader does not need (an
/// accessor's min of the wrong length, a matrix beside a translation, a rotation that is not a
/// unit quaternion) still loads, and each problem is reported; a valid file has none.
#[test]
fn spec_problems_are_warnings_and_the_file_still_loads() {
    let dir = temp_dir("spec");
    let options = crate::scene::LoadOptions::default();
    let good = Asset::default().write(&dir, Kind::Embedded);
    let (_, problems) = super::load_with_problems(&good, &options).unwrap();
    assert!(problems.is_empty(), "{problems:?}");
    let asset = Asset {
        patches: vec![
            // gltf's validation checks POSITION's min and max, not the others'.
            (
                r#""count": 4, "type": "VEC2"}"#,
                r#""count": 4, "type": "VEC2", "min": [0], "max": [1, 1]}"#,
            ),
            (
                r#"{"name": "child", "mesh": 0, "scale": [2, 2, 2]}"#,
                r#"{"name": "child", "mesh": 0, "scale": [2, 2, 2], "matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]}"#,
            ),
            (
                r#"{"name": "plain", "mesh": 1, "translation": [0, 4, 0]}"#,
                r#"{"name": "plain", "mesh": 1, "translation": [0, 4, 0], "rotation": [0, 0, 0, 2]}"#,
            ),
        ],
        ..Asset::default()
    };
    let bad = asset.write(&dir, Kind::Embedded);
    let (scene, problems) = super::load_with_problems(&bad, &options).unwrap();
    assert!(scene.triangle_count() > 0);
    assert_eq!(problems.len(), 3, "{problems:?}");
    for needle in [
        "accessor 1: min has 1 values",
        "node 1 has both a matrix",
        "node 4: rotation",
    ] {
        assert!(
            problems.iter().any(|p| p.contains(needle)),
            "{needle:?} not in {problems:?}"
        );
    }
    // And through the public loader: it loads.
    assert!(load_path(&bad).is_ok());
}
