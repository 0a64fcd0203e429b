//! Tests of the built-in scenes, with a tiny brute-force CPU ray caster to check what the
//! cameras see (and, on request, to write preview images).

use glam::{Vec2, Vec3};

use super::super::{Camera, Scene};
use super::{build, builtin, builtin_names};

/// Triangle budget per scene: tests rasterise these on a CPU Vulkan driver.
const BUDGET: usize = 60_000;

fn build_ok(name: &str) -> (Scene, Vec<super::Solid>) {
    build(name).unwrap_or_else(|| panic!("no built-in '{name}'"))
}

#[test]
fn every_builtin_validates_within_budget() {
    for &name in builtin_names() {
        let scene = builtin(name).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(scene.name, name);
        let n = scene.triangle_count();
        println!("{name}: {n} triangles, {} vertices", scene.positions.len());
        assert!(n > 0 && n <= BUDGET, "{name}: {n} triangles");
        assert!(scene.textures.is_empty());
    }
}

#[test]
fn builtins_are_deterministic() {
    for &name in builtin_names() {
        let (a, b) = (build_ok(name).0, build_ok(name).0);
        assert_eq!(a.positions, b.positions, "{name}");
        assert_eq!(a.uvs, b.uvs, "{name}");
        assert_eq!(a.triangles, b.triangles, "{name}");
        assert_eq!(a.triangle_materials, b.triangle_materials, "{name}");
        assert_eq!(a.materials, b.materials, "{name}");
        assert_eq!(a.cameras, b.cameras, "{name}");
    }
}

#[test]
fn materials_have_distinct_colours() {
    for &name in builtin_names() {
        let scene = build_ok(name).0;
        let colours: Vec<[f32; 4]> = scene.materials.iter().map(|m| m.base_color).collect();
        for (i, a) in colours.iter().enumerate() {
            assert!(
                !colours[..i].contains(a),
                "{name}: material {i} repeats a colour"
            );
        }
    }
}

#[test]
fn cameras_are_valid_aimed_at_the_scene_and_outside_solids() {
    for &name in builtin_names() {
        let (scene, solids) = build_ok(name);
        assert!(
            scene.cameras.len() >= 2,
            "{name}: {} cameras",
            scene.cameras.len()
        );
        assert_eq!(scene.cameras[0].name, "closeup", "{name}: first camera");
        let b = scene.bounds();
        let margin = Vec3::splat(0.1 * b.diagonal());
        for cam in &scene.cameras {
            let c = cam.camera;
            c.validate()
                .unwrap_or_else(|e| panic!("{name}/{}: {e}", cam.name));
            let inside =
                c.target.cmpge(b.min - margin).all() && c.target.cmple(b.max + margin).all();
            assert!(
                inside,
                "{name}/{}: target {} outside {b:?}",
                cam.name, c.target
            );
            for s in &solids {
                assert!(!s.contains(c.eye), "{name}/{}: eye inside {s:?}", cam.name);
            }
            assert_eq!(scene.camera(&cam.name).unwrap(), c);
        }
        assert_eq!(scene.default_camera(1.0), scene.cameras[0].camera);
    }
}

#[test]
fn tower_overview_looks_straight_down() {
    let scene = builtin("tower").unwrap();
    let c = scene.camera("overview").unwrap();
    assert_eq!(c.up, Vec3::NEG_Z);
    assert!(c.view_matrix().is_finite());
    assert!((c.forward() - Vec3::NEG_Y).length() < 1e-6);
}

#[test]
fn grass_blades_are_thin_and_many() {
    let scene = builtin("grass").unwrap();
    let blade_mats: Vec<u32> = (0..scene.materials.len() as u32)
        .filter(|&m| scene.materials[m as usize].double_sided)
        .collect();
    let blade_tris = scene
        .triangle_materials
        .iter()
        .filter(|m| blade_mats.contains(m))
        .count();
    assert_eq!(blade_tris, 4000 * 3);
    // Zero thickness and at most 12 mm wide at the root: every blade triangle's extent across
    // the blade is tiny compared with its height.
    for (t, m) in scene.triangles.iter().zip(&scene.triangle_materials) {
        if blade_mats.contains(m) {
            let [a, b, c] = t.map(|i| scene.positions[i as usize]);
            let width = (a - b).length().min((b - c).length()).min((c - a).length());
            assert!(width <= 0.0121, "blade triangle {t:?} is {width} m wide");
        }
    }
}

#[test]
fn closeups_show_a_silhouette_against_a_farther_surface() {
    // The close-up's purpose (halo test): somewhere in the image a near surface borders one at
    // least 1.5x farther away, most of the image shows geometry (not sky), and nothing is cut
    // open by a near plane at 5 cm.
    for &name in builtin_names() {
        let scene = build_ok(name).0;
        let cam = scene.cameras[0].camera;
        let (w, h) = (64, 48);
        let depth: Vec<Option<(f32, u32)>> = render(&scene, &cam, w, h);
        let hits = depth.iter().flatten().count();
        assert!(
            hits > w * h * 6 / 10,
            "{name}: only {hits} of {} pixels hit",
            w * h
        );
        let nearest = depth
            .iter()
            .flatten()
            .map(|d| d.0)
            .fold(f32::INFINITY, f32::min);
        assert!(nearest > 0.05, "{name}: geometry {nearest} m from the eye");
        let mut edges = 0;
        for y in 0..h {
            for x in 1..w {
                if let (Some(a), Some(b)) = (depth[y * w + x - 1], depth[y * w + x]) {
                    if a.0.max(b.0) > 1.5 * a.0.min(b.0) {
                        edges += 1;
                    }
                }
            }
        }
        println!("{name}: {hits} hits, nearest {nearest:.2} m, {edges} silhouette pixels");
        assert!(edges >= 8, "{name}: close-up has {edges} silhouette pixels");
    }
}

/// Writes shaded previews of every camera of every built-in as PNG (for eyeballing camera
/// placement): `OBSCURA_PREVIEW_DIR=/tmp/p cargo test --release -- --ignored previews`.
#[test]
#[ignore]
fn previews() {
    let dir = std::env::var("OBSCURA_PREVIEW_DIR").unwrap_or("/tmp/obscura-previews".into());
    std::fs::create_dir_all(&dir).unwrap();
    let (w, h) = (320, 240);
    for &name in builtin_names() {
        // One sheet per scene, its cameras side by side.
        let scene = build_ok(name).0;
        let mut sheet = image::RgbImage::new((w * scene.cameras.len()) as u32, h as u32);
        for (c, cam) in scene.cameras.iter().enumerate() {
            let hits = render(&scene, &cam.camera, w, h);
            for (i, hit) in hits.iter().enumerate() {
                let rgb = hit.map_or([30, 30, 40], |(_, packed)| {
                    let [r, g, b, _] = packed.to_le_bytes();
                    [r, g, b]
                });
                let (x, y) = ((c * w + i % w) as u32, (i / w) as u32);
                sheet.put_pixel(x, y, image::Rgb(rgb));
            }
        }
        let path = format!("{dir}/{name}.png");
        sheet.save(&path).unwrap();
        println!("wrote {path}");
    }
}

/// Per pixel: linear depth and a packed shaded colour of the nearest hit (two-sided).
fn render(scene: &Scene, cam: &Camera, w: usize, h: usize) -> Vec<Option<(f32, u32)>> {
    let f = cam.forward();
    let r = f.cross(cam.up).normalize();
    let u = r.cross(f);
    let tan = (0.5 * cam.fov_y_deg.to_radians()).tan();
    let aspect = w as f32 / h as f32;
    let tris: Vec<[Vec3; 3]> = scene
        .triangles
        .iter()
        .map(|t| t.map(|i| scene.positions[i as usize]))
        .collect();
    let mut out = Vec::with_capacity(w * h);
    for y in 0..h {
        for x in 0..w {
            let ndc = Vec2::new(
                ((x as f32 + 0.5) / w as f32 * 2.0 - 1.0) * aspect * tan,
                (1.0 - (y as f32 + 0.5) / h as f32 * 2.0) * tan,
            );
            let dir = (f + r * ndc.x + u * ndc.y).normalize();
            let mut best: Option<(f32, usize)> = None;
            for (i, tri) in tris.iter().enumerate() {
                if let Some(t) = intersect(cam.eye, dir, tri) {
                    if best.is_none_or(|(bt, _)| t < bt) {
                        best = Some((t, i));
                    }
                }
            }
            out.push(best.map(|(t, i)| {
                let [a, b, c] = tris[i];
                let n = (b - a).cross(c - a).normalize_or_zero();
                let light = 0.25 + 0.75 * n.dot(dir).abs();
                let col = scene.materials[scene.triangle_materials[i] as usize].base_color;
                let px = |c: f32| ((c * light).clamp(0.0, 1.0).powf(1.0 / 2.2) * 255.0) as u32;
                (
                    t * dir.dot(f),
                    px(col[0]) | px(col[1]) << 8 | px(col[2]) << 16,
                )
            }));
        }
    }
    out
}

/// Möller–Trumbore, both sides; distance along `dir`.
fn intersect(o: Vec3, dir: Vec3, [a, b, c]: &[Vec3; 3]) -> Option<f32> {
    let (e1, e2) = (*b - *a, *c - *a);
    let p = dir.cross(e2);
    let det = e1.dot(p);
    if det.abs() < 1e-12 {
        return None;
    }
    let s = o - *a;
    let u = s.dot(p) / det;
    let q = s.cross(e1);
    let v = dir.dot(q) / det;
    let t = e2.dot(q) / det;
    (u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t > 1e-4).then_some(t)
}

#[test]
fn layers_can_have_fewer_shells() {
    let all = builtin("layers").unwrap();
    let five = super::layers_with_shells(5).unwrap();
    assert_eq!(
        super::layers_with_shells(10).unwrap().triangles,
        all.triangles
    );
    assert!(five.triangle_count() < all.triangle_count());
    assert_eq!(five.cameras, all.cameras);
    for bad in [0, 11] {
        let err = super::layers_with_shells(bad).unwrap_err().to_string();
        assert!(err.contains(&format!("{bad} shells")), "{err}");
    }
}

#[test]
fn every_builtin_has_a_path_that_stays_outside_solids() {
    for &name in builtin_names() {
        let (scene, solids) = build_ok(name);
        assert!(!scene.paths.is_empty(), "{name}: no camera path");
        let b = scene.bounds();
        for path in &scene.paths {
            let frames = path
                .sample(64)
                .unwrap_or_else(|e| panic!("{name}/{}: {e}", path.name));
            for (t, c) in frames {
                assert!(
                    c.eye.cmpge(b.min).all() && c.eye.cmple(b.max).all()
                        || c.eye.distance(b.center()) < b.diagonal(),
                    "{name}/{} t = {t}: eye {} far from the scene",
                    path.name,
                    c.eye
                );
                for s in &solids {
                    assert!(
                        !s.contains(c.eye),
                        "{name}/{} t = {t}: eye {} inside {s:?}",
                        path.name,
                        c.eye
                    );
                }
            }
        }
    }
}
