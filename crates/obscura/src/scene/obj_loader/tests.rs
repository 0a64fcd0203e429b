//! OBJ loader tests on small files written from code.

use std::path::{Path, PathBuf};

use glam::{Vec2, Vec3};

use super::super::{load, AlphaMode, Scene};

fn temp_dir(tag: &str) -> crate::scene::test_dir::TestDir {
    crate::scene::test_dir::TestDir::new(&format!("obj-{tag}"))
}

/// A quad (material red) and a triangle (material blue), uvs on every vertex.
const QUAD_AND_TRIANGLE: &str = "\
# test
mtllib test.mtl
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 2 0 0
v 3 0 0
v 2 1 0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
usemtl red
f 1/1 2/2 3/3 4/4
usemtl blue
f 5/1 6/2 7/3
";

fn write(dir: &Path, name: &str, text: &[u8]) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

fn load_path(path: &Path) -> Result<Scene, String> {
    load(path.to_str().unwrap()).map_err(|e| e.to_string())
}

#[test]
fn quad_and_triangle_with_materials_and_texture() {
    let dir = temp_dir("mtl");
    let mtl = "newmtl red\nKd 1 0 0\n\nnewmtl blue\nKd 0 0 1\nd 0.5\nmap_Kd tex.png\n";
    write(&dir, "test.mtl", mtl.as_bytes());
    let img = image::RgbaImage::from_pixel(3, 2, image::Rgba([1, 2, 3, 4]));
    img.save(dir.join("tex.png")).unwrap();
    let path = write(&dir, "scene.OBJ", QUAD_AND_TRIANGLE.as_bytes());

    let s = load_path(&path).unwrap();
    assert_eq!(s.triangle_count(), 3);
    assert_eq!(s.materials.len(), 2, "no default material needed");
    let red = &s.materials[0];
    assert_eq!(
        (red.name.as_str(), red.base_color),
        ("red", [1.0, 0.0, 0.0, 1.0])
    );
    assert_eq!(red.base_color_texture, None);
    let blue = &s.materials[1];
    assert_eq!(blue.base_color, [0.0, 0.0, 1.0, 0.5]);
    assert_eq!(blue.alpha_mode, AlphaMode::Blend);
    assert_eq!(blue.base_color_texture, Some(0));
    assert_eq!((s.textures[0].width, s.textures[0].height), (3, 2));
    assert_eq!(&s.textures[0].rgba8[..4], &[1, 2, 3, 4]);
    assert_eq!(&s.triangle_materials, &[0, 0, 1]);
    // OBJ has no culling flag: both sides count.
    assert!(s.materials.iter().all(|m| m.double_sided));

    // Positions read as given (Y up); v flipped to the glTF convention.
    let tri = s.triangles[2].map(|i| s.positions[i as usize]);
    assert_eq!(
        tri,
        [
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(3.0, 0.0, 0.0),
            Vec3::new(2.0, 1.0, 0.0)
        ]
    );
    let uvs = s.triangles[2].map(|i| s.uvs[i as usize]);
    assert_eq!(
        uvs,
        [
            Vec2::new(0.0, 1.0),
            Vec2::new(1.0, 1.0),
            Vec2::new(1.0, 0.0)
        ]
    );
    // Counter-clockwise input stays counter-clockwise (+Z normal).
    for t in &s.triangles {
        let [a, b, c] = t.map(|i| s.positions[i as usize]);
        assert!((b - a).cross(c - a).z > 0.0);
    }
}

#[test]
fn missing_or_broken_mtl_and_texture_are_tolerated() {
    let dir = temp_dir("nomtl");
    let path = write(&dir, "scene.obj", QUAD_AND_TRIANGLE.as_bytes());
    let s = load_path(&path).unwrap();
    assert_eq!(s.triangle_count(), 3);
    assert_eq!(s.materials.len(), 1);
    assert_eq!(s.materials[0].name, "default");
    assert!(s.materials[0].double_sided);
    assert!(s.triangle_materials.iter().all(|&m| m == 0));

    let garbage: Vec<u8> = (0..500u32).map(|i| (i * 7919 % 251) as u8).collect();
    write(&dir, "test.mtl", &garbage);
    let s = load_path(&path).unwrap();
    assert_eq!(s.triangle_count(), 3);

    // A texture that is missing or not an image: the material stays, untextured.
    write(
        &dir,
        "test.mtl",
        b"newmtl red\nKd 1 0 0\nmap_Kd nowhere.png\nnewmtl blue\nmap_Kd junk.png\n",
    );
    write(&dir, "junk.png", b"not a png");
    let s = load_path(&path).unwrap();
    assert_eq!(s.materials.len(), 2);
    assert!(s.textures.is_empty());
    assert!(s.materials.iter().all(|m| m.base_color_texture.is_none()));
    assert_eq!(s.materials[0].base_color, [1.0, 0.0, 0.0, 1.0]);
}

#[test]
fn obj_without_uvs_or_with_partial_uvs_gets_zero_uvs() {
    let dir = temp_dir("uvs");
    let path = write(
        &dir,
        "a.obj",
        b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0.5 0.5\nf 1 2 3\nf 2/1 4/1 3/1\n",
    );
    let s = load_path(&path).unwrap();
    assert_eq!(s.triangle_count(), 2);
    assert_eq!(s.uvs.len(), s.positions.len());
    assert!(s.uvs.iter().all(|&uv| uv == Vec2::ZERO));
}

#[test]
fn bad_obj_files_give_errors_naming_the_file() {
    let dir = temp_dir("bad");
    let cases: [(&str, &[u8], &str); 9] = [
        (
            "random.obj",
            &[0xff, 0xfe, 0x00, 0x81, 0x13, 0x37, 0xc3, 0x28],
            "not text",
        ),
        (
            "range.obj",
            b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n",
            "out of bounds",
        ),
        (
            "zero.obj",
            b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n",
            "index 0",
        ),
        (
            "neg.obj",
            b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -9\n",
            "index -9",
        ),
        (
            "huge.obj",
            b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999\n",
            "99999999999",
        ),
        (
            "uv0.obj",
            b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/0 2/1 3/1\n",
            "texture coordinate index 0",
        ),
        (
            "min.obj",
            b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -9223372036854775808\n",
            "out of range",
        ),
        ("junk.obj", b"v 1 2\nf 1 2 3\n", "position parse"),
        ("empty.obj", b"# nothing\nv 1 2 3\n", "no triangles"),
    ];
    for (name, bytes, needle) in cases {
        let path = write(&dir, name, bytes);
        let err = load_path(&path).expect_err(name);
        assert!(err.contains(&path.display().to_string()), "{err}");
        assert!(
            err.contains(needle),
            "{name}: expected {needle:?} in: {err}"
        );
        assert!(!err.contains("internal error"), "{err}");
    }
    let mut rng = super::super::procedural::rng::Pcg32::new(11, 2);
    for i in 0..30 {
        let bytes: Vec<u8> = (0..rng.next_u32() % 3000)
            .map(|_| rng.next_u32() as u8)
            .collect();
        let path = write(&dir, &format!("noise{i}.obj"), &bytes);
        let err = load_path(&path).expect_err("noise loaded");
        assert!(!err.contains("internal error"), "{err}");
    }
    // Text noise made of OBJ keywords and numbers (valid UTF-8, so it reaches the parser).
    let words = [
        "v", "vt", "vn", "f", "l", "o", "g", "usemtl", "1", "-1", "0", "2/3", "1//1", "x", "\n",
    ];
    for i in 0..200 {
        let text: Vec<&str> = (0..rng.next_u32() % 200)
            .map(|_| words[rng.next_u32() as usize % words.len()])
            .collect();
        let path = write(&dir, &format!("words{i}.obj"), text.join(" ").as_bytes());
        if let Err(err) = load_path(&path) {
            assert!(!err.contains("internal error"), "{err}");
        }
    }
}

#[test]
fn vertex_normals_are_read_where_every_vertex_has_one() {
    let dir = temp_dir("vn");
    let with = write(
        &dir,
        "with.obj",
        b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 2\nvn 0 1 1\nf 1//1 2//1 3//2\n",
    );
    let s = load_path(&with).unwrap();
    let lean = Vec3::new(0.0, 1.0, 1.0).normalize();
    assert_eq!(s.normals.len(), s.positions.len());
    // Normalised, and each vertex has the normal its face corner names.
    for (p, n) in s.positions.iter().zip(&s.normals) {
        let expected = if p.y == 1.0 { lean } else { Vec3::Z };
        assert!(n.distance(expected) < 1e-6, "{p}: {n}");
    }
    // Shading normals by default where the file has vertex normals (issue 62): the AO is computed
    // around the interpolated normal, which leans towards +y at the third corner.
    assert!(s.uses_shading_normals(), "shading normals by default");
    let n = s.surface_normal(0, 0.0, 1.0, Vec3::Z);
    assert!(n.distance(lean) < 1e-6, "{n}");
    let without = write(&dir, "without.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    let flat = load_path(&without).unwrap();
    assert!(flat.normals.is_empty());
    // None to interpolate: face normals, and the report says why.
    assert!(!flat.uses_shading_normals());
    assert_eq!(flat.surface_normal(0, 0.0, 1.0, Vec3::Z), Vec3::Z);
    assert!(flat
        .options_description()
        .ends_with("normals face (no vertex normals)"));
}

/// `map_d` masks cut materials out as glTF's MASK does: the mask's grey level (or its alpha
/// channel, where it has a varying one) becomes the texture's alpha, tested at 0.5, and texture
/// names written with backslashes or with MTL options before them are found.
#[test]
fn map_d_masks_cut_materials_out() {
    let dir = temp_dir("map-d");
    std::fs::create_dir_all(dir.join("textures")).unwrap();
    image::RgbaImage::from_pixel(1, 1, image::Rgba([10, 20, 30, 255]))
        .save(dir.join("textures/leaf.png"))
        .unwrap();
    // Grey mask: white top-left and bottom-right; a TGA, as older scenes' masks are.
    image::GrayImage::from_raw(2, 2, vec![255, 0, 0, 255])
        .unwrap()
        .save(dir.join("textures/leaf_mask.tga"))
        .unwrap();
    // A mask with an alpha channel (its grey level all white): the alpha counts.
    image::RgbaImage::from_raw(2, 1, vec![255, 255, 255, 0, 255, 255, 255, 200])
        .unwrap()
        .save(dir.join("fence.png"))
        .unwrap();
    let mtl = "newmtl red\nKd 1 0 0\nmap_Kd -s 1 1 1 textures/leaf.png\nmap_d textures\\leaf_mask.tga\n\n\
               newmtl blue\nKd 0 0 1\nd 0\nmap_d fence.png\n\n\
               newmtl missing\nmap_Kd textures/leaf.png\nmap_d nowhere.png\n";
    write(&dir, "test.mtl", mtl.as_bytes());
    let obj =
        QUAD_AND_TRIANGLE.replace("usemtl blue", "usemtl blue\nf 5/1 6/2 7/3\nusemtl missing");
    let s = load_path(&write(&dir, "scene.obj", obj.as_bytes())).unwrap();
    let texture = |m: usize| &s.textures[s.materials[m].base_color_texture.unwrap() as usize];

    let leaf = &s.materials[0];
    assert_eq!(leaf.alpha_mode, AlphaMode::Mask { cutoff: 0.5 });
    let t = texture(0);
    assert_eq!((t.width, t.height), (2, 2), "the mask's resolution");
    assert_eq!(
        t.rgba8,
        [10, 20, 30, 255, 10, 20, 30, 0, 10, 20, 30, 0, 10, 20, 30, 255]
    );
    let fence = &s.materials[1];
    assert_eq!(fence.alpha_mode, AlphaMode::Mask { cutoff: 0.5 });
    assert_eq!(
        fence.base_color,
        [0.0, 0.0, 1.0, 1.0],
        "`d` does not cut with a mask"
    );
    assert_eq!(texture(1).rgba8, [255, 255, 255, 0, 255, 255, 255, 200]);
    // A mask that does not load leaves the material opaque, with its colour texture.
    let missing = &s.materials[2];
    assert_eq!(missing.alpha_mode, AlphaMode::Opaque);
    assert_eq!(texture(2).rgba8, [10, 20, 30, 255]);
}

/// A material library in a subfolder names its textures from there.
#[test]
fn textures_are_found_beside_a_material_library_in_a_subfolder() {
    let dir = temp_dir("mtl-folder");
    std::fs::create_dir_all(dir.join("materials")).unwrap();
    image::GrayImage::from_raw(1, 2, vec![255, 0])
        .unwrap()
        .save(dir.join("materials/mask.png"))
        .unwrap();
    write(&dir, "materials/lib.mtl", b"newmtl red\nmap_d mask.png\n");
    let obj = QUAD_AND_TRIANGLE.replace("mtllib test.mtl", "mtllib materials/lib.mtl");
    let s = load_path(&write(&dir, "scene.obj", obj.as_bytes())).unwrap();
    assert_eq!(s.materials[0].alpha_mode, AlphaMode::Mask { cutoff: 0.5 });
    let t = &s.textures[s.materials[0].base_color_texture.unwrap() as usize];
    assert_eq!(t.rgba8, [255, 255, 255, 255, 255, 255, 255, 0]);
}

#[test]
fn faces_are_counted_as_the_triangles_they_make() {
    let text =
        b"v 0 0 0\nf 1 2 3\n  f 1/1 2/2 3/3 4/4\r\nf\t1 2 3 4 5 6 7\nfo 1 2 3\nl 1 2 3 4\nf 1 2\n";
    // 1 + 2 + 5; `fo` is not a face, a line is no triangle, a face of two corners makes none.
    assert_eq!(super::triangle_count(text), 8);
}

#[test]
fn a_polygon_of_fifty_million_corners_is_refused_before_it_is_parsed() {
    // 100 MB: one face of 50,000,004 corners, 50,000,002 triangles once fanned, over the limit
    // of 50,000,000 (tobj would hold gigabytes of indices before any other check).
    let dir = temp_dir("obj-budget");
    let mut text = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf".to_vec();
    text.extend(b" 1 2 3 1".repeat(12_500_001));
    let path = write(&dir, "fan.obj", &text);
    let e = load_path(&path).unwrap_err();
    assert!(e.contains("50,000,002 triangles"), "{e}");
    assert!(e.contains("limit of 50,000,000 triangles"), "{e}");
    assert!(e.contains("OBSCURA_MAX_TRIANGLES"), "{e}");
}
