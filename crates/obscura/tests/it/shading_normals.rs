//! `Normals::Shading`: the G-buffer and the reference (CPU and GPU) compute AO around the same
//! interpolated vertex normals, and `Normals::Face` ignores them. The sphere is coarse (16 × 8
//! facets) so that face and shading normals differ by up to ~11°.

use crate::common::*;
use glam::{UVec2, Vec2, Vec3};
use obscura::bvh::Bvh;
use obscura::reference::gpu::render_reference_gpu;
use obscura::reference::ground_truth::{
    render_reference, ReferenceModel, ReferenceSettings, Tracer,
};
use obscura::scene::{Normals, Scene};
use obscura::{AoSettings, FrameView, Renderer};

/// A unit UV sphere centred at (0, 1, 0) with its exact normals as vertex normals, resting on a
/// floor (which has none: it keeps its face normal either way).
fn sphere_on_floor(normals: Normals) -> Scene {
    let mut scene = quads("sphere", &[floor(10.0)]);
    scene.normals = vec![Vec3::ZERO; scene.positions.len()];
    let (segments, rings) = (16u32, 8u32);
    let base = scene.positions.len() as u32;
    for r in 0..=rings {
        let theta = std::f32::consts::PI * r as f32 / rings as f32;
        for s in 0..=segments {
            let phi = std::f32::consts::TAU * s as f32 / segments as f32;
            let n = Vec3::new(
                theta.sin() * phi.cos(),
                theta.cos(),
                theta.sin() * phi.sin(),
            );
            scene.positions.push(n + Vec3::Y);
            scene.uvs.push(Vec2::ZERO);
            scene.normals.push(n);
        }
    }
    let row = segments + 1;
    for r in 0..rings {
        for s in 0..segments {
            let v = base + r * row + s;
            // Counter-clockwise seen from outside.
            for tri in [[v, v + 1, v + row], [v + 1, v + row + 1, v + row]] {
                scene.triangles.push(tri);
                scene.triangle_materials.push(0);
            }
        }
    }
    scene.validate().unwrap();
    scene.set_normals(normals);
    scene
}

fn view_camera() -> obscura::scene::Camera {
    camera(Vec3::new(0.4, 2.2, 3.0), Vec3::new(0.0, 0.8, 0.0), 50.0)
}

const W: u32 = 64;
const H: u32 = 48;

/// G-buffer normals (view space, visible pixels) of `scene`.
fn gbuffer_normals(scene: &Scene) -> (Vec<Vec3>, FrameView) {
    let gpu = gpu();
    let mut r = Renderer::new(&gpu, scene, &AoSettings::default(), W, H, 0).unwrap();
    r.render(&view_camera(), None).unwrap();
    (r.read_gbuffer().unwrap().normals, *r.view().unwrap())
}

#[test]
fn gbuffer_interpolates_the_vertex_normals_the_tracer_does() {
    let shading = sphere_on_floor(Normals::Shading);
    let (gpu_normals, view) = gbuffer_normals(&shading);
    let bvh = Bvh::build(&shading);
    let tracer = Tracer::new(&shading, &bvh, view);
    let to_view = view.view_matrix();
    let (mut sphere_pixels, mut worst) = (0, 0.0f32);
    let mut face_vs_shading = 0.0f32;
    let face = sphere_on_floor(Normals::Face);
    let (face_normals, _) = gbuffer_normals(&face);
    for y in 0..H {
        for x in 0..W {
            let p = UVec2::new(x, y);
            let ray = tracer.camera_ray(p.as_vec2() + 0.5);
            let Some(hit) = tracer.first_surface(&ray) else {
                continue;
            };
            if hit.world.y < 0.05 {
                continue; // the floor
            }
            let i = (y * W + x) as usize;
            let expected = to_view.transform_vector3(hit.normal);
            worst = worst.max(gpu_normals[i].angle_between(expected));
            face_vs_shading = face_vs_shading.max(face_normals[i].angle_between(expected));
            sphere_pixels += 1;
        }
    }
    assert!(sphere_pixels > 300, "only {sphere_pixels} sphere pixels");
    // Shading normals are continuous across edges, so raster and ray agree even where they pick
    // neighbouring triangles; the bound covers the normal target's 16-bit floats.
    assert!(
        worst < 4e-3,
        "G-buffer vs tracer shading normal: {worst} rad"
    );
    assert!(
        face_vs_shading > 0.1,
        "face normals should differ from shading normals on a coarse sphere ({face_vs_shading} rad)"
    );
}

#[test]
fn face_normals_ignore_vertex_normals() {
    let face = sphere_on_floor(Normals::Face);
    let mut without = face.clone();
    without.normals.clear();
    assert_eq!(face.fingerprint(), without.fingerprint());
    let (a, _) = gbuffer_normals(&face);
    let (b, _) = gbuffer_normals(&without);
    assert_eq!(a, b, "Normals::Face must not read vertex normals");
}

/// A floor whose vertex normals all lean α = 60° from +y towards +x. Around the leaning normal
/// the floor itself hides the part of the cosine-weighted hemisphere below its plane: the view
/// factor of a plane tilted by α, (1 − cos α)/2. So the hemisphere AO is (1 + cos α)/2 = 0.75
/// with shading normals (every downward ray meets the floor within any R), and 1 with face normals.
#[test]
fn the_reference_computes_ao_around_the_shading_normal() {
    let gpu = gpu();
    let alpha = 60f32.to_radians();
    let lean = Vec3::new(alpha.sin(), alpha.cos(), 0.0);
    let settings = ReferenceSettings {
        model: ReferenceModel::Hemisphere,
        spp: 256,
        ..Default::default()
    };
    let cam = camera(Vec3::new(0.0, 2.0, 3.0), Vec3::ZERO, 50.0);
    let view = FrameView::new(cam, 32, 24, 0, 0.05);
    for (normals, expected) in [
        (Normals::Shading, (1.0 + alpha.cos()) / 2.0),
        (Normals::Face, 1.0),
    ] {
        let mut scene = quads("leaning normals", &[floor(10.0)]);
        scene.normals = vec![lean; 4];
        scene.set_normals(normals);
        let bvh = Bvh::build(&scene);
        let cpu = render_reference(&scene, &bvh, view, &settings, &|_| {});
        let (on_gpu, _) =
            render_reference_gpu(&gpu, &scene, &bvh, view, &settings, &|_, _| {}).unwrap();
        for (what, image) in [("CPU", &cpu), ("GPU", &on_gpu)] {
            let mean = image.iter().sum::<f32>() / image.len() as f32;
            let worst = image
                .iter()
                .map(|a| (a - expected).abs())
                .fold(0.0, f32::max);
            // 256 stratified rays: a pixel is within a few rays of the view factor.
            assert!(
                worst < 0.04 && (mean - expected).abs() < 0.01,
                "{normals:?} {what}: mean {mean}, worst error {worst}, expected {expected}"
            );
        }
    }
}
