//! The raster map's `nearest` selection (`stochastic_depth.selection`, ours): each pixel keeps its
//! S nearest distinct hidden depths, by a k-buffer of atomics (map.wgsl, `sd_store_nearest`),
//! instead of seed 001 Alg. 1's stochastic subset.

use crate::common::*;
use glam::Vec3;
use obscura::settings::{RaySdSettings, SdSelection, StochasticDepthSettings};
use obscura::{scene, AoSettings, Renderer, Technique};

fn nearest(technique: Technique, samples: u32) -> AoSettings {
    let mut s = AoSettings {
        technique,
        stochastic_depth: StochasticDepthSettings {
            samples,
            selection: SdSelection::Nearest,
            ..Default::default()
        },
        ..Default::default()
    };
    s.blur.enabled = false;
    s
}

/// The raw AO of built-in scene `name` from its first camera at `width`×`height` + 16 px.
fn raw_ao(
    gpu: &obscura::Gpu,
    name: &str,
    settings: &AoSettings,
    (width, height): (u32, u32),
) -> Vec<f32> {
    let scene = scene::builtin(name).unwrap();
    let mut r = Renderer::new(gpu, &scene, settings, width, height, 16).unwrap();
    r.render(&scene.cameras[0].camera, None).unwrap();
    r.read_raw_ao().unwrap()
}

#[test]
fn each_pixel_keeps_its_s_nearest_hidden_layers_nearest_first() {
    // Seven facing layers in shuffled draw order, the first visible at depth 1: the six behind
    // it must fill the slots nearest first, whatever order their fragments arrive in, and the
    // slots beyond the sixth stay empty. Every pixel, every S.
    let gpu = gpu();
    let drawn = [3.0f32, 1.0, 6.0, 2.0, 7.0, 5.0, 4.0];
    let hidden = [2.0f32, 3.0, 4.0, 5.0, 6.0, 7.0];
    let scene = facing_layers(&drawn);
    for samples in [1u32, 2, 4, 8, 16] {
        let mut r =
            Renderer::new(&gpu, &scene, &nearest(Technique::SdVao, samples), 64, 64, 0).unwrap();
        r.render(&camera(Vec3::ZERO, Vec3::NEG_Z, 90.0), None)
            .unwrap();
        let slots = r.read_stochastic_depth().unwrap().unwrap();
        assert_eq!(slots.len(), samples as usize);
        for (k, slot) in slots.iter().enumerate() {
            for (p, &z) in slot.iter().enumerate() {
                match hidden.get(k) {
                    Some(&want) => assert!(
                        (z - want).abs() <= 1e-5 * want,
                        "S {samples}, pixel {p}, slot {k}: depth {z}, want {want}"
                    ),
                    None => assert_eq!(z, 0.0, "S {samples}, pixel {p}, slot {k} not empty"),
                }
            }
        }
    }
}

#[test]
fn holding_every_hidden_layer_the_raster_map_equals_the_ray_traced_one() {
    // Where no pixel hides more than 8 layers, the nearest 8 are all of them, and so are the
    // ray-traced map's 8 reservoir slots at full resolution (seed 002 §3.1; its rays reach every
    // hit with MAX_COUNT 64). Both are sampled at the pixel centres, so `sd-vao` and
    // `ray-sd-vao-full` read the same depths and must give the same AO (up to the rounding of a
    // rasterised against a traced depth). On `stairs`, `layers` and `grass` a few hundred pixels
    // of 15,360 differ where a sample's pixel centre lies on a triangle edge, which the
    // rasteriser and the traversal assign differently; the two views here have none.
    let gpu = gpu();
    for name in ["colonnade", "tower"] {
        // Neither map with a band of its own (the ray-traced one's is 0 on a one-pass row).
        let mut raster = nearest(Technique::SdVao, 8);
        raster.stochastic_depth.guard_band = Some(0);
        let raster = raw_ao(&gpu, name, &raster, (160, 96));
        let mut traced = nearest(Technique::RaySdVaoFull, 8);
        traced.ray_sd = RaySdSettings {
            resolution: 1,
            reservoir: 8,
            max_count: 64,
            guard_band: Some(0),
            ..Default::default()
        };
        let traced = raw_ao(&gpu, name, &traced, (160, 96));
        let worst = max_abs_diff(&raster, &traced);
        let occluded = raster.iter().filter(|&&a| a < 0.9).count();
        println!("{name}: max |sd-vao − ray-sd-vao-full| {worst:e}, {occluded} occluded pixels");
        assert!(occluded > 100, "{name}: the view must have occlusion");
        assert!(worst <= 1e-5, "{name}: {worst}");
    }
}

#[test]
fn the_two_phase_row_reads_the_same_nearest_layers() {
    // sd-svao rasterises the map only where phase 1 asked for it; with the nearest layers the
    // pixels it asks for hold the same depths, so it must equal sd-vao (seed 000 §3.9's identity,
    // tests/it/two_phase_twins.rs for the stochastic map), with each way of limiting the map.
    use obscura::settings::SdMask;
    let gpu = gpu();
    for name in ["stairs", "grass"] {
        let single = raw_ao(&gpu, name, &nearest(Technique::SdVao, 4), (96, 64));
        for mask in [SdMask::Depth, SdMask::Discard] {
            let mut s = nearest(Technique::SdSvao, 4);
            s.stochastic_depth.mask = mask;
            let worst = max_abs_diff(&single, &raw_ao(&gpu, name, &s, (96, 64)));
            assert!(worst <= 1e-5, "{name}, {mask}: sd-svao − sd-vao {worst}");
        }
    }
}

#[test]
fn the_selection_is_a_setting_with_a_clear_error() {
    let err = "closest".parse::<SdSelection>().unwrap_err().to_string();
    assert!(
        err.contains("stochastic_depth.selection") && err.contains("nearest"),
        "{err}"
    );
    assert_eq!(
        "Nearest".parse::<SdSelection>().unwrap(),
        SdSelection::Nearest
    );
    assert_eq!(
        StochasticDepthSettings::default().selection,
        SdSelection::Stochastic
    );
}
