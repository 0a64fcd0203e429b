//! The hemisphere march over a stochastic depth map (`sd-hemisphere`, `ray-sd-hemisphere`):
//! what the map adds against the traced truth, where the depth buffer hides occluders and where
//! they lie beyond the framebuffer, in the map's own guard band. (Where nothing is hidden both
//! rows equal `hemisphere`: tests/it/source_twins.rs.)

use crate::common::*;
use crate::hemisphere::{hemisphere_truth, mean_abs_difference};
use obscura::settings::AoSettings;
use obscura::{Renderer, Technique};

/// `technique` without blur: 32 rays of 0.5 m (the ground truth's set for frame 0), 16 steps.
fn settings(technique: Technique) -> AoSettings {
    let mut s = technique_settings(technique, false);
    s.hemisphere.rays = 32;
    s.hemisphere.radius = 0.5;
    s.hemisphere.steps = 16;
    s
}

#[test]
fn the_march_over_either_map_finds_occluders_the_depth_buffer_hides() {
    // Stairs' close-up: the figure and the cloth hide the steps and walls behind them, where a
    // march over the first layer meets nothing once it passes `thickness` behind the surface in
    // front. Each depth the map stores is a surface of its own there. Against the same 32 rays
    // traced through the BVH (so only the march's model differs), measured on lavapipe at
    // 128×80: `hemisphere` 0.0270, `sd-hemisphere` 0.0232, `ray-sd-hemisphere` 0.0244.
    let gpu = gpu();
    let scene = obscura::scene::builtin("stairs").unwrap();
    let eye = scene.cameras[0].camera;
    let run = |technique| {
        let mut r = Renderer::new(&gpu, &scene, &settings(technique), 128, 80, 16).unwrap();
        r.render(&eye, None).unwrap();
        (r.read_raw_ao().unwrap(), *r.view().unwrap())
    };
    let (first, view) = run(Technique::Hemisphere);
    let truth = hemisphere_truth(&gpu, &scene, view, 32, 0.5);
    let first_mae = mean_abs_difference(&first, &truth);
    for technique in [Technique::SdHemisphere, Technique::RaySdHemisphere] {
        let (ao, _) = run(technique);
        let mae = mean_abs_difference(&ao, &truth);
        println!(
            "stairs MAE against the traced rays: hemisphere {first_mae:.4}, {technique} {mae:.4}"
        );
        assert!(mae < 0.95 * first_mae, "{technique}: {mae} vs {first_mae}");
    }
}

#[test]
fn the_march_goes_on_in_the_maps_guard_band() {
    // The guard band case (tests/common: a step 0.8 m high just past the framebuffer's right
    // edge, its 4 px guard band included, seen from above). A march over the first layer stops
    // where its ray leaves the framebuffer, so the floor beside the visible edge misses the
    // step. Over a map with a 32 px band of its own (seed 002 §3.5; the rays reach about 12 px)
    // the march goes on over the band's depths, which hold every layer, the step's top nearest.
    // `hemisphere.thickness` = 1 m: the step is solid that deep. Against the same rays traced,
    // the error of the 12 visible columns at the edge must fall to a tenth; where no ray leaves
    // the framebuffer (the left half) the band changes nothing.
    let gpu = gpu();
    let case = edge_band_case();
    for technique in [Technique::SdHemisphere, Technique::RaySdHemisphere] {
        let run = |band: u32| {
            let r = case.render(&gpu, technique, |s| {
                s.hemisphere.rays = 32;
                s.hemisphere.radius = 1.0;
                s.hemisphere.steps = 32;
                s.hemisphere.thickness = 1.0;
                s.stochastic_depth.guard_band = Some(band);
                s.ray_sd.guard_band = Some(band);
            });
            (r.read_raw_ao().unwrap(), *r.view().unwrap())
        };
        let (without, view) = run(0);
        let (with, _) = run(32);
        let truth = hemisphere_truth(&gpu, &case.scene, view, 32, 1.0);
        let (e_without, e_with) = (
            case.edge_error(&without, &truth),
            case.edge_error(&with, &truth),
        );
        println!(
            "{technique}: edge MSE {e_without:.3e} without the map's band, {e_with:.3e} with 32 px"
        );
        assert!(
            e_without > 1e-3,
            "{technique}: the case must miss occlusion: {e_without}"
        );
        assert!(
            e_with < e_without / 10.0,
            "{technique}: {e_with:e} vs {e_without:e}"
        );
        let worst = case.left_half_difference(&with, &without);
        assert!(
            worst <= 1e-6,
            "{technique}: the band changed the left half by {worst}"
        );
    }
}
