//! HBAO+ (the seed authors' baseline, docs/AUTHORS_CODE.md §1.7) against values derived without the
//! GPU kernel: an unoccluded plane, a plain CPU implementation of the same estimator on a
//! read-back G-buffer (single pass and interleaved), its model's closed form for a step seen from
//! above, and its model over exact geometry at an inside corner (its dual-depth row:
//! tests/it/source_twins.rs). The CPU implementation is the estimator's mirror,
//! `estimators::hbao_plus::cpu_hbao_plus`.

use crate::common::*;
use glam::{UVec2, Vec2};
use obscura::estimators::hbao_plus::{cpu_hbao_plus, pixel_pattern, sample};
use obscura::settings::HbaoPlusSettings;
use obscura::{scene, Renderer, Technique};

#[test]
fn unoccluded_plane_is_one_everywhere() {
    // On a plane every sample's V lies in the tangent plane: N·V/|V| = 0 < bias, no occlusion.
    let gpu = gpu();
    for (blur, technique) in [
        (false, Technique::HbaoPlus),
        (true, Technique::HbaoPlus),
        (false, Technique::HbaoPlusInterleaved),
    ] {
        for (directions, steps) in [(8, 4), (4, 8), (32, 1)] {
            let mut s = technique_settings(technique, blur);
            s.hbao_plus.directions = directions;
            s.hbao_plus.steps = steps;
            let ao = tilted_floor_ao(&gpu, &s);
            let min = ao.iter().copied().fold(f32::MAX, f32::min);
            assert!(
                min > 1.0 - 1e-3,
                "{technique} {directions}×{steps}, blur {blur}: min AO {min}"
            );
        }
    }
}

#[test]
fn gpu_matches_the_cpu_implementation() {
    // Both schedules: the interleaved one (the authors' HBAO+) is the same estimator whose samples
    // read the nearest pixel of their own residue class mod 4.
    let gpu = gpu();
    for name in ["stairs", "colonnade"] {
        let scene = scene::builtin(name).unwrap();
        for technique in [Technique::HbaoPlus, Technique::HbaoPlusInterleaved] {
            let s = technique_settings(technique, false);
            let mut r = Renderer::new(&gpu, &scene, &s, 160, 96, 16).unwrap();
            r.render(&scene.cameras[0].camera, None).unwrap();
            let gpu_ao = r.read_raw_ao().unwrap();
            let cpu = cpu_hbao_plus(
                &r.read_gbuffer().unwrap(),
                &r.view().unwrap().screen(),
                &s.hbao_plus,
                technique == Technique::HbaoPlusInterleaved,
            );
            assert_mirrors(&format!("{name} {technique}"), &gpu_ao, cpu);
        }
    }
}

/// HBAO+'s model for the floor point `d` before a step of height `h` seen from above (normal and
/// view straight down, 20 m away; [`step_ao`]), for visible pixel `pixel`'s own samples: a sample
/// `t` pixels out along its direction lands on the block's top where it passes the edge (world
/// offset t·size·(20 − h)/20 there, size the floor's pixel), V = (offset, h), and occludes by
/// saturate(h/|V| − bias)·saturate(1 − |V|²/R²); the floor occludes nothing.
/// AO = saturate(1 − 2·mean)^exponent over all samples.
fn hbao_plus_step_closed_form(d: f32, h: f32, s: &HbaoPlusSettings, pixel: UVec2) -> f32 {
    let size = step_pixel_size();
    let radius_px = s.radius / size;
    let step = radius_px / (s.steps + 1) as f32;
    let (c, sn, jitter) = pixel_pattern(pixel.x, pixel.y, s.directions);
    let mut occlusion = 0.0;
    for i in 0..s.directions * s.steps {
        let (bx, by, k) = sample(i, s.directions, s.steps);
        let dir_x = bx * c - by * sn;
        let t = jitter * step + 1.0 + k as f32 * step;
        let offset = t * size * (20.0 - h) / 20.0;
        if dir_x * offset <= d {
            continue;
        }
        let v2 = offset * offset + h * h;
        let angle = (h / v2.sqrt() - s.bias).clamp(0.0, 1.0);
        occlusion += angle * (1.0 - v2 / (s.radius * s.radius)).clamp(0.0, 1.0);
    }
    let mean = occlusion / (s.directions * s.steps) as f32;
    (1.0 - 2.0 * mean).clamp(0.0, 1.0).powf(s.exponent)
}

#[test]
fn a_step_seen_from_above_matches_the_models_closed_form() {
    // Per pixel with its own sample pattern, against the GPU's pixel-snapped samples (measured:
    // within 0.009).
    for (d, h) in [(0.1, 0.2), (0.3, 0.3), (0.5, 0.4)] {
        let s = technique_settings(Technique::HbaoPlus, false);
        let (got, want) = step_ao(&s, d, h, |d, pixel| {
            hbao_plus_step_closed_form(d, h, &s.hbao_plus, pixel)
        });
        println!("hbao+ step d {d} h {h}: GPU {got:.4}, closed form {want:.4}");
        assert!(want < 0.97, "the configuration must occlude: {want}");
        assert!((got - want).abs() < 0.02, "d {d} h {h}: {got} vs {want}");
    }
}

#[test]
fn at_an_inside_corner_matches_its_model_with_exact_geometry() {
    // Per corner pixel, its own samples evaluated on the exact floor and wall (each sample's
    // camera ray cast against both planes) instead of the pixel-snapped G-buffer (measured:
    // 0.337 against 0.337).
    let s = technique_settings(Technique::HbaoPlus, false);
    let h = s.hbao_plus;
    let (got, want, count, _) = corner_ao_and_model(&s, |pixel, corner| {
        let centre = (pixel + corner.screen.guard_band).as_vec2() + 0.5;
        let (p, n) = corner
            .surface(centre)
            .expect("the corner pixel sees the floor");
        let radius_px = h.radius * corner.screen.uniform().projection_scale[1] / -p.z;
        let step = radius_px / (h.steps + 1) as f32;
        let (c, sn, jitter) = pixel_pattern(pixel.x, pixel.y, h.directions);
        let mut occlusion = 0.0;
        for i in 0..h.directions * h.steps {
            let (bx, by, k) = sample(i, h.directions, h.steps);
            let dir = Vec2::new(bx * c - by * sn, bx * sn + by * c);
            let px = centre + dir * (jitter * step + 1.0 + k as f32 * step);
            if let Some((q, _)) = corner.surface(px) {
                let v = q - p;
                let v2 = v.dot(v);
                let angle = (n.dot(v) / v2.sqrt() - h.bias).clamp(0.0, 1.0);
                occlusion += angle * (1.0 - v2 / (h.radius * h.radius)).clamp(0.0, 1.0);
            }
        }
        let mean = occlusion / (h.directions * h.steps) as f32;
        (1.0 - 2.0 * mean).clamp(0.0, 1.0).powf(h.exponent)
    });
    println!("hbao+ at the inside corner: GPU {got:.4}, model {want:.4} over {count} pixels");
    assert!(want < 0.9, "the corner must occlude: {want}");
    assert!((got - want).abs() < 0.03, "{got} vs {want}");
}
