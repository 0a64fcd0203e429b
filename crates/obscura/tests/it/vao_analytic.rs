//! VAO against values derived independently of the kernel: an unoccluded plane, and a 90° inside
//! corner whose expected AO is the column-model integral computed here by quadrature.

use crate::common::*;
use glam::{Vec2, Vec3};
use obscura::settings::{AoSettings, Normalization};
use obscura::{FrameView, Renderer};

fn settings(exponent: f32, samples: u32, blur: bool) -> AoSettings {
    let mut s = AoSettings::default();
    s.vao.exponent = exponent;
    s.vao.samples = samples;
    s.blur.enabled = blur;
    s
}

#[test]
fn unoccluded_plane_is_one_everywhere() {
    let gpu = gpu();
    for (exponent, blur) in [(1.0, false), (1.3, false), (1.3, true)] {
        for samples in [8, 16, 32] {
            // Float rounding of the column heights leaves AO a few 1e-4 below 1 at worst.
            let ao = tilted_floor_ao(&gpu, &settings(exponent, samples, blur));
            let min = ao.iter().copied().fold(f32::MAX, f32::min);
            let max = ao.iter().copied().fold(f32::MIN, f32::max);
            assert!(
                min > 1.0 - 1e-3 && max <= 1.0,
                "exponent {exponent}, {samples} samples, blur {blur}: AO in [{min}, {max}]"
            );
        }
    }
}

/// Expected AO of a floor point at distance `a` from a wall (inside 90° corner along x) for a view
/// direction `e` = (0, 1, 1)/√2 in the orthographic limit: ∫ free dA / ∫ clipped dA over the disc
/// ⟂ e of radius R, with the thickness/halo model of seed 000 Fig. 4 (τ = `thickness`).
///
/// Disc offsets d = u·T + v·B with T = x, B = (0, 1, −1)/√2, column points P + d + z·e.
/// Floor tangent plane y = 0 ⇔ z = −v: the column is clipped to [max(−h, −v), h].
/// Along the column, seen from the camera (z decreasing), the first surface is the floor at z = −v
/// where v < a/√2, else the wall z_world = 0 at z = v − √2·a.
fn corner_integral(a: f32, radius: f32, thickness: f32) -> f32 {
    let n = 1500;
    let (mut free_sum, mut clipped_sum) = (0.0f64, 0.0f64);
    for i in 0..n {
        for j in 0..n {
            let u = ((i as f32 + 0.5) / n as f32 * 2.0 - 1.0) * radius;
            let v = ((j as f32 + 0.5) / n as f32 * 2.0 - 1.0) * radius;
            let r2 = u * u + v * v;
            if r2 >= radius * radius {
                continue;
            }
            let h = (radius * radius - r2).sqrt();
            let (start, end) = (h, (-v).max(-h));
            if start <= end {
                continue;
            }
            let z = if v < a / 2f32.sqrt() {
                -v
            } else {
                v - 2f32.sqrt() * a
            };
            let length = start - end;
            let sphere = (start - end.max(z)).max(0.0);
            let halo = ((z - (1.0 + thickness) * radius) / length).clamp(0.0, 1.0) * length;
            free_sum += f64::from(sphere + halo);
            clipped_sum += f64::from(length);
        }
    }
    (free_sum / clipped_sum) as f32
}

#[test]
fn inside_corner_matches_the_column_integral() {
    let gpu = gpu();
    // Floor y = 0 (z > 0) and wall z = 0 (y > 0) meeting along the x axis.
    let wall = [
        Vec3::new(-100.0, 0.0, 0.0),
        Vec3::new(100.0, 0.0, 0.0),
        Vec3::new(100.0, 100.0, 0.0),
        Vec3::new(-100.0, 100.0, 0.0),
    ];
    let floor = [
        Vec3::new(-100.0, 0.0, 100.0),
        Vec3::new(100.0, 0.0, 100.0),
        Vec3::new(100.0, 0.0, 0.0),
        Vec3::new(-100.0, 0.0, 0.0),
    ];
    let scene = quads("corner", &[wall, floor]);
    // Telephoto from far along (0, 1, 1): nearly orthographic, R ≈ 46 px.
    let eye = Vec3::new(0.0, 20.0, 20.0) / 2f32.sqrt() + Vec3::new(0.0, 0.0, 0.0);
    let cam = camera(eye, Vec3::ZERO, 4.0);
    let (w, h) = (128, 128);
    let s = settings(1.0, 32, false);
    let mut r = Renderer::new(&gpu, &scene, &s, w, h, 48).unwrap();
    r.render(&cam, None).unwrap();
    let ao = r.read_ao().unwrap();
    let view = FrameView::new(cam, w, h, 48, 1e-3);
    let g = view.guard_band as f32;
    for a in [0.1f32, 0.2, 0.3, 0.45, 0.7] {
        let expected = corner_integral(a, s.vao.radius, s.vao.thickness);
        // The image row through the floor point (0, 0, a); average it over x (translation
        // invariant along the corner) to average the per-pixel rotations.
        let p = view.view_to_pixel_world(Vec3::new(0.0, 0.0, a));
        let row = (p.y - g).floor() as u32;
        let values: Vec<f32> = (16..w - 16).map(|x| ao[(row * w + x) as usize]).collect();
        let mean = values.iter().sum::<f32>() / values.len() as f32;
        println!("a = {a}: GPU row mean {mean:.4}, integral {expected:.4}");
        assert!(
            (mean - expected).abs() < 0.02,
            "a = {a}: GPU {mean} vs integral {expected}"
        );
    }
    // Far from the wall (a > (1+τ)R + the falloff) the floor is unoccluded.
    assert!((corner_integral(2.0, 0.5, 0.5) - 1.0).abs() < 1e-6);
    let _ = Vec2::ZERO;
}

#[test]
fn paper_normalisation_agrees_on_average() {
    // The paper's 2/N estimator is 1 on an unoccluded plane only on average over the rotations.
    let gpu = gpu();
    let scene = quads("floor", &[floor(100.0)]);
    let cam = camera(Vec3::new(0.0, 2.0, 4.0), Vec3::new(0.0, 0.0, -1.0), 50.0);
    let mut s = settings(1.0, 8, false);
    s.vao.normalization = Normalization::Hemisphere;
    let mut r = Renderer::new(&gpu, &scene, &s, 96, 64, 16).unwrap();
    r.render(&cam, None).unwrap();
    let ao = r.read_ao().unwrap();
    let mean = ao.iter().sum::<f32>() / ao.len() as f32;
    assert!(mean > 0.9 && mean <= 1.0, "mean {mean}");
}
