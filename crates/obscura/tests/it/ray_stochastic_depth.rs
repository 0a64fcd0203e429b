//! The ray-traced stochastic depth map (seed 002 §3.1, Listing 1) and its rows `ray-sd-vao`
//! (two-phase) and `ray-sd-vao-full` (one pass): what the reservoir keeps, where the ray stops,
//! and the AO against the `vao` ground truth.

use crate::common::*;
use glam::Vec3;
use obscura::scene::Scene;
use obscura::settings::RaySdSettings;
use obscura::{scene, AoSettings, Gpu, Renderer, Technique};

const SIZE: u32 = 64;

/// The map's slot layers (linear depth, 0 = empty) and hits per ray for `scene` seen from the
/// origin with `ray-sd-vao-full` (every pixel traced), 64×64, no guard band.
fn ray_map(gpu: &Gpu, scene: &Scene, ray_sd: RaySdSettings) -> (Vec<Vec<f32>>, Vec<u32>) {
    let settings = AoSettings {
        technique: Technique::RaySdVaoFull,
        ray_sd,
        ..Default::default()
    };
    let mut r = Renderer::new(gpu, scene, &settings, SIZE, SIZE, 0).unwrap();
    r.render(&camera(Vec3::ZERO, Vec3::NEG_Z, 90.0), None)
        .unwrap();
    (
        r.read_stochastic_depth().unwrap().unwrap(),
        r.read_ray_sd_hits().unwrap().unwrap(),
    )
}

/// Per layer of `depths` (the first is the visible one), the fraction of pixels whose slots hold
/// it; every stored depth must be one of the layers.
fn kept_fraction(slots: &[Vec<f32>], depths: &[f32]) -> Vec<f64> {
    let pixels = slots[0].len();
    let mut kept = vec![0usize; depths.len()];
    for p in 0..pixels {
        for layer in slots {
            let z = layer[p];
            if z == 0.0 {
                continue;
            }
            let k = depths
                .iter()
                .position(|d| (z - d).abs() <= 1e-5 * d)
                .unwrap_or_else(|| panic!("stored depth {z} is none of {depths:?}"));
            kept[k] += 1;
        }
    }
    kept.iter().map(|&k| k as f64 / pixels as f64).collect()
}

#[test]
fn every_hidden_layer_is_kept_at_its_exact_depth_when_the_reservoir_holds_them_all() {
    // Seed 002 §3.1: the first N distinct depths fill the reservoir. Three hidden layers, N = 4:
    // each pixel holds all three (to f32 rounding of the ray's t) and one empty slot; the
    // visible layer is skipped as the raster map skips it. At 1/2 and 1/4 resolution (§3.3) the
    // jittered rays meet the same planes, and every pixel reads its texel's slots.
    let gpu = gpu();
    let depths = [1.0, 2.0, 3.0, 5.0];
    for resolution in [1, 2, 4] {
        let settings = RaySdSettings {
            resolution,
            ..RaySdSettings::default()
        };
        let (slots, hits) = ray_map(&gpu, &facing_layers(&depths), settings);
        let kept = kept_fraction(&slots, &depths);
        assert_eq!(kept, vec![0.0, 1.0, 1.0, 1.0], "1/{resolution}: {kept:?}");
        let empty = (0..slots[0].len())
            .filter(|&p| slots.iter().filter(|l| l[p] == 0.0).count() == 1)
            .count();
        assert_eq!(empty, slots[0].len(), "one empty slot per pixel");
        let texels = (SIZE / resolution).pow(2) as usize;
        assert_eq!(hits.len(), texels);
        assert!(hits.iter().all(|&h| h == 3), "three hits per ray");
    }
}

#[test]
fn without_z_culling_every_hidden_layer_is_kept_with_probability_n_over_k() {
    // Reservoir sampling (Vitter 1985): k = 8 hidden layers, N = 4, MAX_COUNT = 8: each layer is
    // in a pixel's reservoir with probability N/k = 1/2, whatever order the BVH meets them in.
    let gpu = gpu();
    let depths: Vec<f32> = (0..9).map(|i| 1.0 + 0.5 * i as f32).collect();
    let settings = RaySdSettings {
        z_cull: false,
        seed: 3,
        ..RaySdSettings::default()
    };
    let (slots, hits) = ray_map(&gpu, &facing_layers(&depths), settings);
    let pixels = slots[0].len();
    let kept = kept_fraction(&slots, &depths);
    assert_eq!(kept[0], 0.0, "the visible layer is never stored");
    for (k, &f) in kept.iter().enumerate().skip(1) {
        let sigma = (0.25 / pixels as f64).sqrt();
        assert!(
            (f - 0.5).abs() <= 5.0 * sigma,
            "layer {k}: kept in {f:.3} of the pixels, expected 0.5 ± {:.3}",
            5.0 * sigma
        );
    }
    assert!(slots.iter().all(|l| l.iter().all(|&z| z > 0.0)), "full");
    assert!(hits.iter().all(|&h| h == 8));
}

#[test]
fn z_culling_favours_near_layers() {
    // The paper's default: a slot is overwritten only by a nearer depth, so the nearest hidden
    // layer is kept more often than plain reservoir sampling keeps it, the farthest less often.
    // Our traversal visits the nearer child first, so on these layers the first N hits are the
    // N nearest and z-culling keeps exactly them (measured: [0, 1, 1, 1, 1, 0, 0, 0, 0]).
    let gpu = gpu();
    let depths: Vec<f32> = (0..9).map(|i| 1.0 + 0.5 * i as f32).collect();
    let (slots, _) = ray_map(&gpu, &facing_layers(&depths), RaySdSettings::default());
    let kept = kept_fraction(&slots, &depths);
    println!("kept per layer with z-culling: {kept:?}");
    assert!(kept[1] > 0.6 && kept[8] < 0.4, "{kept:?}");
}

#[test]
fn a_ray_stops_after_max_count_hits() {
    // MAX_COUNT = 3 of 8 hidden layers: every ray handles exactly three hits, so at most three
    // distinct layers reach a pixel's reservoir and hits past the third are never kept.
    let gpu = gpu();
    let depths: Vec<f32> = (0..9).map(|i| 1.0 + 0.5 * i as f32).collect();
    let settings = RaySdSettings {
        reservoir: 2,
        max_count: 3,
        z_cull: false,
        ..RaySdSettings::default()
    };
    let (slots, hits) = ray_map(&gpu, &facing_layers(&depths), settings);
    assert_eq!(slots.len(), 2);
    assert!(
        hits.iter().all(|&h| h == 3),
        "hits per ray: {:?}",
        &hits[..8]
    );
    // Every pixel keeps two distinct layers of the three its ray met.
    for (p, (&a, &b)) in slots[0].iter().zip(&slots[1]).enumerate() {
        assert!(
            a > 0.0 && b > 0.0 && (a - b).abs() > 0.25,
            "pixel {p}: {a} {b}"
        );
    }
}

#[test]
fn settings_out_of_range_are_clear_errors() {
    let gpu = gpu();
    let scene = facing_layers(&[1.0, 2.0]);
    for (ray_sd, field) in [
        (
            RaySdSettings {
                reservoir: 9,
                ..Default::default()
            },
            "ray_sd.reservoir",
        ),
        (
            RaySdSettings {
                reservoir: 4,
                max_count: 3,
                ..Default::default()
            },
            "ray_sd.max_count",
        ),
        (
            RaySdSettings {
                guard_band: Some(4096),
                ..Default::default()
            },
            "ray_sd.guard_band",
        ),
    ] {
        let settings = AoSettings {
            technique: Technique::RaySdVao,
            ray_sd,
            ..Default::default()
        };
        let e = Renderer::new(&gpu, &scene, &settings, SIZE, SIZE, 0)
            .err()
            .expect("out of range")
            .to_string();
        assert!(e.contains(field), "{e}");
    }
}

#[test]
fn a_map_over_the_storage_binding_limit_is_a_clear_error() {
    // The widest guard band with 8 slots per texel at full resolution: (64 + 2·2048)² texels of
    // 32 bytes, 554 MB, over lavapipe's 128 MiB binding limit. Where an adapter allows it, the
    // map is made.
    let gpu = gpu();
    let scene = facing_layers(&[1.0, 2.0]);
    let mut settings = AoSettings {
        technique: Technique::RaySdVao,
        ..Default::default()
    };
    settings.ray_sd.reservoir = 8;
    settings.ray_sd.guard_band = Some(2048);
    let side = u64::from(SIZE + 2 * 2048);
    let bytes = side * side * 32;
    let result = Renderer::new(&gpu, &scene, &settings, SIZE, SIZE, 0)
        .and_then(|mut r| r.render(&camera(Vec3::ZERO, Vec3::NEG_Z, 90.0), None));
    if bytes > gpu.device.limits().max_storage_buffer_binding_size {
        let e = result.expect_err("over the limit").to_string();
        assert!(
            e.contains("storage-binding limit") && e.contains("ray_sd.guard_band"),
            "{e}"
        );
    } else {
        result.expect("within the adapter's limit");
    }
}

#[test]
fn ray_sd_vao_beats_vao_and_raster_sd_svao_against_the_ground_truth() {
    // The protocol of stochastic_depth.rs's quality test (blurred output against the blurred
    // `vao` ground truth, 160×96, guard band 32): the ray-traced map with N = 4 at full
    // resolution against `vao` and the raster `sd-svao` (S = 4, α = 1.5/S). Measured on lavapipe
    // with ray intervals (the default): stairs 4.4e-6 against vao 1.45e-3 and sd-svao 1.5e-4
    // (3.8e-5 without intervals: the reservoir then also holds depths no sample needs); tower
    // 1.46e-5 against vao 6.55e-5 (4.5×) and sd-svao 1.60e-5. Tower's remainder does not move with
    // N = 8, MAX_COUNT = 16 or without z-culling (`obscura compare --reference-model vao`, same
    // size), so it is not the reservoir's; nor is it the border's here (this framebuffer's own
    // guard band is 32 px): the map's guard band, on by default (48 px at this height), moved
    // tower from 1.46e-5 to 1.44e-5. Issue 12's 5× is missed on tower at this size, which is
    // held to 4× here (at 320×192 with the default 16 px framebuffer band, where samples leave
    // the framebuffer far more often, the map's band takes tower's 1/4-resolution MSE from
    // 6.2e-4 to 3.6e-5, 19× below `vao`: BENCHMARKS.md).
    let gpu = gpu();
    for name in ["stairs", "tower"] {
        let scene = scene::builtin(name).unwrap();
        let runs = [
            (Technique::Vao, 1),
            (Technique::SdSvao, 1),
            (Technique::RaySdVao, 1),
            (Technique::RaySdVao, 4),
        ]
        .map(|(technique, resolution)| {
            let mut s = AoSettings {
                technique,
                ..Default::default()
            };
            s.ray_sd.resolution = resolution;
            s
        });
        let errors = mse_against_blurred_vao_truth(&gpu, &scene, &runs);
        let [vao, raster, ray, quarter] = errors[..] else {
            unreachable!()
        };
        println!(
            "{name}: MSE vao {vao:.3e}, sd-svao {raster:.3e}, ray-sd-vao {ray:.3e}, \
             at 1/4 resolution {quarter:.3e}"
        );
        // At 1/4 resolution a texel is 4×4 pixels of this small image, and near edges its ray
        // stores what lies behind a neighbour (§3.3's aliasing); measured: stairs 8.1e-5, tower
        // 4.9e-5. Held to beating `vao` only.
        assert!(quarter < vao, "{name}: 1/4 {quarter:e} vs vao {vao:e}");
        assert!(
            ray <= raster,
            "{name}: ray-sd-vao {ray:e} vs sd-svao {raster:e}"
        );
        let factor = if name == "stairs" { 5.0 } else { 4.0 };
        assert!(
            ray <= vao / factor,
            "{name}: ray-sd-vao {ray:e} vs vao {vao:e}"
        );
    }
}

#[test]
fn at_the_papers_proportions_the_quarter_resolution_map_beats_vao_five_times() {
    // Issue 12's quality target where the framebuffer's guard band is what the paper used
    // (64 px at 1080p: obscura's default, 16 px at 192 px high), so samples leave the
    // framebuffer as often as there: 1/4-resolution `ray-sd-vao` (N = 4, the map's own band at
    // its default) beats `vao` ≥ 5× in MSE on stairs and tower and is no worse than the raster
    // map at S = 4 as seed 001 made it, without a band (`sd-svao`). Measured on lavapipe:
    // stairs 5.8e-5 against vao 2.0e-3 and the bandless sd-svao 5.2e-4; tower 3.7e-5 against
    // 6.8e-4 and 6.1e-4. Without its band the 1/4 map measured 4.4e-4 and 6.2e-4 (the test
    // fails). The raster map with its own band at its default (issue 62) must beat `vao` ≥ 5×
    // as well: measured 1.4e-4 on stairs and 3.0e-5 on tower, where it beats the 1/4 map.
    let gpu = gpu();
    for name in ["stairs", "tower"] {
        let scene = scene::builtin(name).unwrap();
        let settings = |technique, raster_band: Option<u32>| {
            let mut s = AoSettings {
                technique,
                ..Default::default()
            };
            s.ray_sd.resolution = 4;
            s.stochastic_depth.guard_band = raster_band;
            s
        };
        let runs = [
            settings(Technique::Vao, None),
            settings(Technique::SdSvao, Some(0)),
            settings(Technique::SdSvao, None),
            settings(Technique::RaySdVao, None),
        ];
        let size = (320, 192, obscura::default_guard_band(192));
        let errors = mse_against_blurred_vao_truth_at(&gpu, &scene, &runs, size);
        let [vao, bandless, banded, quarter] = errors[..] else {
            unreachable!()
        };
        println!(
            "{name}: MSE vao {vao:.3e}, sd-svao without a band {bandless:.3e}, with its default \
             band {banded:.3e}, ray-sd-vao 1/4 {quarter:.3e}"
        );
        assert!(quarter <= vao / 5.0, "{name}: {quarter:e} vs vao {vao:e}");
        assert!(
            quarter <= bandless,
            "{name}: {quarter:e} vs sd-svao without a band {bandless:e}"
        );
        assert!(
            banded <= vao / 5.0,
            "{name}: sd-svao with its band {banded:e} vs vao {vao:e}"
        );
    }
}

#[test]
fn the_radius_cutoff_only_removes_requests_near_the_shading_pixel() {
    // Seed 002 §3.4: samples nearer than t pixels to their pixel never request the map. A cutoff
    // larger than the image leaves nothing to request, and the two-phase image is `vao`'s; the
    // paper's t = 6 requests fewer pixels than no cutoff.
    let gpu = gpu();
    let scene = scene::builtin("stairs").unwrap();
    let camera = scene.cameras[0].camera;
    let run = |technique, cutoff: f32| {
        let mut s = AoSettings {
            technique,
            ..Default::default()
        };
        s.blur.enabled = false;
        s.ray_sd.radius_cutoff = cutoff;
        // No map guard band: its samples off the framebuffer request it whatever the cutoff
        // (the authors force them), which this test is not about.
        s.ray_sd.guard_band = Some(0);
        let mut r = Renderer::new(&gpu, &scene, &s, 160, 96, 16).unwrap();
        r.render(&camera, None).unwrap();
        let requested = r
            .read_sd_requests()
            .unwrap()
            .map_or(0, |m| m.iter().filter(|&&v| v != 0).count());
        (r.read_raw_ao().unwrap(), requested)
    };
    let (vao, _) = run(Technique::Vao, 0.0);
    let (all, requested_all) = run(Technique::RaySdVao, 0.0);
    let (cut, requested_cut) = run(Technique::RaySdVao, 6.0);
    let (none, requested_none) = run(Technique::RaySdVao, 1.0e6);
    println!("requested pixels: no cutoff {requested_all}, 6 px {requested_cut}, 1e6 px {requested_none}");
    assert!(requested_all > 0 && requested_cut < requested_all && requested_none == 0);
    let worst = max_abs_diff(&none, &vao);
    assert!(worst <= 1e-5, "{worst}");
    assert!(
        max_abs_diff(&cut, &all) > 0.0,
        "the cutoff changes something"
    );
}

#[test]
fn ray_intervals_drop_only_depths_no_sample_needs() {
    // Seed 002 §3.2: phase 1 records per pixel the depths its samples need (VAO: where a surface
    // can change the sample's column), and the map's rays cover only those. With a reservoir
    // large enough for every hidden layer (N = 8, MAX_COUNT = 64) nothing the samples read is
    // lost, so the image is the same; the rays meet fewer surfaces.
    let gpu = gpu();
    for name in ["stairs", "colonnade", "tower"] {
        let scene = scene::builtin(name).unwrap();
        let camera = scene.cameras[0].camera;
        let run = |intervals: bool| {
            let mut s = AoSettings {
                technique: Technique::RaySdVao,
                ..Default::default()
            };
            s.blur.enabled = false;
            s.ray_sd.reservoir = 8;
            s.ray_sd.max_count = 64;
            s.ray_sd.intervals = intervals;
            let mut r = Renderer::new(&gpu, &scene, &s, 160, 96, 16).unwrap();
            r.render(&camera, None).unwrap();
            let hits: u64 = r
                .read_ray_sd_hits()
                .unwrap()
                .unwrap()
                .iter()
                .map(|&h| u64::from(h))
                .sum();
            (r.read_raw_ao().unwrap(), hits)
        };
        let (with, hits_with) = run(true);
        let (without, hits_without) = run(false);
        let worst = max_abs_diff(&with, &without);
        println!("{name}: hits {hits_without} -> {hits_with} with intervals, max |Δ AO| {worst:e}");
        assert!(
            worst <= 1e-6,
            "{name}: intervals changed the image by {worst}"
        );
        assert!(
            hits_with < hits_without,
            "{name}: {hits_with} vs {hits_without}"
        );
    }
}

#[test]
fn the_map_guard_band_restores_occlusion_from_beyond_the_framebuffer() {
    // Seed 002 §3.5: a step whose face lies just past the framebuffer's right edge (its 4 px
    // guard band included) darkens the floor beside the visible edge, but the samples that reach
    // it fall off the framebuffer, where without the map's guard band they read the
    // framebuffer's edge (more floor). With a band wider than the samples reach (radius 1 m ≈
    // 12 px here), those samples read the map's band texels, which hold every layer there, the
    // step's top included. Against the ray-traced `vao` truth, the error of the visible columns
    // near the edge must drop; pixels whose samples all stay on the framebuffer do not change.
    let gpu = gpu();
    let case = edge_band_case();
    let (w, _, frame_guard) = case.size;
    for resolution in [1, 4] {
        let run = |guard_band: u32| {
            let r = case.render(&gpu, Technique::RaySdVao, |s| {
                s.ray_sd.resolution = resolution;
                s.ray_sd.guard_band = Some(guard_band);
            });
            let extent = r.ray_sd_map_size().unwrap().unwrap();
            let (mw, mh, g) = (extent.width, extent.height, extent.guard_texels);
            assert_eq!(g, guard_band.div_ceil(resolution));
            assert_eq!(mw, (w + 2 * frame_guard).div_ceil(resolution) + 2 * g);
            let requests = r.read_sd_request_texels().unwrap().unwrap();
            assert_eq!(requests.len(), (mw * mh) as usize);
            let in_band = requested_in_band(&requests, mw, g);
            (r.read_raw_ao().unwrap(), in_band, *r.view().unwrap())
        };
        let (without, band_without, view) = run(0);
        let (with, band_with, _) = run(32);
        let reference = case.reference(view);
        let e_without = case.edge_error(&without, &reference);
        let e_with = case.edge_error(&with, &reference);
        println!(
            "1/{resolution}: edge MSE {e_without:.3e} without the map's guard band, {e_with:.3e} \
             with 32 px; band texels requested {band_without} -> {band_with}"
        );
        assert_eq!(band_without, 0);
        assert!(
            band_with > 0,
            "1/{resolution}: nothing requested in the band"
        );
        // At full resolution the band texels hold exactly the surfaces the samples meet
        // (measured on lavapipe: 3.2e-3 -> 4e-11). At 1/4 a texel is 4×4 pixels (34 cm here) and
        // its one jittered ray decides for all of them, so samples near the step's edge read the
        // step or the floor beside it by the jitter's row (§3.3's aliasing; measured 3.2e-3 ->
        // 1.5e-3).
        let factor = if resolution == 1 { 1000.0 } else { 1.5 };
        assert!(
            e_with < e_without / factor,
            "1/{resolution}: {e_with:e} vs {e_without:e}"
        );
        // Samples reach at most 12 px: the left half never leaves the framebuffer.
        let worst = case.left_half_difference(&with, &without);
        assert!(
            worst <= 1e-6,
            "1/{resolution}: the band changed the left half by {worst}"
        );
    }
}

#[test]
fn the_reservoir_fills_its_slots_in_order() {
    // The readers stop at a texel's first empty slot (samples.wgsl's SD_COMPACT): the first N
    // distinct hits take the slots in order and a later hit only overwrites one, so no slot is
    // empty before a filled one. Built-in scenes with few and many layers, every texel traced
    // (`ray-sd-vao-full`) and the two-phase row at 1/4 resolution with its guard band, with and
    // without z-culling.
    let gpu = gpu();
    let (mut partly_filled, mut full) = (0, 0);
    for name in ["stairs", "grass", "layers"] {
        let scene = scene::builtin(name).unwrap();
        for technique in [Technique::RaySdVaoFull, Technique::RaySdVao] {
            for z_cull in [true, false] {
                let settings = AoSettings {
                    technique,
                    ray_sd: RaySdSettings {
                        z_cull,
                        ..RaySdSettings::default()
                    },
                    ..Default::default()
                };
                let mut r = Renderer::new(&gpu, &scene, &settings, 96, 64, 8).unwrap();
                r.render(&scene.cameras[0].camera, None).unwrap();
                let slots = r.read_stochastic_depth().unwrap().unwrap();
                for p in 0..slots[0].len() {
                    let filled: Vec<bool> = slots.iter().map(|l| l[p] > 0.0).collect();
                    let count = filled.iter().filter(|&&f| f).count();
                    assert!(
                        filled.iter().take(count).all(|&f| f),
                        "{name} {technique} z_cull {z_cull}: texel of pixel {p} holds {filled:?}"
                    );
                    partly_filled += usize::from(count > 0 && count < slots.len());
                    full += usize::from(count == slots.len());
                }
            }
        }
    }
    assert!(
        partly_filled > 1000 && full > 1000,
        "{partly_filled} partly filled, {full} full"
    );
}
