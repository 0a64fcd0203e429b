//! GPU validation sweep (issue 15): every row of the technique table over every built-in scene, at
//! degenerate and odd sizes with and without a guard band, and at the extremes of every setting,
//! on lavapipe with wgpu validation on. Every frame must render without a validation error and
//! give finite AO in [0, 1]. Table-driven: a new technique joins by being a row.
//!
//! A setting the adapter cannot run (e.g. 16 stochastic depth samples where lavapipe's depth
//! targets take 4) must be refused with an error that says so; that counts as handled.

use crate::common::*;
use obscura::scene::{self, Scene};
use obscura::settings::{SdRasterizer, SdSelection};
use obscura::{AoSettings, Renderer, Technique};

/// Renders `scene`'s first camera with `settings` at `size` + `guard_band`, and checks the AO.
/// `Err` only for a setting the adapter refuses (the message must say it is unsupported).
fn check(
    gpu: &obscura::Gpu,
    scene: &Scene,
    settings: &AoSettings,
    (w, h): (u32, u32),
    guard_band: u32,
) -> Result<(), String> {
    let what = format!(
        "{} on {} at {w}x{h}+{guard_band} with {:?}",
        settings.technique,
        scene.name,
        settings.resolved()
    );
    let mut r = match Renderer::new(gpu, scene, settings, w, h, guard_band) {
        Ok(r) => r,
        Err(e) => return refused(&what, &e.to_string()),
    };
    let camera = scene.default_camera(w as f32 / h as f32);
    if let Err(e) = r.render(&camera, None) {
        return refused(&what, &e.to_string());
    }
    let ao = r.read_ao().unwrap_or_else(|e| panic!("{what}: {e}"));
    assert_eq!(ao.len(), (w * h) as usize, "{what}");
    if let Some(bad) = ao
        .iter()
        .find(|v| !(v.is_finite() && (0.0..=1.0).contains(*v)))
    {
        panic!("{what}: AO value {bad}");
    }
    Ok(())
}

fn refused(what: &str, message: &str) -> Result<(), String> {
    let m = message.to_lowercase();
    assert!(
        m.contains("adapter") && (m.contains("support") || m.contains("limit")),
        "{what} failed: {message}"
    );
    Err(message.to_owned())
}

#[test]
fn every_technique_on_every_builtin_scene() {
    let gpu = gpu();
    for name in scene::builtin_names() {
        let scene = scene::builtin(name).unwrap();
        for technique in Technique::all() {
            check(
                &gpu,
                &scene,
                &technique_settings(technique, true),
                (33, 17),
                8,
            )
            .unwrap_or_else(|e| panic!("{technique} on {name}: {e}"));
        }
    }
}

#[test]
fn every_technique_at_degenerate_and_odd_sizes() {
    let gpu = gpu();
    let scene = scene::builtin("stairs").unwrap();
    for technique in Technique::all() {
        for size in [(1, 1), (7, 5), (64, 64), (3, 61)] {
            for guard_band in [0, 48] {
                let settings = technique_settings(technique, true);
                check(&gpu, &scene, &settings, size, guard_band)
                    .unwrap_or_else(|e| panic!("{technique} at {size:?}+{guard_band}: {e}"));
            }
        }
    }
}

/// The stochastic depth map rasterised in compute at the same sizes, with and without its own
/// band (boxes clamped to maps of one pixel, tiles cut by the map's edge).
#[test]
fn the_compute_rasterised_map_at_degenerate_and_odd_sizes() {
    let gpu = gpu();
    let scene = scene::builtin("stairs").unwrap();
    for technique in [
        Technique::SdVao,
        Technique::SdSvao,
        Technique::SdHbaoPlusMultiview,
    ] {
        for size in [(1, 1), (7, 5), (64, 64), (3, 61)] {
            for (guard_band, map_band) in [(0, 0), (48, 0), (0, 5)] {
                let mut settings = technique_settings(technique, true);
                settings.stochastic_depth.rasterizer = SdRasterizer::Compute;
                settings.stochastic_depth.guard_band = Some(map_band);
                check(&gpu, &scene, &settings, size, guard_band).unwrap_or_else(|e| {
                    panic!("{technique} at {size:?}+{guard_band}, band {map_band}: {e}")
                });
            }
        }
    }
}

/// The settings at the edges of what `AoSettings::validate` accepts, one change at a time.
fn extremes(technique: Technique) -> Vec<AoSettings> {
    let base = technique_settings(technique, true);
    let mut out = Vec::new();
    let mut push = |f: &dyn Fn(&mut AoSettings)| {
        let mut s = base;
        f(&mut s);
        s.validate().expect("an extreme the rules accept");
        out.push(s);
    };
    push(&|s| s.vao.radius = 1e-4);
    push(&|s| s.vao.radius = 1e3);
    push(&|s| s.vao.thickness = 0.0);
    push(&|s| s.vao.thickness = 1e3);
    push(&|s| s.vao.exponent = 1e-3);
    push(&|s| s.vao.exponent = 20.0);
    push(&|s| s.vao.samples = 32);
    push(&|s| s.hbao_plus.radius = 1e-4);
    push(&|s| s.hbao_plus.bias = 0.999);
    push(&|s| {
        s.hbao_plus.directions = 32;
        s.hbao_plus.steps = 1;
    });
    push(&|s| {
        s.hbao_plus.directions = 1;
        s.hbao_plus.steps = 32;
    });
    push(&|s| s.gtao_vb.radius = 1e3);
    push(&|s| s.gtao_vb.thickness = 0.0);
    push(&|s| {
        s.gtao_vb.slices = 1;
        s.gtao_vb.steps = 16;
    });
    push(&|s| {
        s.gtao_vb.slices = 3;
        s.gtao_vb.steps = 5;
    });
    push(&|s| s.peel_separation = 0.0);
    push(&|s| s.peel_separation = 1e3);
    push(&|s| s.stochastic_depth.samples = 1);
    push(&|s| s.stochastic_depth.samples = 16);
    push(&|s| s.stochastic_depth.alpha = Some(1e-4));
    push(&|s| s.stochastic_depth.alpha = Some(1.0));
    push(&|s| s.stochastic_depth.rasterizer = SdRasterizer::Compute);
    push(&|s| {
        s.stochastic_depth.rasterizer = SdRasterizer::Compute;
        s.stochastic_depth.samples = 16;
        s.stochastic_depth.selection = SdSelection::Nearest;
    });
    push(&|s| s.blur.radius = 16);
    push(&|s| s.blur.sharpness = 0.0);
    out
}

#[test]
fn every_technique_at_the_extremes_of_every_setting() {
    let gpu = gpu();
    let scene = scene::builtin("colonnade").unwrap();
    let mut refused = Vec::new();
    for technique in Technique::all() {
        for settings in extremes(technique) {
            if let Err(e) = check(&gpu, &scene, &settings, (24, 16), 8) {
                refused.push(format!("{technique}: {e}"));
            }
        }
    }
    // Only stochastic depth sample counts the adapter lacks may be refused.
    for r in &refused {
        assert!(r.contains("sample"), "unexpected refusal: {r}");
    }
    println!("refused as unsupported on this adapter: {refused:?}");
}
