//! Which faces count (`Sidedness`): an open mesh seen from behind occludes in the G-buffer, the
//! stochastic depth map and the reference (CPU and GPU) when double-sided, and not when its back
//! faces are culled. The scenes' occluders show the camera or the shaded point their back face.

use crate::common::*;
use glam::{Vec2, Vec3};
use obscura::bvh::Bvh;
use obscura::reference::gpu::render_reference_gpu;
use obscura::reference::ground_truth::{
    render_reference, ReferenceModel, ReferenceSettings, Tracer,
};
use obscura::scene::{Scene, Sidedness};
use obscura::settings::StochasticDepthSettings;
use obscura::{AoSettings, FrameView, Renderer, Technique};

const SIDES: [Sidedness; 2] = [Sidedness::DoubleSided, Sidedness::CullBackFaces];

/// A floor at y = 0 under a 10 × 8 m ceiling at y = 0.5 whose front faces up (+y): from the
/// floor and from the camera below it, only the ceiling's back face is seen.
fn floor_under_open_ceiling(sidedness: Sidedness) -> Scene {
    let y = 0.5;
    let ceiling = [
        Vec3::new(-5.0, y, -5.0),
        Vec3::new(-5.0, y, 3.0),
        Vec3::new(5.0, y, 3.0),
        Vec3::new(5.0, y, -5.0),
    ];
    let mut scene = quads("open ceiling", &[floor(20.0), ceiling]);
    scene.set_sidedness(sidedness);
    scene
}

/// Under the ceiling, looking at the floor point (0, 0, −1).
fn under_the_ceiling() -> obscura::scene::Camera {
    camera(Vec3::new(0.0, 0.3, 2.0), Vec3::new(0.0, 0.0, -1.0), 60.0)
}

#[test]
fn the_gbuffer_sees_a_back_face_only_when_double_sided() {
    let gpu = gpu();
    let (w, h) = (48, 32);
    // The top row looks up and meets the ceiling (found by the CPU tracer on the double-sided
    // scene); culled, the same pixel sees the floor far away, or nothing.
    let top = glam::UVec2::new(w / 2, 0);
    let view = FrameView::new(under_the_ceiling(), w, h, 0, 0.05);
    let double = floor_under_open_ceiling(Sidedness::DoubleSided);
    let bvh = Bvh::build(&double);
    let tracer = Tracer::new(&double, &bvh, view);
    let ceiling = tracer
        .first_surface(&tracer.camera_ray(top.as_vec2() + 0.5))
        .expect("the top row meets the ceiling");
    assert!((ceiling.world.y - 0.5).abs() < 1e-4, "{:?}", ceiling.world);
    for sidedness in SIDES {
        let scene = floor_under_open_ceiling(sidedness);
        let mut r = Renderer::new(&gpu, &scene, &AoSettings::default(), w, h, 0).unwrap();
        r.render(&under_the_ceiling(), None).unwrap();
        let depth = r.read_gbuffer().unwrap().depth_at(top);
        match sidedness {
            Sidedness::DoubleSided => assert!(
                (depth - ceiling.depth).abs() < 1e-3 * ceiling.depth,
                "{sidedness:?}: depth {depth}, the ceiling is at {}",
                ceiling.depth
            ),
            _ => assert!(
                depth == 0.0 || depth > 2.0 * ceiling.depth,
                "{sidedness:?}: the culled ceiling is seen at depth {depth}"
            ),
        }
    }
}

/// Cosine-weighted hemisphere AO at a floor point 0.5 below an infinite plane, radius 1: rays
/// reach the plane within R when cos θ > 0.5, and cos²θ is uniform under cosine weighting, so
/// the unoccluded fraction is P(cos²θ < 1/4) = 1/4.
const AO_UNDER_PLANE: f32 = 0.25;

#[test]
fn the_reference_is_occluded_by_a_back_face_only_when_double_sided() {
    let gpu = gpu();
    let (w, h) = (24, 16);
    let settings = ReferenceSettings {
        model: ReferenceModel::Hemisphere,
        spp: 256,
        vao: obscura::settings::VaoSettings {
            radius: 1.0,
            ..Default::default()
        },
        ..Default::default()
    };
    for sidedness in SIDES {
        let scene = floor_under_open_ceiling(sidedness);
        let bvh = Bvh::build(&scene);
        let view = FrameView::new(under_the_ceiling(), w, h, 0, 0.05);
        let cpu = render_reference(&scene, &bvh, view, &settings, &|_| {});
        let (gpu_image, _) =
            render_reference_gpu(&gpu, &scene, &bvh, view, &settings, &|_, _| {}).unwrap();
        let tracer = Tracer::new(&scene, &bvh, view);
        let expected = match sidedness {
            Sidedness::DoubleSided => AO_UNDER_PLANE,
            _ => 1.0,
        };
        let mut checked = 0;
        for y in 0..h {
            for x in 0..w {
                let px = Vec2::new(x as f32, y as f32) + 0.5;
                let Some(s) = tracer.first_surface(&tracer.camera_ray(px)) else {
                    continue;
                };
                // Floor points at least 1 m (the radius) inside the ceiling's edges.
                let p = s.world;
                if p.y.abs() > 1e-3 || p.x.abs() > 4.0 || !(-4.0..=2.0).contains(&p.z) {
                    continue;
                }
                let i = (y * w + x) as usize;
                for (what, image) in [("CPU", &cpu), ("GPU", &gpu_image)] {
                    assert!(
                        (image[i] - expected).abs() < 0.03,
                        "{sidedness:?} {what} reference at {p}: {} (expected {expected})",
                        image[i]
                    );
                }
                checked += 1;
            }
        }
        assert!(
            checked > 50,
            "only {checked} floor pixels under the ceiling"
        );
    }
}

#[test]
fn the_stochastic_depth_map_keeps_a_back_face_only_when_double_sided() {
    let gpu = gpu();
    // A camera-facing layer at depth 1 and, hidden behind it, a layer at depth 2 facing away
    // (its back face towards the camera). α = 1: every sample stores the hidden layer if it counts.
    let mut scene = quads("hidden back face", &[]);
    let front = |d: f32| {
        [
            Vec3::new(-4.0 * d, -4.0 * d, -d),
            Vec3::new(4.0 * d, -4.0 * d, -d),
            Vec3::new(4.0 * d, 4.0 * d, -d),
            Vec3::new(-4.0 * d, 4.0 * d, -d),
        ]
    };
    push_quad(&mut scene, front(1.0), 0);
    let mut back = front(2.0);
    back.reverse();
    push_quad(&mut scene, back, 0);
    let mut settings = AoSettings {
        technique: Technique::SdVao,
        stochastic_depth: StochasticDepthSettings {
            samples: 4,
            alpha: Some(1.0),
            ..Default::default()
        },
        ..Default::default()
    };
    settings.blur.enabled = false;
    let size = 32;
    for sidedness in SIDES {
        let mut scene = scene.clone();
        scene.set_sidedness(sidedness);
        let mut r = Renderer::new(&gpu, &scene, &settings, size, size, 0).unwrap();
        r.render(&camera(Vec3::ZERO, Vec3::NEG_Z, 60.0), None)
            .unwrap();
        let layers = r.read_stochastic_depth().unwrap().unwrap();
        let stored: Vec<f32> = layers.iter().flatten().copied().collect();
        let at_two = stored.iter().filter(|&&z| (z - 2.0).abs() < 1e-3).count();
        match sidedness {
            Sidedness::DoubleSided => assert_eq!(
                at_two,
                stored.len(),
                "{sidedness:?}: every sample should hold the hidden back face"
            ),
            _ => assert!(
                stored.iter().all(|&z| z == 0.0),
                "{sidedness:?}: the culled back face is stored ({at_two} samples at depth 2)"
            ),
        }
    }
}
