//! The classic horizon estimators, HBAO (seed 001 §3.2 Algorithm 2, seed 004 §2.2.1) and GTAO
//! (Jimenez et al. 2016 with XeGTAO's falloff), against values derived without the GPU kernels:
//! unoccluded planes, the closed forms of their models for a step seen from above and at an
//! inside corner, plain CPU implementations on read-back G-buffers (single pass and interleaved),
//! the hemisphere ground truth, and the debug images. The CPU implementations are the
//! estimators' mirrors, `estimators::hbao::cpu_hbao` and `estimators::gtao::cpu_gtao`.

use crate::common::*;
use glam::Vec3;
use obscura::estimators::gtao::{self, cpu_gtao};
use obscura::estimators::hbao::cpu_hbao;
use obscura::scene::{self, Camera};
use obscura::settings::{AoSettings, GtaoSettings, HbaoSettings};
use obscura::{Renderer, Technique};
use std::f32::consts::{FRAC_PI_2, PI};

#[test]
fn unoccluded_plane_is_one_everywhere() {
    // HBAO: every step lies on the tangent, below the biased starting horizon. GTAO: both
    // horizons lie on the tangent plane, and the clipped normalisation makes that exactly 1.
    let gpu = gpu();
    for blur in [false, true] {
        let mut settings = Vec::new();
        for (directions, steps) in [(8, 4), (4, 8), (16, 20)] {
            for t in [Technique::Hbao, Technique::HbaoInterleaved] {
                let mut s = technique_settings(t, blur);
                (s.hbao.directions, s.hbao.steps) = (directions, steps);
                settings.push(s);
            }
        }
        for (slices, steps, blend) in [(2, 2, 0.0), (3, 3, 0.5), (9, 3, 0.0), (1, 8, 1.0)] {
            let mut s = technique_settings(Technique::Gtao, blur);
            (s.gtao.slices, s.gtao.steps, s.gtao.thickness_blend) = (slices, steps, blend);
            settings.push(s);
        }
        for s in settings {
            let ao = tilted_floor_ao(&gpu, &s);
            let min = ao.iter().copied().fold(f32::MAX, f32::min);
            let max = ao.iter().copied().fold(f32::MIN, f32::max);
            assert!(
                min > 1.0 - 1e-3 && max < 1.0 + 1e-3,
                "{} {:?} {:?}, blur {blur}: AO in [{min}, {max}]",
                s.technique,
                s.hbao,
                s.gtao
            );
        }
    }
}

// ------------------------------------------------------------------------ closed forms

/// ∫ f(θ) dθ over (−π/2, π/2) by the midpoint rule.
fn integrate_half_circle(f: impl Fn(f32) -> f32) -> f32 {
    let n = 4000;
    let dt = PI / n as f32;
    (0..n)
        .map(|i| f(-FRAC_PI_2 + (i as f32 + 0.5) * dt))
        .sum::<f32>()
        * dt
}

/// HBAO's model for a floor point `d` before a step of height `h`, seen from above (normal = V,
/// tangent elevation 0), in the limit of fine steps: towards the step (|θ| < π/2) the horizon
/// rises once, at the step's edge r_e = d/cos θ, to sin φ = h/ρ with ρ = √(h² + r_e²), adding
/// W(ρ)·(sin φ − sin bias) (Algorithm 2, line 18); beyond the edge the block's top lies lower, and
/// the floor never rises above the bias. AO = 1 − (1/2π) ∫ over all directions.
fn hbao_step_closed_form(d: f32, h: f32, s: &HbaoSettings) -> f32 {
    let occlusion = integrate_half_circle(|theta| {
        let rho = (h * h + (d / theta.cos()).powi(2)).sqrt();
        let w = (1.0 - rho / s.radius).max(0.0);
        w * (h / rho - s.angle_bias.sin()).max(0.0)
    });
    1.0 - occlusion / (2.0 * PI)
}

/// GTAO's model for the same point: every slice has γ = 0 and |n_p| = 1; the side away from the
/// step keeps its horizon on the floor (visibility ½), the side towards it meets the edge, whose
/// weighted horizon cosine c = w(ρ)·h/ρ is the largest of the side (farther block points are lower
/// and weigh less), visibility ¼(1 − cos 2h) = (1 − c²)/2. The slice sees 1 − c²/2; slice angles
/// are uniform, so AO = 1 − (1/π) ∫_{−π/2}^{π/2} c²/2 dθ.
fn gtao_step_closed_form(d: f32, h: f32, s: &GtaoSettings) -> f32 {
    let loss = integrate_half_circle(|theta| {
        let rho = (h * h + (d / theta.cos()).powi(2)).sqrt();
        let c = gtao::falloff(rho, s.radius) * h / rho;
        c * c / 2.0
    });
    1.0 - loss / PI
}

#[test]
fn a_step_seen_from_above_matches_each_models_closed_form() {
    // Fine steps make the first sample past the edge land within a pixel of it; the centre
    // block's 16 patterns average the direction rotation. Pixel snapping leaves a hundredth or
    // two.
    for (d, h) in [(0.15, 0.2), (0.3, 0.3), (0.08, 0.4)] {
        let mut s = technique_settings(Technique::Hbao, false);
        (s.hbao.directions, s.hbao.steps, s.hbao.radius) = (16, 48, 1.0);
        let (got, want) = step_ao(&s, d, h, |d, _| hbao_step_closed_form(d, h, &s.hbao));
        println!("hbao step d {d} h {h}: GPU {got:.4}, closed form {want:.4}");
        assert!(want < 0.97, "the configuration must occlude: {want}");
        assert!(
            (got - want).abs() < 0.02,
            "hbao d {d} h {h}: {got} vs {want}"
        );

        let mut s = technique_settings(Technique::Gtao, false);
        (s.gtao.slices, s.gtao.steps) = (8, 24);
        let (got, want) = step_ao(&s, d, h, |d, _| gtao_step_closed_form(d, h, &s.gtao));
        println!("gtao step d {d} h {h}: GPU {got:.4}, closed form {want:.4}");
        assert!(want < 0.97, "the configuration must occlude: {want}");
        assert!(
            (got - want).abs() < 0.02,
            "gtao d {d} h {h}: {got} vs {want}"
        );
    }
}

#[test]
fn gtao_sees_half_the_cosine_weighted_hemisphere_at_an_inside_corner() {
    // At the corner the wall hides exactly half of the cosine-weighted hemisphere (every
    // direction towards it meets it), which GTAO's analytic inner integral recovers once the
    // horizons sit on the wall. Within 2 cm of the corner line (the first sample is 1.3 px out: the
    // horizon is a few degrees short of the wall).
    let mut s = technique_settings(Technique::Gtao, false);
    (s.gtao.slices, s.gtao.steps) = (8, 16);
    let (mean, count, _) = corner_ao(&s);
    println!("gtao at the inside corner: mean AO {mean:.4} over {count} pixels");
    assert!((mean - 0.5).abs() < 0.05, "{mean}");
}

/// HBAO's model at the corner point itself, in the limit of fine steps: in the slice of screen
/// direction θ (V and the direction made orthogonal to it, D), the floor's tangent t and the
/// wall's line meet the corner. Where the floor's line on the +D side runs into the wall (world
/// z < 0), the samples there lie on the wall's line, all at one elevation h, the first of them at
/// distance → 0 (W → 1): the direction adds sin h − sin(t + bias) if positive (Algorithm 2,
/// line 18). Elsewhere the floor adds nothing. AO = 1 − (1/2π) ∫ dθ. All in view space, V the
/// unit vector from the corner point to the camera.
fn hbao_corner_closed_form(view: glam::Mat4, s: &HbaoSettings) -> f32 {
    let n = 4000;
    let mut occlusion = 0.0;
    for i in 0..n {
        let c = corner_slice(view, (i as f32 + 0.5) / n as f32 * std::f32::consts::TAU);
        if !c.into_wall {
            continue;
        }
        let sin_t = c.floor_line.dot(c.v);
        let start = (sin_t.clamp(-1.0, 1.0).asin() + s.angle_bias)
            .min(FRAC_PI_2)
            .sin();
        occlusion += (c.wall_line.dot(c.v) - start).max(0.0);
    }
    1.0 - occlusion / n as f32
}

#[test]
fn hbao_at_an_inside_corner_matches_its_models_limit() {
    // Many directions and fine steps over a radius large against the pixels' 2 cm: the first wall
    // sample lies within a few millimetres, W ≈ 1 there (measured: 0.551 against the limit 0.537).
    let mut s = technique_settings(Technique::Hbao, false);
    (s.hbao.directions, s.hbao.steps, s.hbao.radius) = (16, 32, 2.0);
    let (mean, count, view) = corner_ao(&s);
    let want = hbao_corner_closed_form(view, &s.hbao);
    println!("hbao at the inside corner: mean AO {mean:.4} over {count} pixels, limit {want:.4}");
    assert!(want < 0.9, "the corner must occlude: {want}");
    assert!((mean - want).abs() < 0.04, "{mean} vs {want}");
}

#[test]
fn gpu_matches_the_cpu_implementations() {
    let gpu = gpu();
    for name in ["stairs", "colonnade"] {
        let scene = scene::builtin(name).unwrap();
        let mut hb = technique_settings(Technique::Hbao, false);
        (hb.hbao.directions, hb.hbao.steps) = (6, 5);
        let mut hbi = hb;
        hbi.technique = Technique::HbaoInterleaved;
        let mut gt = technique_settings(Technique::Gtao, false);
        (gt.gtao.slices, gt.gtao.steps, gt.gtao.thickness_blend) = (3, 3, 0.3);
        for s in [hb, hbi, gt] {
            let mut r = Renderer::new(&gpu, &scene, &s, 160, 96, 16).unwrap();
            r.render(&scene.cameras[0].camera, None).unwrap();
            let gpu_ao = r.read_raw_ao().unwrap();
            let g = r.read_gbuffer().unwrap();
            let screen = r.view().unwrap().screen();
            let cpu = match s.technique {
                Technique::Hbao => cpu_hbao(&g, &screen, &s.hbao, false),
                // The interleaved schedule: samples read their own residue class mod 4.
                Technique::HbaoInterleaved => cpu_hbao(&g, &screen, &s.hbao, true),
                _ => cpu_gtao(&g, &screen, &s.gtao),
            };
            assert_mirrors(&format!("{name} {}", s.technique), &gpu_ao, cpu);
        }
    }
}

#[test]
fn closer_to_the_hemisphere_ground_truth_than_no_occlusion() {
    let gpu = gpu();
    assert_beats_no_occlusion(&gpu, Technique::Hbao, |s| s.hbao.radius);
    assert_beats_no_occlusion(&gpu, Technique::Gtao, |s| s.gtao.radius);
}

#[test]
fn light_passes_behind_thin_geometry() {
    // Seed 003's claim for the visibility bitmask: with a constant thickness, light passes behind
    // thin surfaces (grass blades) that a horizon hides everything behind, so GTAO-VB darkens
    // less next to their silhouettes than GTAO does. Measured here as the report's dark halo
    // (mean excess occlusion within 4 px of depth jumps) against the hemisphere ground truth.
    // Whole-image MAE is printed, not asserted: on our grass views GTAO's MAE is the lower one
    // (both miss occlusion from hidden blades, GTAO-VB more, having let light through them).
    // GTAO's own thickness heuristic moves the same way: β = 0.5 lets horizons drop behind the
    // blades, less occlusion than β = 0.
    let gpu = gpu();
    let scene = scene::builtin("grass").unwrap();
    let mut gtao = technique_settings(Technique::Gtao, true);
    let mut vb = technique_settings(Technique::GtaoVb, true);
    // The same reach and sampling for both: 3 slices × 3 steps.
    (gtao.gtao.slices, gtao.gtao.steps) = (3, 3);
    (vb.gtao_vb.slices, vb.gtao_vb.steps) = (3, 3);
    vb.gtao_vb.radius = gtao::reach(gtao.gtao.radius);
    let (g, _) = hemisphere_metrics(&gpu, &scene, &gtao, gtao.gtao.radius);
    let (v, _) = hemisphere_metrics(&gpu, &scene, &vb, gtao.gtao.radius);
    println!(
        "grass: gtao MAE {:.4} dark halo {:.4}; gtao-vb MAE {:.4} dark halo {:.4}",
        g.mae, g.halo_dark, v.mae, v.halo_dark
    );
    assert!(
        v.halo_dark > g.halo_dark,
        "gtao-vb dark halo {} vs gtao {}",
        v.halo_dark,
        g.halo_dark
    );

    let mean_ao = |s: &AoSettings| {
        let mut r = Renderer::new(&gpu, &scene, s, 128, 80, 16).unwrap();
        r.render(&scene.cameras[0].camera, None).unwrap();
        let ao = r.read_raw_ao().unwrap();
        ao.iter().sum::<f32>() / ao.len() as f32
    };
    let plain = mean_ao(&gtao);
    gtao.gtao.thickness_blend = 0.5;
    let blended = mean_ao(&gtao);
    println!("grass: mean GTAO AO β = 0: {plain:.4}, β = 0.5: {blended:.4}");
    assert!(blended > plain + 0.005, "{blended} vs {plain}");
}

#[test]
fn debug_images_show_open_horizons_on_a_plane_and_closed_ones_at_a_step() {
    // `render --debug-out`: on an unoccluded plane every GTAO slice is open (π between its
    // horizons: 1), GTAO-VB occupies no sector and HBAO+ sees no per-sample occlusion (0); HBAO's
    // horizon stays at the tangent plus the bias. Seen from above (the normal along the view),
    // the tangent lies at 0 and the image at ½ + bias/π. At the step the horizons rise.
    let gpu = gpu();
    let plane = quads("floor", &[floor(100.0)]);
    let view = Camera {
        eye: Vec3::new(0.0, 20.0, 0.0),
        target: Vec3::ZERO,
        up: Vec3::NEG_Z,
        fov_y_deg: 4.0,
    };
    let debug = |t: Technique, scene: &obscura::scene::Scene| {
        let s = technique_settings(t, false);
        let mut r = Renderer::new(&gpu, scene, &s, 48, 48, 16).unwrap();
        r.render(&view, None).unwrap();
        let image = r.read_estimator_debug().unwrap().expect("a debug image");
        let (min, max) = image
            .iter()
            .fold((f32::MAX, f32::MIN), |(a, b), &v| (a.min(v), b.max(v)));
        (min, max, image.iter().sum::<f32>() / image.len() as f32)
    };
    let bias = AoSettings::default().hbao.angle_bias;
    for (t, want) in [
        (Technique::Gtao, 1.0),
        (Technique::GtaoVb, 0.0),
        (Technique::HbaoPlus, 0.0),
        (Technique::Hbao, 0.5 + bias / PI),
        // The interleaved schedule writes the same image.
        (Technique::HbaoInterleaved, 0.5 + bias / PI),
    ] {
        let (min, max, _) = debug(t, &plane);
        println!("{t} on a plane: debug image in [{min:.5}, {max:.5}], want {want:.5}");
        assert!(
            (min - want).abs() < 2e-3 && (max - want).abs() < 2e-3,
            "{t}: [{min}, {max}] vs {want}"
        );
    }
    // A step 5 cm beside the view's centre: its edge is within every radius of the image's
    // middle, so the mean moves from the plane's value towards occlusion.
    let step = step_scene(0.05, 0.3);
    for (t, plane_value, rises) in [
        (Technique::Gtao, 1.0, false),
        (Technique::GtaoVb, 0.0, true),
        (Technique::HbaoPlus, 0.0, true),
        (Technique::Hbao, 0.5 + bias / PI, true),
    ] {
        let (_, _, mean) = debug(t, &step);
        println!("{t} at a step: mean debug value {mean:.4} (plane {plane_value:.4})");
        if rises {
            assert!(mean > plane_value + 0.01, "{t}: {mean}");
        } else {
            assert!(mean < plane_value - 0.01, "{t}: {mean}");
        }
    }
    let none = technique_settings(Technique::Vao, false);
    let mut r = Renderer::new(&gpu, &plane, &none, 16, 16, 0).unwrap();
    r.render(&view, None).unwrap();
    assert!(r.read_estimator_debug().unwrap().is_none());
}
