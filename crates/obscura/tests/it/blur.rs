//! The GPU bilateral blur against its CPU mirror, and the properties a depth-aware blur must have.

use crate::common::*;
use obscura::reference::cpu_blur::cpu_blur;
use obscura::{scene, AoSettings, Renderer};

#[test]
fn gpu_blur_matches_cpu_blur() {
    let gpu = gpu();
    // The last: seed 004's plain Gaussian (σ = 1.5, no depth weight) for Pyramid HBAO.
    for (name, radius, sharpness, sigma) in [
        ("stairs", 4, 16.0, None),
        ("colonnade", 4, 16.0, None),
        ("grass", 9, 16.0, None),
        ("stairs", 2, 0.0, Some(1.5)),
    ] {
        let scene = scene::builtin(name).unwrap();
        let mut settings = AoSettings::default();
        settings.blur.radius = radius;
        settings.blur.sharpness = sharpness;
        settings.blur.sigma = sigma;
        // Sizes that are not multiples of the 64-pixel runs, and a guard band smaller than the radius.
        let (w, h, band) = (150, 90, 8);
        let mut r = Renderer::new(&gpu, &scene, &settings, w, h, band).unwrap();
        r.render(&scene.cameras[0].camera, None).unwrap();
        let raw = r.read_raw_ao().unwrap();
        let blurred = r.read_ao().unwrap();
        let g = r.read_gbuffer().unwrap();
        let cpu = cpu_blur(&raw, &g, &r.view().unwrap().screen(), &settings.blur);
        let worst = max_abs_diff(&blurred, &cpu);
        assert!(worst < 1e-4, "{name}: max |GPU-CPU| {worst}");
        assert_ne!(raw, blurred, "{name}: the blur must change the noisy AO");
    }
}

#[test]
fn blur_keeps_a_depth_edge() {
    // A square 0.6 m in front of a wall darkens the wall around it (inside (1+τ)R = 0.75 m) but is
    // itself an unoccluded plane: its pixels must stay 1 after the blur, taking nothing from the
    // dark wall pixels next to them.
    let gpu = gpu();
    let near = [
        glam::Vec3::new(-0.5, -0.5, -1.0),
        glam::Vec3::new(0.5, -0.5, -1.0),
        glam::Vec3::new(0.5, 0.5, -1.0),
        glam::Vec3::new(-0.5, 0.5, -1.0),
    ];
    let far = [
        glam::Vec3::new(-5.0, -5.0, -1.6),
        glam::Vec3::new(5.0, -5.0, -1.6),
        glam::Vec3::new(5.0, 5.0, -1.6),
        glam::Vec3::new(-5.0, 5.0, -1.6),
    ];
    let scene = quads("edge", &[near, far]);
    let settings = AoSettings::default();
    let mut r = Renderer::new(&gpu, &scene, &settings, 64, 64, 16).unwrap();
    r.render(
        &camera(
            glam::Vec3::new(0.0, 0.0, 1.0),
            glam::Vec3::new(0.0, 0.0, -1.0),
            60.0,
        ),
        None,
    )
    .unwrap();
    let raw = r.read_raw_ao().unwrap();
    let blurred = r.read_ao().unwrap();
    let g = r.read_gbuffer().unwrap();
    let mut near_pixels = 0;
    for y in 0..64u32 {
        for x in 0..64u32 {
            let z = g.depth[((y + 16) * g.width + x + 16) as usize];
            if (z - 2.0).abs() < 0.01 {
                near_pixels += 1;
                // The near square is a flat unoccluded plane: 1 before and after the blur.
                let i = (y * 64 + x) as usize;
                assert!(
                    raw[i] > 0.999 && blurred[i] > 0.999,
                    "({x},{y}) raw {} blurred {}",
                    raw[i],
                    blurred[i]
                );
            }
        }
    }
    assert!(near_pixels > 100);
    // The wall around the square is darkened (the square occludes it) and stays so.
    assert!(blurred.iter().any(|&v| v < 0.9));
}
