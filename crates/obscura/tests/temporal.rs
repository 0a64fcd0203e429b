//! Temporal accumulation (issue 13) on lavapipe: a still camera converges to the mean over the 16
//! pattern rotations, a disocclusion restarts its history instead of smearing the old one, and
//! along a moving camera the accumulated AO flickers less than the single-frame technique.

mod common;

use obscura::bvh::Bvh;
use obscura::metrics::temporal::{path_metrics, PathFrame, Reprojection};
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

#[test]
fn a_still_camera_converges_to_the_mean_over_all_rotations() {
    let gpu = common::gpu();
    let scene = scene::builtin("stairs").unwrap();
    let camera = scene.cameras[0].camera;
    for technique in [Technique::Vao, Technique::Hbao, Technique::Gtao] {
        // Unblurred, so the accumulator's input is the raw AO of each frame.
        let settings = temporal_settings(technique, false);
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
        let history = r
            .ambient_occlusion()
            .unwrap()
            .read_temporal_history()
            .unwrap()
            .unwrap();
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

#[test]
fn a_moving_camera_flickers_less_with_accumulation() {
    let gpu = common::gpu();
    let (scene, cameras) = dolly(12);
    let near = obscura::near_plane(&scene);
    let views: Vec<FrameView> = cameras
        .iter()
        .map(|c| FrameView::new(*c, W, H, GUARD, near))
        .collect();
    let run = |temporal: bool| {
        let mut settings = common::technique_settings(Technique::Vao, true);
        settings.temporal.enabled = temporal;
        let mut r = Renderer::new(&gpu, &scene, &settings, W, H, GUARD).unwrap();
        let mut ao = Vec::new();
        let mut depth = Vec::new();
        for c in &cameras {
            r.render(c, None).unwrap();
            ao.push(r.read_ao().unwrap());
            depth.push(r.read_gbuffer().unwrap().visible_depth(GUARD));
        }
        (ao, depth)
    };
    let (plain, depth) = run(false);
    let (accumulated, _) = run(true);
    // The ground truth of AO within VAO's radius: cosine-weighted hemisphere rays.
    let bvh = Bvh::build(&scene);
    let reference_settings = ReferenceSettings {
        model: ReferenceModel::Hemisphere,
        spp: 256,
        vao: AoSettings::default().vao,
        ..ReferenceSettings::default()
    };
    let reference: Vec<Vec<f32>> = views
        .iter()
        .map(|v| render_reference(&scene, &bvh, *v, &reference_settings, &|_| {}))
        .collect();
    let frames: Vec<PathFrame> = views
        .iter()
        .zip(&depth)
        .map(|(&view, depth)| PathFrame { view, depth })
        .collect();
    let plain_m = path_metrics(&frames, &plain, &reference).unwrap();
    let acc_m = path_metrics(&frames, &accumulated, &reference).unwrap();
    let mae = |images: &[Vec<f32>]| -> f64 {
        images
            .iter()
            .zip(&reference)
            .map(|(a, r)| {
                a.iter()
                    .zip(r)
                    .map(|(a, r)| f64::from((a - r).abs()))
                    .sum::<f64>()
                    / a.len() as f64
            })
            .sum::<f64>()
            / images.len() as f64
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
        acc_m.temporal_error < 0.75 * plain_m.temporal_error,
        "{} vs {}",
        acc_m.temporal_error,
        plain_m.temporal_error
    );
    assert!(mae(&accumulated) <= 1.02 * mae(&plain));
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
