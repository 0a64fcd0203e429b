//! Issue 62, defect 4: a scene far from its file's origin. At 10^7 m a 32-bit float keeps about
//! 1 m, so a 5 m scene lost its shape, its camera's eye and target became "the same point", and
//! an explicit camera saw AO = 1 everywhere. The loader re-centres such a scene in f64 and
//! `Scene::from_file_point` moves points given in the file's coordinates with it: the same scene
//! 10^7 m away renders as it does at the origin.

use crate::common;

use glam::{DVec3, Vec3};
use obscura::scene::{self, Camera, Scene};
use obscura::{AoSettings, Renderer};

const W: u32 = 80;
const H: u32 = 48;
const GUARD: u32 = 12;

/// A 4 m floor with a 1 m box on it, moved by `shift`, as OBJ text (f64 digits).
fn floor_and_box(shift: DVec3) -> String {
    let mut obj = String::new();
    let mut quad = |corners: [[f64; 3]; 4]| {
        for c in corners {
            let p = DVec3::from_array(c) + shift;
            obj += &format!("v {:.6} {:.6} {:.6}\n", p.x, p.y, p.z);
        }
        obj += "f -4 -3 -2 -1\n";
    };
    quad([[-2., 0., -2.], [-2., 0., 2.], [2., 0., 2.], [2., 0., -2.]]);
    let (a, b) = (-0.5, 0.5);
    quad([[a, 1., a], [a, 1., b], [b, 1., b], [b, 1., a]]);
    quad([[a, 0., b], [b, 0., b], [b, 1., b], [a, 1., b]]);
    quad([[a, 0., a], [a, 1., a], [b, 1., a], [b, 0., a]]);
    quad([[a, 0., a], [a, 0., b], [a, 1., b], [a, 1., a]]);
    quad([[b, 0., a], [b, 1., a], [b, 1., b], [b, 0., b]]);
    obj
}

fn load(dir: &std::path::Path, name: &str, shift: DVec3) -> Scene {
    let path = dir.join(name);
    std::fs::write(&path, floor_and_box(shift)).unwrap();
    scene::load(path.to_str().unwrap()).unwrap()
}

fn render(gpu: &obscura::Gpu, scene: &Scene, camera: &Camera) -> Vec<f32> {
    let mut r = Renderer::new(gpu, scene, &AoSettings::default(), W, H, GUARD).unwrap();
    r.render(camera, None).unwrap();
    r.read_ao().unwrap()
}

fn assert_same(what: &str, near: &[f32], far: &[f32]) {
    let worst = near
        .iter()
        .zip(far)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0f32, f32::max);
    let occluded = near.iter().filter(|&&a| a < 0.9).count();
    println!("{what}: max difference {worst:.2e}, {occluded} occluded pixels at the origin");
    // Something must be occluded for the comparison to mean anything (AO = 1 everywhere was the
    // defect); the two differ by rounding only (vertices 1e-7 m apart after re-centring).
    assert!(occluded > 20, "{what}: {occluded} occluded pixels");
    assert!(worst < 0.02, "{what}: max difference {worst}");
}

#[test]
fn a_scene_far_from_the_origin_renders_as_at_the_origin() {
    let dir = tempfile::tempdir().unwrap();
    let shift = DVec3::new(1e7, 0.0, 1e7);
    let near = load(dir.path(), "near.obj", DVec3::ZERO);
    let far = load(dir.path(), "far.obj", shift);
    assert_eq!(near.origin, DVec3::ZERO);
    assert!(
        (far.origin - shift).abs().max_element() < 1.0,
        "{}",
        far.origin
    );
    let gpu = common::gpu();

    // Automatic framing: from the bounds, the same relative to each scene.
    let aspect = W as f32 / H as f32;
    let (a, b) = (near.default_camera(aspect), far.default_camera(aspect));
    assert_same(
        "auto framing",
        &render(&gpu, &near, &a),
        &render(&gpu, &far, &b),
    );

    // An explicit camera in the file's coordinates, 5.3 m from its target.
    let (eye, target) = (DVec3::new(3.0, 2.5, 4.0), DVec3::new(0.0, 0.3, 0.0));
    let camera = |s: &Scene, shift: DVec3| {
        let (e, t) = (
            s.from_file_point(eye + shift),
            s.from_file_point(target + shift),
        );
        Camera::new(e, t, 60.0).unwrap()
    };
    let (a, b) = (camera(&near, DVec3::ZERO), camera(&far, shift));
    // The far scene is the near one moved by shift − origin (a few metres): so is its camera.
    let moved: Vec3 = (shift - far.origin).as_vec3();
    assert!(
        (b.eye - a.eye - moved).length() < 1e-4,
        "{} {} {moved}",
        a.eye,
        b.eye
    );
    assert_same(
        "explicit camera",
        &render(&gpu, &near, &a),
        &render(&gpu, &far, &b),
    );
}
