//! AO does not depend on the scene's units: a scene scaled by k, seen by the camera scaled by k,
//! with every world length of the settings scaled by k (`AoSettings::scaled`), gives the same
//! image. Outside scenes come in metres, centimetres or millimetres; a world-unit constant left in
//! a shader (an ε, a bias, a depth precision) shows up here as a difference between the scales.
//! The factors are powers of two, so every length scales exactly in floating point and the
//! arithmetic along the way scales with it: differences are rounding, not approximation.

use crate::common;

use obscura::bvh::Bvh;
use obscura::reference::ground_truth::{render_reference, ReferenceModel, ReferenceSettings};
use obscura::settings::Resolution;
use obscura::{AoSettings, FrameView, Renderer, Technique};

const W: u32 = 80;
const H: u32 = 48;
const GUARD: u32 = 12;

fn render(gpu: &obscura::Gpu, name: &str, settings: &AoSettings, k: f32) -> Vec<f32> {
    let (scene, camera) = common::scaled_builtin(name, k);
    let mut r = Renderer::new(gpu, &scene, &settings.scaled(k), W, H, GUARD).unwrap();
    r.render(&camera, None).unwrap();
    r.read_ao().unwrap()
}

/// The largest difference, the mean one, and how many pixels differ by more than 1e-3.
fn difference(a: &[f32], b: &[f32]) -> (f32, f64, usize) {
    let (mut worst, mut sum, mut differ) = (0.0f32, 0.0f64, 0usize);
    for (x, y) in a.iter().zip(b) {
        let d = (x - y).abs();
        worst = worst.max(d);
        sum += f64::from(d);
        differ += usize::from(d > 1e-3);
    }
    (worst, sum / a.len() as f64, differ)
}

// Where the scales part, float rounding alone: f32 keeps 24 bits, and the worst pixel at the
// built-ins' scale was 7e-6 apart (SAO, ×1/1024). Before the fixes this test came with, `sao`
// was 0.96 apart, `ssao` 0.10 (both had ε in world units), `rt-vao` 4e-3 (its rays' interval
// slope taken as a difference of large heights) and the CPU ground truth at least 3.3e-2.
#[test]
fn every_technique_gives_the_same_ao_in_any_units() {
    let gpu = common::gpu();
    let mut failures = Vec::new();
    for technique in Technique::all() {
        let settings = common::technique_settings(technique, true);
        let base = render(&gpu, "stairs", &settings, 1.0);
        for k in [1.0 / 1048576.0, 1.0 / 1024.0, 4096.0] {
            let other = render(&gpu, "stairs", &settings, k);
            let (worst, mae, differ) = difference(&base, &other);
            println!("{technique} ×{k}: max {worst:.2e}, MAE {mae:.2e}, {differ} pixels > 1e-3");
            if worst > 5e-5 || differ > 0 {
                failures.push(format!(
                    "{technique} ×{k}: max {worst}, MAE {mae}, {differ} px"
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

#[test]
fn the_ground_truths_are_the_same_in_any_units() {
    for model in [ReferenceModel::Vao, ReferenceModel::Hemisphere] {
        let reference = |k: f32| {
            let (scene, camera) = common::scaled_builtin("stairs", k);
            let bvh = Bvh::build(&scene);
            let view = FrameView::new(camera, W, H, GUARD, obscura::near_plane(&scene));
            let settings = ReferenceSettings {
                model,
                vao: AoSettings::default().scaled(k).vao,
                spp: 16,
                ..ReferenceSettings::default()
            };
            render_reference(&scene, &bvh, view, &settings, &|_| {})
        };
        let base = reference(1.0);
        for k in [1.0 / 1024.0, 4096.0] {
            let (worst, mae, differ) = difference(&base, &reference(k));
            println!("{model:?} ×{k}: max {worst:.2e}, MAE {mae:.2e}, {differ} pixels > 1e-3");
            assert!(
                worst <= 5e-5 && differ == 0,
                "{model:?} ×{k}: max {worst}, MAE {mae}, {differ} pixels"
            );
        }
    }
}

#[test]
fn the_pipeline_options_give_the_same_output_in_any_units() {
    // Half resolution (its depth-aware upsample), bent normals, missing-occlusion compensation,
    // and temporal accumulation along a moving camera (reprojection, the history's depth test).
    let gpu = common::gpu();
    type Tweak = fn(&mut AoSettings);
    let options: [(&str, Technique, Tweak); 5] = [
        ("half resolution", Technique::Vao, |s| {
            s.resolution = Resolution::Half
        }),
        ("half resolution", Technique::HbaoPlus, |s| {
            s.resolution = Resolution::Half
        }),
        ("bent normals", Technique::Gtao, |s| s.bent_normals = true),
        ("compensation", Technique::SdVao, |s| {
            s.stochastic_depth.compensation = 2.0
        }),
        ("temporal", Technique::Vao, |s| s.temporal.enabled = true),
    ];
    for (option, technique, tweak) in options {
        let mut settings = common::technique_settings(technique, true);
        tweak(&mut settings);
        let run = |k: f32| {
            let (scene, camera) = common::scaled_builtin("stairs", k);
            let mut r = Renderer::new(&gpu, &scene, &settings.scaled(k), W, H, GUARD).unwrap();
            // Three frames, the camera stepping sideways between them (what temporal
            // accumulation reprojects; the other options only show in each frame).
            for step in 0..3 {
                let mut c = camera;
                let shift = glam::Vec3::new(0.05 * step as f32, 0.0, 0.0) * k;
                c.eye += shift;
                c.target += shift;
                r.render(&c, None).unwrap();
            }
            let bent: Vec<f32> = r
                .read_bent_normals()
                .unwrap()
                .map(|b| b.iter().flat_map(|t| t[..3].iter().copied()).collect())
                .unwrap_or_default();
            (r.read_ao().unwrap(), bent)
        };
        let (base, base_bent) = run(1.0);
        for k in [1.0 / 1024.0, 4096.0] {
            let (ao, bent) = run(k);
            let (worst, mae, differ) = difference(&base, &ao);
            println!("{option} {technique} ×{k}: max {worst:.2e}, MAE {mae:.2e}");
            assert!(
                worst <= 5e-5 && differ == 0,
                "{option} {technique} ×{k}: max {worst}, MAE {mae}, {differ} pixels"
            );
            let (worst, ..) = difference(&base_bent, &bent);
            // Bent normals are stored as f16 (a step of 4.9e-4 near 1).
            assert!(
                worst <= 1e-3,
                "{option} {technique} ×{k}: bent normals {worst} apart"
            );
        }
    }
}
