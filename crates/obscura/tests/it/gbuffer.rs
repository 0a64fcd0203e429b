//! The G-buffer (a visibility buffer resolved in compute, src/raster/gbuffer.rs) against rays
//! through the pixel centres traced on the CPU: depth and normal of every pixel where both see the
//! same surface, on every built-in scene and camera.

use crate::common::*;
use glam::{UVec2, Vec3};
use obscura::bvh::Bvh;
use obscura::reference::ground_truth::Tracer;
use obscura::{scene, AoSettings, Renderer};

const W: u32 = 96;
const H: u32 = 64;
const GUARD: u32 = 8;

/// Per scene and camera: pixels compared, worst relative depth error and worst normal angle
/// (radians) where the rasteriser and the ray agree on the surface.
fn compare_with_rays(scene: &obscura::scene::Scene) -> Vec<(String, usize, f32, f32, usize)> {
    let gpu = gpu();
    let bvh = Bvh::build(scene);
    let mut out = Vec::new();
    // One renderer for every camera, and a frame of another view first: the visibility target is
    // never cleared (src/raster/gbuffer.rs), so each camera's background pixels hold the triangles
    // of the frame before, which must read as background.
    let mut r = Renderer::new(&gpu, scene, &AoSettings::default(), W, H, GUARD).unwrap();
    let mut other = scene.cameras.last().unwrap().camera;
    other.eye += (other.target - other.eye) * 0.5;
    r.render(&other, None).unwrap();
    for named in &scene.cameras {
        r.render(&named.camera, None).unwrap();
        let g = r.read_gbuffer().unwrap();
        let view = *r.view().unwrap();
        let tracer = Tracer::new(scene, &bvh, view);
        let to_view = view.view_matrix();
        let (mut compared, mut worst_depth, mut worst_angle, mut coverage_mismatches) =
            (0, 0.0f32, 0.0f32, 0);
        for y in 0..g.height {
            for x in 0..g.width {
                let i = (y * g.width + x) as usize;
                let ray = tracer.camera_ray(UVec2::new(x, y).as_vec2() + 0.5);
                let hit = tracer.first_surface(&ray);
                let (depth, normal) = (g.depth[i], g.normals[i]);
                let Some(hit) = hit else {
                    // A ray that misses may still graze a triangle's edge the rasteriser covers.
                    coverage_mismatches += usize::from(depth > 0.0);
                    continue;
                };
                if depth <= 0.0 || depth.is_nan() {
                    coverage_mismatches += 1;
                    continue;
                }
                let relative = (depth - hit.depth).abs() / hit.depth;
                let expected = to_view.transform_vector3(hit.normal);
                // Where the two pick different triangles (edges, coplanar overlaps) the values
                // legitimately differ; a surface is the same when depth agrees to 1e-3.
                if relative > 1e-3 {
                    coverage_mismatches += 1;
                    continue;
                }
                if expected.angle_between(normal) > 0.05 {
                    // Same depth, another plane: a crease where two faces meet.
                    continue;
                }
                worst_depth = worst_depth.max(relative);
                worst_angle = worst_angle.max(expected.angle_between(normal));
                compared += 1;
            }
        }
        out.push((
            named.name.clone(),
            compared,
            worst_depth,
            worst_angle,
            coverage_mismatches,
        ));
    }
    out
}

#[test]
fn gbuffer_depth_and_normals_are_the_pixel_centre_ray_hits() {
    for name in scene::builtin_names() {
        let scene = scene::builtin(name).unwrap();
        for (camera, compared, depth, angle, mismatches) in compare_with_rays(&scene) {
            println!(
                "{name}/{camera}: {compared} pixels, max relative depth error {depth:.2e}, \
                 max normal error {angle:.2e} rad, {mismatches} coverage mismatches"
            );
            let pixels = ((W + 2 * GUARD) * (H + 2 * GUARD)) as usize;
            assert!(compared > pixels / 10, "{name}/{camera}: {compared} pixels");
            // The resolve computes the point the ray hits; both are f32 (relative ~1e-7 each),
            // over depths that span two orders of magnitude.
            assert!(depth < 1e-5, "{name}/{camera}: depth error {depth}");
            // 16-bit float normals: 2^-11 relative per component.
            assert!(angle < 2e-3, "{name}/{camera}: normal error {angle} rad");
            // Raster and ray disagree only along edges: a pixel centre on a shared edge.
            assert!(
                mismatches <= pixels / 100,
                "{name}/{camera}: {mismatches} coverage mismatches"
            );
        }
    }
}

/// A triangle crossing the eye plane (one corner behind the camera) still resolves to the
/// ray's point: the resolve works in homogeneous clip space, never dividing by a corner's w.
#[test]
fn a_triangle_through_the_eye_plane_resolves_exactly() {
    let mut s = quads("floor through the eye plane", &[floor(50.0)]);
    s.cameras.clear();
    s.cameras.push(obscura::scene::NamedCamera {
        name: "low".into(),
        camera: camera(Vec3::new(0.0, 0.5, 0.0), Vec3::new(0.0, 0.0, -3.0), 70.0),
    });
    let results = compare_with_rays(&s);
    let (_, compared, depth, angle, mismatches) = &results[0];
    println!("{compared} pixels, depth {depth:.2e}, angle {angle:.2e}, {mismatches} mismatches");
    assert!(*compared > 1000 && *depth < 2e-5 && *angle < 2e-3 && *mismatches < 50);
}
