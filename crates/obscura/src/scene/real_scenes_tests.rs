//! Loads the real test scenes from `shared/scenes` (skipped, with a printed reason, when absent).

use std::path::PathBuf;
use std::time::Instant;

use super::{load, shared_scenes_dir, AlphaMode, Scene};

/// The file under the shared scenes folder, or `None` (and a printed reason) to skip.
fn scene_file(rel: &str) -> Option<PathBuf> {
    let Some(dir) = shared_scenes_dir() else {
        println!("skipping: no shared scenes folder (set OBSCURA_SHARED_SCENES)");
        return None;
    };
    let path = dir.join(rel);
    if !path.is_file() {
        println!("skipping: {} not found", path.display());
        return None;
    }
    Some(path)
}

fn timed_load(path: &std::path::Path) -> Scene {
    let start = Instant::now();
    let scene = load(path.to_str().unwrap()).unwrap_or_else(|e| panic!("{e}"));
    println!(
        "{}: {} triangles, {} vertices, {} materials, {} textures, {} cameras in {:.2} s",
        path.display(),
        scene.triangle_count(),
        scene.positions.len(),
        scene.materials.len(),
        scene.textures.len(),
        scene.cameras.len(),
        start.elapsed().as_secs_f32()
    );
    scene
}

#[test]
fn sponza_glb() {
    let Some(path) = scene_file("crytek-sponza/sponza.glb") else {
        return;
    };
    let s = timed_load(&path);
    assert_eq!(s.triangle_count(), 262_267);
    let masked: Vec<&str> = s
        .materials
        .iter()
        .filter(|m| matches!(m.alpha_mode, AlphaMode::Mask { .. }))
        .map(|m| m.name.as_str())
        .collect();
    println!("MASK materials: {masked:?}");
    assert_eq!(masked.len(), 3);
    assert_eq!(
        s.materials.len(),
        25,
        "25 glTF materials, no default needed"
    );
    // Every masked material has a texture carrying its alpha.
    for m in s.materials.iter().filter(|m| m.keeps_back_faces()) {
        if matches!(m.alpha_mode, AlphaMode::Mask { .. }) {
            assert!(m.base_color_texture.is_some(), "{}", m.name);
        }
    }
    for t in &s.textures {
        assert!(t.width <= super::MAX_TEXTURE_SIZE && t.height <= super::MAX_TEXTURE_SIZE);
    }
    let b = s.bounds();
    println!("bounds {:?}..{:?}", b.min, b.max);
    s.default_camera(16.0 / 9.0).validate().unwrap();
}

#[test]
fn sibenik_obj() {
    let Some(path) = scene_file("sibenik/sibenik.obj") else {
        return;
    };
    let s = timed_load(&path);
    assert_eq!(s.triangle_count(), 73_564);
    s.default_camera(1.0).validate().unwrap();
}

#[test]
fn cornell_box_obj_without_its_mtl() {
    let Some(path) = scene_file("cornell-box/CornellBox-Original.obj") else {
        return;
    };
    let s = timed_load(&path);
    assert_eq!(s.triangle_count(), 36);
    // The .mtl is not shipped: everything gets the default material.
    assert_eq!(s.materials.len(), 1);
    assert_eq!(s.materials[0].name, "default");
}
