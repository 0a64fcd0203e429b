//! The plugin inside a headless Bevy app (issue 61's tests): the AO Bevy's lighting reads is
//! obscura's own render of the same camera and row; a hidden-depth row reads the scene's meshes
//! and follows them; the lit frame differs from Bevy's SSAO frame only where the AO does.

mod harness;

use bevy::camera::visibility::RenderLayers;
use bevy::diagnostic::{DiagnosticPath, DiagnosticsStore};
use bevy::mesh::{Mesh, Meshable};
use bevy::pbr::ScreenSpaceAmbientOcclusion;
use bevy::prelude::*;
use bevy_obscura::ObscuraAo;
use harness::{mae, Harness, ONE_APP};
use obscura::settings::{AoSettings, Preset, Resolution};
use obscura::{Gpu, GpuOptions, Renderer, Technique};

const SIZE: (u32, u32) = (160, 96);

/// obscura's own render of `scene` from `camera`: its G-buffer, no guard band (Bevy renders
/// none), on its own device.
fn own_render(
    scene: &obscura::scene::Scene,
    camera: &obscura::scene::Camera,
    settings: &AoSettings,
) -> Vec<f32> {
    let gpu = Gpu::new(&GpuOptions::default()).expect("a GPU");
    let mut renderer =
        Renderer::new(&gpu, scene, settings, SIZE.0, SIZE.1, 0).expect("obscura's renderer");
    renderer.render(camera, None).expect("obscura renders");
    renderer.read_ao().expect("obscura's AO")
}

/// A built-in scene, the camera it opens with at [`SIZE`], its near plane, and a headless app
/// that has its meshes.
fn scene_app(name: &str) -> (Harness, obscura::scene::Scene, obscura::scene::Camera, f32) {
    let scene = obscura::scene::load(name).unwrap();
    let camera = scene.default_camera(SIZE.0 as f32 / SIZE.1 as f32);
    let near = obscura::view::near_plane(&scene);
    let mut h = Harness::new();
    h.spawn_scene(&scene);
    (h, scene, camera, near)
}

#[test]
fn the_ao_bevy_reads_is_obscuras_own_render_of_the_same_camera_and_row() {
    let _one = ONE_APP.lock().unwrap_or_else(|e| e.into_inner());
    let scene = obscura::scene::load("stairs").unwrap();
    let camera = scene.default_camera(SIZE.0 as f32 / SIZE.1 as f32);
    let near = obscura::view::near_plane(&scene);
    // Screen-space rows (one at half resolution, whose output is the upsample's), and a
    // hidden-depth row that traces the meshes Bevy was given.
    let half = |row: &str, preset| {
        let mut settings = AoSettings::preset(row.parse().unwrap(), preset);
        settings.resolution = Resolution::Half;
        ("gtao, half resolution", settings)
    };
    let full = |row: &'static str, preset| (row, AoSettings::preset(row.parse().unwrap(), preset));
    for (row, settings) in [
        full("gtao", Preset::High),
        half("gtao", Preset::Low),
        full("vao", Preset::Medium),
        full("rt-vao", Preset::Medium),
    ] {
        let mut h = Harness::new();
        h.spawn_scene(&scene);
        let (cam, _) = h.spawn_camera(&camera, near, SIZE, ObscuraAo::with_settings(settings));
        h.frames(3);

        let report = h.report(cam);
        assert_eq!(report.error, None, "{row}");
        let plugin = h.view_ao(cam);
        assert_eq!((plugin.width, plugin.height), SIZE);
        let own = own_render(&scene, &camera, &settings);
        let error = mae(&plugin.values, &own);
        let covered = own.iter().filter(|&&v| v < 0.99).count();
        let over = |t: f32| {
            plugin
                .values
                .iter()
                .zip(&own)
                .filter(|(a, b)| (*a - *b).abs() > t)
                .count()
        };
        eprintln!("{row}: MAE {error:.2e} against obscura's own render, {covered} occluded pixels, {} / {} / {} differ by over 0.01 / 0.1 / 0.3", over(0.01), over(0.1), over(0.3));
        assert!(covered > own.len() / 10, "{row}: the view shows occlusion");
        assert!(
            error <= 2e-3,
            "{row}: MAE {error} against obscura's own render"
        );

        // Bevy's SSAO passes did not run; obscura's did.
        let store = h.app.world().resource::<DiagnosticsStore>();
        let ran = |name: &str| {
            store
                .get(&DiagnosticPath::new(format!("render/{name}/elapsed_cpu")))
                .is_some_and(|d| d.measurement().is_some())
        };
        assert!(ran("obscura_ao"), "{row}: obscura's time span");
        assert!(!ran("ssao"), "{row}: Bevy's SSAO ran as well");
    }
}

#[test]
fn a_hidden_depth_row_reads_the_meshes_and_a_moved_mesh_moves_its_occlusion() {
    let _one = ONE_APP.lock().unwrap_or_else(|e| e.into_inner());
    let mut h = Harness::new();
    let floor = Plane3d::new(Vec3::Y, Vec2::splat(3.0)).mesh().build();
    h.spawn_mesh(floor, Transform::IDENTITY);
    // A box the camera does not draw (another render layer): not in the depth buffer, so only
    // a row that reads the meshes can see it.
    let cube: Mesh = Cuboid::new(0.5, 0.5, 0.5).into();
    let left = Transform::from_xyz(-1.0, 0.25, 0.0);
    let occluder = h.spawn_mesh(cube, left);
    h.app
        .world_mut()
        .entity_mut(occluder)
        .insert(RenderLayers::layer(1));
    let camera = obscura::scene::Camera {
        eye: glam::Vec3::new(0.0, 4.0, 0.001),
        target: glam::Vec3::ZERO,
        up: glam::Vec3::NEG_Z,
        fov_y_deg: 60.0,
    };
    let mut settings = AoSettings::preset("rtao".parse().unwrap(), Preset::High);
    settings.hemisphere.radius = 0.6;
    let (cam, _) = h.spawn_camera(&camera, 0.01, SIZE, ObscuraAo::with_settings(settings));
    let halves = |h: &Harness| {
        let ao = h.view_ao(cam);
        let w = ao.width as usize;
        let mean = |range: std::ops::Range<usize>| {
            let v: Vec<f32> = ao
                .values
                .chunks(w)
                .flat_map(|row| row[range.clone()].to_vec())
                .collect();
            v.iter().sum::<f32>() / v.len() as f32
        };
        (mean(0..w / 2), mean(w / 2..w))
    };
    h.frames(2);
    let (l, r) = halves(&h);
    eprintln!("box on the left: mean AO left {l:.4}, right {r:.4}");
    assert!(l < r - 0.01, "the hidden box darkens the floor beside it");

    h.app
        .world_mut()
        .entity_mut(occluder)
        .insert(Transform::from_xyz(1.0, 0.25, 0.0));
    h.frames(2);
    let (l2, r2) = halves(&h);
    eprintln!("box on the right: mean AO left {l2:.4}, right {r2:.4}");
    assert!(r2 < l2 - 0.01, "the occlusion moved with the box");
    assert!(
        (l2 - r).abs() < 0.005 && (r2 - l).abs() < 0.005,
        "mirror images"
    );

    // A depth-only row cannot see it.
    h.app
        .world_mut()
        .entity_mut(cam)
        .insert(ObscuraAo::new(Technique::Gtao, Preset::High));
    h.frames(2);
    let (l3, r3) = halves(&h);
    assert!((l3 - r3).abs() < 0.002, "gtao sees no box: {l3} vs {r3}");
}

#[test]
fn the_lit_frame_differs_from_bevys_ssao_frame_only_where_the_ao_does() {
    let _one = ONE_APP.lock().unwrap_or_else(|e| e.into_inner());
    let (mut h, _, camera, near) = scene_app("colonnade");
    let order = |i| Camera {
        order: i,
        ..default()
    };
    let (ours, ours_image) = h.spawn_camera(
        &camera,
        near,
        SIZE,
        (order(0), ObscuraAo::new(Technique::Gtao, Preset::High)),
    );
    let (bevys, bevys_image) = h.spawn_camera(
        &camera,
        near,
        SIZE,
        (order(1), ScreenSpaceAmbientOcclusion::default()),
    );
    let (_, plain_image) = h.spawn_camera(&camera, near, SIZE, order(2));
    h.frames(3);
    let (ao_ours, ao_bevys) = (h.view_ao(ours).values, h.view_ao(bevys).values);
    let lit = |image| h.lit_frame(image);
    let (ours_lit, bevys_lit, plain_lit) = (lit(&ours_image), lit(&bevys_image), lit(&plain_image));
    let close = |a: [u8; 4], b: [u8; 4]| a.iter().zip(b).all(|(x, y)| x.abs_diff(y) <= 1);

    let (mut same_ao, mut open, mut darker, mut occluded) = (0, 0, 0, 0);
    for i in 0..ao_ours.len() {
        if (ao_ours[i] - ao_bevys[i]).abs() <= 1e-3 {
            same_ao += 1;
            assert!(
                close(ours_lit[i], bevys_lit[i]),
                "pixel {i}: same AO, other light"
            );
        }
        if ao_ours[i] >= 0.999 {
            open += 1;
            assert!(
                close(ours_lit[i], plain_lit[i]),
                "pixel {i}: no AO, yet not the plain frame"
            );
        }
        if ao_ours[i] < 0.8 && plain_lit[i][0] > 8 {
            occluded += 1;
            darker += usize::from(ours_lit[i][0] < plain_lit[i][0]);
        }
    }
    eprintln!(
        "{same_ao} pixels of equal AO, {open} open, {darker} of {occluded} occluded ones darker"
    );
    assert!(
        same_ao > 500 && open > 500,
        "both comparisons cover many pixels"
    );
    assert!(
        occluded > 200 && darker * 10 >= occluded * 9,
        "the lighting reads obscura's AO"
    );
}

#[test]
fn a_setting_that_cannot_run_is_reported_and_bevys_ssao_runs_meanwhile() {
    let _one = ONE_APP.lock().unwrap_or_else(|e| e.into_inner());
    let (mut h, scene, camera, near) = scene_app("stairs");
    let mut bad = AoSettings::preset(Technique::Gtao, Preset::High);
    bad.gtao.radius = -1.0;
    let (cam, _) = h.spawn_camera(&camera, near, SIZE, ObscuraAo::with_settings(bad));
    h.frames(2);
    let report = h.report(cam);
    let error = report.error.expect("the bad radius is reported");
    assert!(error.contains("gtao.radius"), "{error}");
    // Bevy's SSAO filled the texture instead: occlusion, and not obscura's image.
    let ao = h.view_ao(cam).values;
    let own = own_render(
        &scene,
        &camera,
        &AoSettings::preset(Technique::Gtao, Preset::High),
    );
    assert!(
        ao.iter().filter(|&&v| v < 0.9).count() > ao.len() / 20,
        "Bevy's SSAO ran"
    );
    assert!(mae(&ao, &own) > 0.01, "the AO is Bevy's, not obscura's");

    // Mended at run time: obscura's row from the next frame on.
    h.app
        .world_mut()
        .entity_mut(cam)
        .insert(ObscuraAo::new(Technique::Gtao, Preset::High));
    h.frames(2);
    let report = h.report(cam);
    assert_eq!(report.error, None);
    assert!(mae(&h.view_ao(cam).values, &own) <= 2e-3);
}

#[test]
fn a_multisampled_camera_is_reported_and_runs_once_msaa_is_off() {
    let _one = ONE_APP.lock().unwrap_or_else(|e| e.into_inner());
    let (mut h, scene, camera, near) = scene_app("stairs");
    let settings = AoSettings::preset(Technique::Gtao, Preset::High);
    let (cam, _) = h.spawn_camera(&camera, near, SIZE, ObscuraAo::with_settings(settings));
    // Bevy's default, 4 samples, after the harness's Msaa::Off.
    h.app.world_mut().entity_mut(cam).insert(Msaa::Sample4);
    h.frames(2);
    let error = h.report(cam).error.expect("MSAA is reported");
    assert!(
        error.contains("Msaa::Off") && error.contains("4 samples"),
        "{error}"
    );

    h.app.world_mut().entity_mut(cam).insert(Msaa::Off);
    h.frames(2);
    assert_eq!(h.report(cam).error, None);
    let own = own_render(&scene, &camera, &settings);
    assert!(mae(&h.view_ao(cam).values, &own) <= 2e-3);
}
