//! The depth pyramid (seed 004 §3.3) and the two estimators that read it, SAO (McGuire et al.
//! 2012, seed 004 §2.2.2) and Pyramid HBAO (seed 004 §3): every level against the mean of its
//! children computed here, unoccluded planes, the closed forms of both models for a step seen from
//! above and at an inside corner (Pyramid HBAO's limit, SAO over exact geometry), plain CPU
//! implementations over the read-back depth and pyramid, and the hemisphere ground truth. The CPU
//! implementations are the estimators' mirrors, `estimators::sao::cpu_sao` and
//! `estimators::pyramid_hbao::cpu_pyramid_hbao`.

use crate::common::*;
use glam::{UVec2, Vec2, Vec3};
use obscura::estimators::mirror::Levels;
use obscura::estimators::pyramid_hbao::cpu_pyramid_hbao;
use obscura::estimators::pyramid_level_size;
use obscura::estimators::sao::{self, cpu_sao};
use obscura::scene;
use obscura::settings::{PyramidHbaoSettings, PyramidSettings, SaoSettings};
use obscura::{Renderer, Technique};
use std::f32::consts::{PI, TAU};

/// Level `l` from level `l − 1` (`below`, `size` texels) as build.wgsl makes it: the mean of the
/// K × K texels below each texel, background (≤ 0) left out, 0 if all are background.
fn cpu_level(below: &[f32], below_size: (u32, u32), size: (u32, u32), k: u32) -> Vec<f32> {
    let mut out = Vec::with_capacity((size.0 * size.1) as usize);
    for y in 0..size.1 {
        for x in 0..size.0 {
            let (mut sum, mut count) = (0.0f64, 0);
            for j in 0..k {
                for i in 0..k {
                    let (bx, by) = (x * k + i, y * k + j);
                    if bx < below_size.0 && by < below_size.1 {
                        let z = below[(by * below_size.0 + bx) as usize];
                        if z > 0.0 {
                            sum += f64::from(z);
                            count += 1;
                        }
                    }
                }
            }
            out.push(if count > 0 {
                (sum / count as f64) as f32
            } else {
                0.0
            });
        }
    }
    out
}

#[test]
fn every_level_is_the_mean_of_its_children() {
    let gpu = gpu();
    let scene = scene::builtin("colonnade").unwrap();
    for (levels, factor) in [(4, 3), (5, 2), (3, 4), (6, 4)] {
        let mut s = technique_settings(Technique::PyramidHbao, false);
        s.pyramid = PyramidSettings { levels, factor };
        let mut r = Renderer::new(&gpu, &scene, &s, 150, 94, 16).unwrap();
        r.render(&scene.cameras[0].camera, None).unwrap();
        let g = r.read_gbuffer().unwrap();
        let gpu_levels = r.read_depth_pyramid().unwrap().expect("a pyramid row");
        assert_eq!(gpu_levels.len(), levels as usize - 1);
        let full = (g.width, g.height);
        let mut below = g.depth.clone();
        for (l, got) in (1..levels).zip(&gpu_levels) {
            let size = pyramid_level_size(full, factor, l);
            let want = cpu_level(
                &below,
                pyramid_level_size(full, factor, l - 1),
                size,
                factor,
            );
            assert_eq!(got.len(), want.len(), "level {l} of K = {factor}");
            let mut geometry = 0;
            for (i, (&a, &b)) in got.iter().zip(&want).enumerate() {
                assert!(
                    (a - b).abs() <= 1e-5 * b.max(1.0),
                    "K = {factor}, level {l}, texel {i}: GPU {a} CPU {b}"
                );
                geometry += usize::from(b > 0.0);
            }
            assert!(geometry > want.len() / 2, "level {l} shows the scene");
            below = want;
        }
    }
}

#[test]
fn unoccluded_plane_is_one_everywhere() {
    // On a plane every sample lies on the tangent plane (level 0) or, at coarser levels, on or
    // behind it: a block's mean depth over a plane lies behind the plane at the block's centre
    // (depth is convex over a plane's pixels). Neither estimator occludes.
    let gpu = gpu();
    for blur in [false, true] {
        let mut settings = Vec::new();
        for (levels, factor, directions, steps) in [(5, 3, 8, 4), (3, 2, 4, 6), (1, 3, 8, 8)] {
            let mut s = technique_settings(Technique::PyramidHbao, blur);
            s.pyramid = PyramidSettings { levels, factor };
            (s.pyramid_hbao.directions, s.pyramid_hbao.steps) = (directions, steps);
            settings.push(s);
        }
        for (levels, samples) in [(5, 11), (3, 32), (1, 7)] {
            let mut s = technique_settings(Technique::Sao, blur);
            s.pyramid.levels = levels;
            s.sao.samples = samples;
            settings.push(s);
        }
        for s in settings {
            let ao = tilted_floor_ao(&gpu, &s);
            let min = ao.iter().copied().fold(f32::MAX, f32::min);
            assert!(
                min > 1.0 - 1e-3,
                "{} {:?} {:?} {:?}, blur {blur}: min AO {min}",
                s.technique,
                s.pyramid,
                s.pyramid_hbao,
                s.sao
            );
        }
    }
}

// ------------------------------------------------------------------------ closed forms

/// Pyramid HBAO's model (Eq. 8) for a floor point `d` before a step of height `h`, seen from above
/// (normal up), on level 0 with 1-px steps reaching `reach` world units: towards the step
/// (|θ| < π/2) the largest W(ρ)·sin α over the block's top is at its edge, horizontal distance
/// r_e = d/cos θ if within reach, ρ_e = √(h² + r_e²), sin α = h/ρ_e (farther points are lower and
/// weigh less); the floor adds nothing. AO = 1 − (1/2π) ∫ over directions.
fn pyramid_hbao_step_closed_form(d: f32, h: f32, s: &PyramidHbaoSettings, reach: f32) -> f32 {
    let n = 4000;
    let occlusion: f32 = (0..n)
        .map(|i| {
            let theta = -PI / 2.0 + (i as f32 + 0.5) * PI / n as f32;
            let edge = d / theta.cos();
            let rho = (h * h + edge * edge).sqrt();
            let w = if edge <= reach {
                (1.0 - rho / s.radius).max(0.0)
            } else {
                0.0
            };
            w * h / rho
        })
        .sum::<f32>()
        * PI
        / n as f32;
    1.0 - occlusion / TAU
}

/// SAO's model for the same point on level 0, for the taps of visible pixel `pixel`: tap i at
/// α_i = (i + 0.5)/N of the radius (horizontal distance α_i R: the view looks straight down) and
/// angle 2π·α_i·τ + φ (φ the pixel's Bayer rotation; view x is world x); a tap on the block's
/// top (α_i R cos θ > d) has v·n = h and v·v = (α_i R)² + h² and adds
/// (R² − v·v)³ (h − β)/(v·v + ε); A = max(0, 1 − σR/R⁶ · 5/N · Σ). Per pixel, as the
/// clamp is not linear.
fn sao_step_closed_form(d: f32, h: f32, s: &SaoSettings, pixel: UVec2) -> f32 {
    let (c, sn, _) = obscura::estimators::bayer_pattern(pixel.x, pixel.y, TAU);
    let phi = sn.atan2(c);
    let r = s.radius;
    let n = s.samples as f32;
    let sum: f32 = (0..s.samples)
        .map(|i| {
            let alpha = (i as f32 + 0.5) / n;
            let theta = alpha * TAU * s.spiral_turns + phi;
            if alpha * r * theta.cos() <= d {
                return 0.0;
            }
            let vv = (alpha * r).powi(2) + h * h;
            let f = (r * r - vv).max(0.0);
            f * f * f * ((h - s.bias) / (sao::epsilon(s.radius) + vv)).max(0.0)
        })
        .sum();
    (1.0 - sao::obscurance_scale(s, r) * sum).max(0.0)
}

#[test]
fn a_step_seen_from_above_matches_each_models_closed_form() {
    // Level 0 only (the closed forms are of the models, not of the pyramid's coarsening, which
    // every_level_is_the_mean_of_its_children checks); fine sampling; the centre block's 16
    // pattern entries average the rotations.
    for (d, h) in [(0.08, 0.1), (0.1, 0.2), (0.14, 0.1)] {
        let mut s = technique_settings(Technique::PyramidHbao, false);
        s.pyramid.levels = 1;
        (s.pyramid_hbao.directions, s.pyramid_hbao.steps) = (16, 16);
        // Steps o, 1 + o, …, 15 + o px (o in [0, 1) per direction): the reach is 15.5 px on
        // average, 0.23 m; the edge lies within it for |θ| ≲ 60° and beyond it the weight is small.
        let reach = 15.5 * step_pixel_size();
        let (got, want) = step_ao(&s, d, h, |d, _| {
            pyramid_hbao_step_closed_form(d, h, &s.pyramid_hbao, reach)
        });
        println!("pyramid-hbao step d {d} h {h}: GPU {got:.4}, closed form {want:.4}");
        assert!(want < 0.97, "the configuration must occlude: {want}");
        assert!(
            (got - want).abs() < 0.03,
            "pyramid-hbao d {d} h {h}: {got} vs {want}"
        );

        let mut s = technique_settings(Technique::Sao, false);
        s.pyramid.levels = 1;
        // Less intensity than the default, so that the clamp at 0 does not hide the comparison
        // (σR = 0.2 at R = 0.5).
        (s.sao.samples, s.sao.intensity) = (64, 0.4);
        let (got, want) = step_ao(&s, d, h, |d, pixel| {
            sao_step_closed_form(d, h, &s.sao, pixel)
        });
        println!("sao step d {d} h {h}: GPU {got:.4}, closed form {want:.4}");
        assert!(
            (got - want).abs() < 0.03,
            "sao d {d} h {h}: {got} vs {want}"
        );
    }
}

#[test]
fn gpu_matches_the_cpu_implementations() {
    let gpu = gpu();
    for name in ["stairs", "colonnade"] {
        let scene = scene::builtin(name).unwrap();
        let mut ph = technique_settings(Technique::PyramidHbao, false);
        ph.pyramid = PyramidSettings {
            levels: 4,
            factor: 3,
        };
        (ph.pyramid_hbao.directions, ph.pyramid_hbao.steps) = (6, 3);
        let mut sa = technique_settings(Technique::Sao, false);
        sa.pyramid = PyramidSettings {
            levels: 4,
            factor: 2,
        };
        sa.sao.radius = 1.5;
        for s in [ph, sa] {
            let mut r = Renderer::new(&gpu, &scene, &s, 160, 96, 16).unwrap();
            r.render(&scene.cameras[0].camera, None).unwrap();
            let gpu_ao = r.read_raw_ao().unwrap();
            let g = r.read_gbuffer().unwrap();
            let screen = r.view().unwrap().screen();
            let pyramid = r.read_depth_pyramid().unwrap().unwrap();
            let levels = Levels {
                g: &g,
                screen: &screen,
                pyramid: &pyramid,
                factor: s.pyramid.factor,
            };
            let cpu = match s.technique {
                Technique::Sao => cpu_sao(&levels, &s.sao, s.pyramid.levels),
                _ => cpu_pyramid_hbao(&levels, &s.pyramid_hbao, s.pyramid.levels),
            };
            assert_mirrors(&format!("{name} {}", s.technique), &gpu_ao, cpu);
        }
    }
}

#[test]
fn closer_to_the_hemisphere_ground_truth_than_no_occlusion() {
    let gpu = gpu();
    assert_beats_no_occlusion(&gpu, Technique::PyramidHbao, |s| s.pyramid_hbao.radius);
    assert_beats_no_occlusion(&gpu, Technique::Sao, |s| s.sao.radius);
}

/// Pyramid HBAO's model at the corner point itself on level 0, in the limit of near samples: in
/// screen direction θ, where the floor's line (in the slice of V and θ) runs into the wall, the
/// samples lie on the wall's line w, all at sin α = n·w above the floor's tangent plane, the
/// nearest at distance → 0 (W → 1): A(θ) = n·w (Eq. 8). Elsewhere the floor adds nothing.
/// AO = 1 − (1/2π) ∫ A(θ) dθ.
fn pyramid_hbao_corner_limit(view: glam::Mat4) -> f32 {
    let n = 4000;
    let mut occlusion = 0.0;
    for i in 0..n {
        let c = corner_slice(view, (i as f32 + 0.5) / n as f32 * TAU);
        if c.into_wall {
            occlusion += c.floor_n.dot(c.wall_line).max(0.0);
        }
    }
    1.0 - occlusion / n as f32
}

#[test]
fn pyramid_hbao_at_an_inside_corner_matches_its_models_limit() {
    // Level 0 only, 1-px steps, many directions, a radius large against the corner pixels' 2 cm
    // (measured: 0.669 against the limit 0.664).
    let mut s = technique_settings(Technique::PyramidHbao, false);
    s.pyramid.levels = 1;
    (
        s.pyramid_hbao.directions,
        s.pyramid_hbao.steps,
        s.pyramid_hbao.radius,
    ) = (16, 16, 2.0);
    let (mean, count, view) = corner_ao(&s);
    let want = pyramid_hbao_corner_limit(view);
    println!(
        "pyramid-hbao at the inside corner: mean AO {mean:.4} over {count} pixels, limit {want:.4}"
    );
    assert!(want < 0.8, "the corner must occlude: {want}");
    assert!((mean - want).abs() < 0.04, "{mean} vs {want}");
}

#[test]
fn sao_at_an_inside_corner_matches_its_model_with_exact_geometry() {
    // Level 0 only; per corner pixel, its own taps evaluated on the exact floor and wall (each
    // tap's camera ray cast against both planes) instead of the pixel-snapped G-buffer (measured:
    // 0.366 against 0.377).
    let mut s = technique_settings(Technique::Sao, false);
    s.pyramid.levels = 1;
    // SAO's intensity saturates at a corner (A = 0 for model and kernel alike): a lower one
    // keeps the comparison in range (σR = 0.3 at R = 0.5).
    s.sao.intensity = 0.6;
    let sa = s.sao;
    let (got, want, count, _) = corner_ao_and_model(&s, |pixel, corner| {
        let centre = (pixel + corner.screen.guard_band).as_vec2() + 0.5;
        let (p, n) = corner
            .surface(centre)
            .expect("the corner pixel sees the floor");
        let radius_px = sa.radius * corner.screen.uniform().projection_scale[1] / -p.z;
        let (c, sn, _) = obscura::estimators::bayer_pattern(pixel.x, pixel.y, TAU);
        let rotation = sn.atan2(c);
        let taps = sa.samples as f32;
        let mut sum = 0.0;
        for i in 0..sa.samples {
            let alpha = (i as f32 + 0.5) / taps;
            let angle = alpha * TAU * sa.spiral_turns + rotation;
            let px = centre + Vec2::new(angle.cos(), -angle.sin()) * (alpha * radius_px);
            if let Some((q, _)) = corner.surface(px) {
                let v = q - p;
                let vv = v.dot(v);
                let f = (sa.radius * sa.radius - vv).max(0.0);
                sum += f * f * f * ((v.dot(n) - sa.bias) / (sao::epsilon(sa.radius) + vv)).max(0.0);
            }
        }
        (1.0 - sum * sao::obscurance_scale(&sa, sa.radius)).max(0.0)
    });
    println!("sao at the inside corner: GPU {got:.4}, model {want:.4} over {count} pixels");
    assert!(
        want > 0.1 && want < 0.9,
        "the corner must occlude, unsaturated: {want}"
    );
    assert!((got - want).abs() < 0.05, "{got} vs {want}");
}

#[test]
fn debug_images_show_the_levels_read() {
    // `render --debug-out`: SAO's mean tap level follows from each pixel's radius alone (the
    // level formula of cpu_sao); Pyramid HBAO's directions find nothing on a plane (level 0) and
    // their largest contributions on coarser levels beside a step.
    let gpu = gpu();
    let plane = quads("floor", &[floor(100.0)]);
    let view = obscura::scene::Camera {
        eye: Vec3::new(0.0, 20.0, 0.0),
        target: Vec3::ZERO,
        up: Vec3::NEG_Z,
        fov_y_deg: 4.0,
    };
    let debug = |s: &obscura::AoSettings, scene: &obscura::scene::Scene| {
        let mut r = Renderer::new(&gpu, scene, s, 48, 48, 16).unwrap();
        r.render(&view, None).unwrap();
        let image = r.read_estimator_debug().unwrap().expect("a debug image");
        let radius_px = {
            let screen = r.view().unwrap().screen();
            s.sao.radius * screen.uniform().projection_scale[1] / 20.0
        };
        (image.iter().sum::<f32>() / image.len() as f32, radius_px)
    };
    // A radius of 68 px: taps from level 0 to level 2.
    let mut s = technique_settings(Technique::Sao, false);
    s.sao.radius = 2.0;
    let (mean, radius_px) = debug(&s, &plane);
    let levels = s.pyramid.levels;
    let want = (0..s.sao.samples)
        .map(|i| {
            let distance = (i as f32 + 0.5) / s.sao.samples as f32 * radius_px;
            let exact = (distance.max(1.0).ln() - sao::LEVEL_OFFSET_PX.ln())
                / (s.pyramid.factor as f32).ln();
            exact.floor().clamp(0.0, (levels - 1) as f32)
        })
        .sum::<f32>()
        / (s.sao.samples * (levels - 1)) as f32;
    println!("sao levels: mean {mean:.4}, from the radius {want:.4}");
    assert!(want > 0.0 && (mean - want).abs() < 1e-4, "{mean} vs {want}");

    let s = technique_settings(Technique::PyramidHbao, false);
    let (on_plane, _) = debug(&s, &plane);
    let (at_step, _) = debug(&s, &step_scene(0.3, 0.5));
    println!("pyramid-hbao levels: plane {on_plane:.4}, step {at_step:.4}");
    assert_eq!(on_plane, 0.0);
    assert!(at_step > 0.05, "{at_step}");
}
