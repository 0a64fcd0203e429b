//! Temporal accumulation (issue 13) on lavapipe: a still camera converges to the mean over the 16
//! pattern rotations, a disocclusion restarts its history instead of smearing the old one, and
//! along a moving camera the accumulated AO flickers less than the single-frame technique.

use crate::common;

use obscura::bvh::Bvh;
use obscura::filter::temporal::HistoryTexel;
use obscura::metrics::temporal::{path_metrics, PathFrame, Reprojection};
use obscura::reference::cpu_blur::cpu_blur;
use obscura::reference::cpu_vao::cpu_vao_turned;
use obscura::reference::ground_truth::{render_reference, ReferenceModel, ReferenceSettings};
use obscura::scene::{self, Camera};
use obscura::{AoSettings, FrameView, Renderer, Technique};

const W: u32 = 96;
const H: u32 = 64;
const GUARD: u32 = 16;

fn temporal_settings(technique: Technique, blur: bool) -> AoSettings {
    let mut s = common::technique_settings(technique, blur);
    s.temporal.enabled = true;
    s
}

fn raw(renderer: &Renderer) -> Vec<f32> {
    renderer.read_raw_ao().unwrap()
}

fn history(renderer: &Renderer) -> Vec<HistoryTexel> {
    renderer
        .ambient_occlusion()
        .unwrap()
        .read_temporal_history()
        .unwrap()
        .unwrap()
}

#[test]
fn a_still_camera_converges_to_the_mean_over_all_rotations() {
    let gpu = common::gpu();
    let scene = scene::builtin("stairs").unwrap();
    let camera = scene.cameras[0].camera;
    for technique in [Technique::Vao, Technique::Hbao, Technique::Gtao] {
        // Unclamped: the plain running mean over the frames (the output is blurred afterwards,
        // so the blur is off here to read the mean itself).
        let mut settings = temporal_settings(technique, false);
        settings.temporal.clamp = false;
        let mut r = Renderer::new(&gpu, &scene, &settings, W, H, GUARD).unwrap();
        let mut frames = Vec::new();
        for _ in 0..16 {
            r.render(&camera, None).unwrap();
            frames.push(raw(&r));
        }
        let accumulated = r.read_ao().unwrap();
        // The pattern turned every frame: consecutive frames differ, and the 17th frame has
        // the first frame's rotation again.
        assert_ne!(
            frames[0], frames[1],
            "{technique}: the pattern did not turn"
        );
        r.render(&camera, None).unwrap();
        assert_eq!(raw(&r), frames[0], "{technique}: period is not 16 frames");
        let n = frames.len() as f64;
        let mut worst = 0.0f64;
        for (i, &a) in accumulated.iter().enumerate() {
            let mean = frames.iter().map(|f| f64::from(f[i])).sum::<f64>() / n;
            worst = worst.max((f64::from(a) - mean).abs());
        }
        assert!(
            worst < 2e-6,
            "{technique}: accumulated AO {worst} from the mean"
        );
        // Each pixel saw all 16 rotations: the per-pixel pattern noise is gone, so neighbours
        // on the same surface agree far better than in one frame.
        let roughness = |img: &[f32]| -> f64 {
            let mut sum = 0.0;
            for y in 0..H as usize {
                for x in 1..W as usize {
                    sum += f64::from((img[y * W as usize + x] - img[y * W as usize + x - 1]).abs());
                }
            }
            sum
        };
        println!(
            "{technique}: roughness {:.1} -> {:.1}",
            roughness(&frames[0]),
            roughness(&accumulated)
        );
        assert!(
            roughness(&accumulated) < 0.85 * roughness(&frames[0]),
            "{technique}: {} vs {}",
            roughness(&accumulated),
            roughness(&frames[0])
        );
    }
}

#[test]
fn the_history_is_clipped_to_the_spread_of_the_pixel_and_its_four_neighbours() {
    // A still camera's second frame: the history is the first frame's AO at the same texel (one
    // frame, 24-bit fixed point), clipped to mean ± σ of this frame's raw AO over the pixel and
    // its four edge neighbours (clamped into the image), then averaged with this frame's AO.
    let gpu = common::gpu();
    let scene = scene::builtin("stairs").unwrap();
    let camera = scene.cameras[0].camera;
    let settings = temporal_settings(Technique::Vao, false);
    assert!(settings.temporal.clamp, "the clamp is on by default");
    let mut r = Renderer::new(&gpu, &scene, &settings, W, H, GUARD).unwrap();
    r.render(&camera, None).unwrap();
    let first = r.read_ao().unwrap();
    assert_eq!(first, raw(&r), "the first frame has no history");
    r.render(&camera, None).unwrap();
    let current = raw(&r);
    let out = r.read_ao().unwrap();
    let depth = r.read_gbuffer().unwrap().visible_depth(GUARD);
    let (w, h) = (W as i64, H as i64);
    let at =
        |x: i64, y: i64| f64::from(current[(y.clamp(0, h - 1) * w + x.clamp(0, w - 1)) as usize]);
    let (mut worst, mut clipped) = (0.0f64, 0);
    for y in 0..h {
        for x in 0..w {
            let i = (y * w + x) as usize;
            let (expected, tolerance) = if depth[i] <= 0.0 {
                (f64::from(current[i]), 2e-6)
            } else {
                let plus = [
                    at(x, y),
                    at(x - 1, y),
                    at(x + 1, y),
                    at(x, y - 1),
                    at(x, y + 1),
                ];
                let mean = plus.iter().sum::<f64>() / 5.0;
                let sigma = (plus.iter().map(|v| v * v).sum::<f64>() / 5.0 - mean * mean)
                    .max(0.0)
                    .sqrt();
                let history =
                    (f64::from(first[i].clamp(0.0, 1.0)) * 16_777_215.0).round() / 16_777_215.0;
                let past = history.clamp(mean - sigma, mean + sigma);
                if (past - history).abs() > 1e-3 {
                    clipped += 1;
                }
                // The shader's σ² = E[a²] − mean² in f32 (values ≤ 1) is off by up to a few ulps
                // of 1, and σ by that over 2σ (at most its square root) where σ is small; the
                // output moves by half of σ's error.
                let variance_error = 4.0 * f64::from(f32::EPSILON);
                let sigma_error = variance_error.sqrt().min(variance_error / (2.0 * sigma));
                (
                    past + (f64::from(current[i]) - past) * 0.5,
                    2e-6 + 0.5 * sigma_error,
                )
            };
            worst = worst.max((f64::from(out[i]) - expected).abs() / tolerance);
        }
    }
    assert!(
        worst <= 1.0,
        "accumulated AO {worst}× its tolerance from the clipped mean"
    );
    // The pattern turned between the frames, so the clip is exercised.
    assert!(clipped > (W * H / 20) as usize, "{clipped} pixels clipped");
}

/// The frames of the `stairs` dolly at the test size, and their views.
fn dolly(frames: u32) -> (scene::Scene, Vec<Camera>) {
    let scene = scene::builtin("stairs").unwrap();
    let path = scene.path("dolly", W as f32 / H as f32).unwrap();
    let cameras = path
        .sample(frames)
        .unwrap()
        .into_iter()
        .map(|(_, c)| c)
        .collect();
    (scene, cameras)
}

#[test]
fn disocclusions_restart_their_history() {
    let gpu = common::gpu();
    let (scene, cameras) = dolly(12);
    let settings = temporal_settings(Technique::Vao, false);
    let mut r = Renderer::new(&gpu, &scene, &settings, W, H, GUARD).unwrap();
    let near = obscura::near_plane(&scene);
    let mut previous: Option<(FrameView, Vec<f32>)> = None;
    let (mut restarted, mut carried) = (0, 0);
    for camera in &cameras[..4] {
        r.render(camera, None).unwrap();
        let view = FrameView::new(*camera, W, H, GUARD, near);
        let depth = r.read_gbuffer().unwrap().visible_depth(GUARD);
        let history = history(&r);
        let out = r.read_ao().unwrap();
        let current = raw(&r);
        if let Some((prev_view, prev_depth)) = &previous {
            // The metrics' reprojection is the oracle: where it finds no texel of the same
            // surface in the previous frame, the history must restart (1 frame, this frame's AO).
            let oracle = Reprojection::new(
                &PathFrame {
                    view: *prev_view,
                    depth: prev_depth,
                },
                &PathFrame {
                    view,
                    depth: &depth,
                },
            )
            .unwrap();
            let mut disagree = 0;
            for (i, h) in history.iter().enumerate() {
                if depth[i] <= 0.0 {
                    continue;
                }
                match oracle.sample(&current, i) {
                    None if h.frames != 1 || out[i] != current[i] => disagree += 1,
                    None => restarted += 1,
                    Some(_) if h.frames > 1 => carried += 1,
                    Some(_) => {}
                }
            }
            // Bilinear weights at the tolerance's edge may round the other way on the GPU.
            assert!(
                disagree <= (W * H / 200) as usize,
                "{disagree} disoccluded pixels kept history"
            );
        }
        previous = Some((view, depth));
    }
    assert!(restarted > 50, "the dolly disoccludes: {restarted}");
    assert!(
        carried > 10 * restarted,
        "{carried} carried, {restarted} restarted"
    );
}

/// The corner scene (floor meeting a wall) seen from a camera trucking along it, `frames` views.
fn corner_truck(frames: usize) -> Vec<Camera> {
    (0..frames)
        .map(|k| {
            let x = 0.04 * k as f32;
            common::camera(
                glam::Vec3::new(0.6 + x, 2.0, 3.0),
                glam::Vec3::new(x, 0.3, 0.0),
                50.0,
            )
        })
        .collect()
}

#[test]
fn each_frame_turns_the_pattern_as_the_cpu_oracle_does() {
    let gpu = common::gpu();
    let scene = common::corner_scene();
    let settings = temporal_settings(Technique::Vao, false);
    let mut r = Renderer::new(&gpu, &scene, &settings, W, H, GUARD).unwrap();
    let camera = corner_truck(1)[0];
    // The k-th frame (k = 1, 2, …) runs with the pattern turned by k entries.
    for k in 1..=3u32 {
        r.render(&camera, None).unwrap();
        let g = r.read_gbuffer().unwrap();
        let screen = r.view().unwrap().screen();
        let cpu = cpu_vao_turned(&g, &screen, &settings.vao, k);
        common::assert_mirrors(&format!("frame {k}"), &raw(&r), (cpu.ao, cpu.ambiguous));
    }
}

/// The moving-camera test runs without the blur: on this plain corner the blur alone already
/// removes most of the pattern (measured with it on: temporal error 0.00027 → 0.00021, MAE
/// 0.0010 → 0.0015, the accumulation's lag), so the test looks at what the accumulation itself
/// does to the raw AO.
const BLUR: bool = false;

#[test]
fn a_moving_camera_flickers_less_with_accumulation() {
    // Single-frame VAO carries its 4×4 rotation pattern, fixed on the screen, so as the camera
    // moves the pattern slides over the surfaces and flickers; accumulated frames average the
    // rotations. The reference is what both estimate: VAO averaged over all 16 rotations (the
    // CPU oracle; one depth layer, so nothing is hidden).
    let gpu = common::gpu();
    let scene = common::corner_scene();
    let cameras = corner_truck(16);
    let run = |temporal: bool| {
        let mut settings = common::technique_settings(Technique::Vao, BLUR);
        settings.temporal.enabled = temporal;
        let mut r = Renderer::new(&gpu, &scene, &settings, W, H, GUARD).unwrap();
        let mut out = Vec::new();
        for c in &cameras {
            r.render(c, None).unwrap();
            let g = r.read_gbuffer().unwrap();
            out.push((r.read_ao().unwrap(), g, *r.view().unwrap()));
        }
        (out, settings)
    };
    let (plain, settings) = run(false);
    let (accumulated, _) = run(true);
    let mut reference = Vec::new();
    let mut frames_depth = Vec::new();
    for (k, (_, g, view)) in plain.iter().enumerate() {
        let screen = view.screen();
        let mut mean = vec![0.0f32; (W * H) as usize];
        for offset in 0..16 {
            for (m, v) in mean
                .iter_mut()
                .zip(cpu_vao_turned(g, &screen, &settings.vao, offset).ao)
            {
                *m += v / 16.0;
            }
        }
        if k == 0 {
            // The `vao-mean` reference model is this mean, traced from the triangles.
            let traced = render_reference(
                &scene,
                &Bvh::build(&scene),
                *view,
                &ReferenceSettings {
                    model: ReferenceModel::VaoMean,
                    vao: settings.vao,
                    ..Default::default()
                },
                &|_| {},
            );
            let off = traced
                .iter()
                .zip(&mean)
                .filter(|(a, b)| (*a - *b).abs() > 1.0 / 255.0)
                .count();
            assert!(off * 100 <= traced.len(), "vao-mean: {off} pixels off");
        }
        reference.push(match BLUR {
            true => cpu_blur(&mean, g, &screen, &settings.blur),
            false => mean,
        });
        frames_depth.push(g.visible_depth(GUARD));
    }
    let frames: Vec<PathFrame> = plain
        .iter()
        .zip(&frames_depth)
        .map(|((_, _, view), depth)| PathFrame { view: *view, depth })
        .collect();
    let images = |run: &[(
        Vec<f32>,
        obscura::reference::cpu_vao::GBufferImage,
        FrameView,
    )]| { run.iter().map(|(ao, _, _)| ao.clone()).collect::<Vec<_>>() };
    let (plain, accumulated) = (images(&plain), images(&accumulated));
    let plain_m = path_metrics(&frames, &plain, &reference).unwrap();
    let acc_m = path_metrics(&frames, &accumulated, &reference).unwrap();
    // Over the second half of the path, once the history has filled.
    let mae = |images: &[Vec<f32>]| -> f64 {
        images[8..]
            .iter()
            .zip(&reference[8..])
            .map(|(a, r)| {
                a.iter()
                    .zip(r)
                    .map(|(a, r)| f64::from((a - r).abs()))
                    .sum::<f64>()
                    / a.len() as f64
            })
            .sum::<f64>()
            / 8.0
    };
    println!(
        "temporal error {:.5} -> {:.5}, popping {:.5} -> {:.5}, MAE {:.5} -> {:.5}",
        plain_m.temporal_error,
        acc_m.temporal_error,
        plain_m.popping,
        acc_m.popping,
        mae(&plain),
        mae(&accumulated)
    );
    assert!(
        plain_m.popping > 0.01,
        "the pattern should pop: {}",
        plain_m.popping
    );
    assert!(acc_m.popping < 1e-3, "{}", acc_m.popping);
    assert!(
        acc_m.temporal_error < plain_m.temporal_error / 3.0,
        "{} vs {}",
        acc_m.temporal_error,
        plain_m.temporal_error
    );
    assert!(mae(&accumulated) < mae(&plain));
}

#[test]
fn encoding_without_a_camera_is_an_error_and_reset_restarts() {
    let gpu = common::gpu();
    let scene = scene::builtin("cornell").unwrap();
    let settings = temporal_settings(Technique::Vao, true);
    let mut r = Renderer::new(&gpu, &scene, &settings, W, H, GUARD).unwrap();
    let camera = scene.cameras[0].camera;
    for _ in 0..3 {
        r.render(&camera, None).unwrap();
    }
    let ao = r.ambient_occlusion().unwrap();
    let frames = |ao: &obscura::AmbientOcclusion| {
        ao.read_temporal_history()
            .unwrap()
            .unwrap()
            .iter()
            .map(|h| h.frames)
            .max()
            .unwrap()
    };
    assert_eq!(frames(ao), 3);
    ao.reset_temporal();
    r.render(&camera, None).unwrap();
    assert_eq!(frames(r.ambient_occlusion().unwrap()), 1);

    // An engine that never sets the camera gets a clear error.
    let screen = FrameView::new(camera, W, H, GUARD, 0.05).screen();
    let engine =
        obscura::AmbientOcclusion::new(&gpu, &settings, screen, Default::default()).unwrap();
    let size = (W + 2 * GUARD, H + 2 * GUARD);
    let texels = (size.0 * size.1) as usize;
    let depth = common::upload_texture(
        &gpu,
        wgpu::TextureFormat::R32Float,
        size,
        bytemuck::cast_slice(&vec![1.0f32; texels]),
        4,
    );
    let normals = common::upload_texture(
        &gpu,
        wgpu::TextureFormat::Rgba32Float,
        size,
        bytemuck::cast_slice(&vec![[0.0f32, 0.0, 1.0, 0.0]; texels]),
        16,
    );
    let err = common::encode_and_submit(&gpu, &engine, &depth, &normals)
        .unwrap_err()
        .to_string();
    assert!(err.contains("set_camera"), "{err}");
}

#[test]
fn the_stochastic_maps_change_per_frame_only_under_accumulation() {
    // With accumulation the maps' random choices (coverage masks; the ray-traced map's
    // reservoir and low-resolution jitter) change every frame, so their noise averages out as the
    // pattern's does; without it every frame is the same (the determinism the tests rely on).
    let gpu = common::gpu();
    let scene = scene::builtin("stairs").unwrap();
    let camera = scene.cameras[0].camera;
    for (technique, ray_sd_res) in [(Technique::SdVao, 1), (Technique::RaySdVaoFull, 4)] {
        for temporal in [false, true] {
            let mut settings = common::technique_settings(technique, true);
            settings.temporal.enabled = temporal;
            settings.ray_sd.resolution = ray_sd_res;
            let mut r = Renderer::new(&gpu, &scene, &settings, W, H, GUARD).unwrap();
            let mut maps = Vec::new();
            for _ in 0..2 {
                r.render(&camera, None).unwrap();
                maps.push(r.read_stochastic_depth().unwrap().unwrap());
            }
            assert_eq!(
                maps[0] != maps[1],
                temporal,
                "{technique}, temporal {temporal}: the map should change only with accumulation"
            );
        }
    }
}

#[test]
fn the_history_keeps_its_surface_at_any_scene_scale() {
    // A still camera over `stairs` scaled by 1e-5 to 1e6 (depths of about 1e-4 to 1e7 world
    // units: a large scene in millimetres is past 65,504, where an f16 depth overflowed and every
    // pixel restarted): every visible pixel's history must match its own surface again each
    // frame, so after 4 frames it holds 4, at the G-buffer's depth within the history's 16-bit
    // rounding (2^-10 relative).
    let gpu = common::gpu();
    for scale in [1e-5f32, 1.0, 1e3, 1e6] {
        let (scene, camera) = common::scaled_builtin("stairs", scale);
        let settings = temporal_settings(Technique::Vao, false).scaled(scale);
        let mut r = Renderer::new(&gpu, &scene, &settings, W, H, GUARD).unwrap();
        for _ in 0..4 {
            r.render(&camera, None).unwrap();
        }
        let depth = r.read_gbuffer().unwrap().visible_depth(GUARD);
        let history = history(&r);
        let (mut visible, mut short, mut worst) = (0, 0, 0.0f32);
        for (h, &z) in history.iter().zip(&depth) {
            if z <= 0.0 {
                assert_eq!(h.frames, 0, "scale {scale}: background keeps no history");
                continue;
            }
            visible += 1;
            if h.frames != 4 {
                short += 1;
            }
            worst = worst.max((h.depth - z).abs() / z);
        }
        assert!(
            visible > (W * H / 2) as usize,
            "scale {scale}: {visible} visible"
        );
        assert_eq!(
            short, 0,
            "scale {scale}: {short} of {visible} pixels restarted"
        );
        assert!(
            worst <= 1.0 / 1024.0,
            "scale {scale}: history depth {worst} from the G-buffer's"
        );
    }
}
