//! Portability: every row of the technique table runs on a device made with WebGPU's default
//! limits and no optional features (`wgpu::Limits::default()`, `wgpu::Features::empty()`), what a
//! browser's WebGPU gives and what an engine that asks for nothing more hands to
//! `Gpu::from_device`, and it gives the image the adapter's own limits and features give. The
//! binding that ran out first was WebGPU's 8 storage buffers per shader stage: the BVH binds five,
//! so phase 2 of the ray-traced rows (the two-phase work list with its count in one buffer) and
//! the ray-traced map's collection (its hit counts in the map's buffer) were made to fit. Only the
//! compute rasteriser of the stochastic depth map needs more (12 buffers); `auto` then chooses the
//! hardware's, whose map is the same (tests/it/stochastic_depth.rs, compute_raster tests).

use crate::common::*;
use obscura::settings::Resolution;
use obscura::technique::{Needs, Schedule};
use obscura::{
    scene, AoSettings, EngineFrame, EngineNormals, Gpu, Renderer, ScreenGeometry, Technique,
};

/// A device of the test adapter with WebGPU's default limits and no optional features.
fn webgpu_default_device(gpu: &Gpu) -> Gpu {
    let (device, queue) = pollster::block_on(gpu.adapter.request_device(&wgpu::DeviceDescriptor {
        label: Some("WebGPU defaults"),
        required_features: wgpu::Features::empty(),
        required_limits: wgpu::Limits::default(),
        ..Default::default()
    }))
    .expect("every adapter gives WebGPU's default limits");
    Gpu::from_device(gpu.adapter.clone(), device, queue)
}

/// What a row's second frame gives: the AO, the bent normals (when asked for) and the ray-traced
/// map's hits per texel (where the row has that map).
type Frame = (Vec<f32>, Option<Vec<[f32; 4]>>, Option<Vec<u32>>);

fn second_frame(gpu: &Gpu, settings: &AoSettings) -> Result<Frame, obscura::Error> {
    let stairs = scene::builtin("stairs").unwrap();
    let camera = stairs.cameras[0].camera;
    let mut r = Renderer::new(gpu, &stairs, settings, 96, 64, 16)?;
    // Two frames: the temporal pass reads the first one's history in the second.
    r.render(&camera, None)?;
    r.render(&camera, None)?;
    let frame = (r.read_ao()?, r.read_bent_normals()?, r.read_ray_sd_hits()?);
    gpu.finish()?;
    Ok(frame)
}

#[test]
fn every_technique_runs_within_webgpu_default_limits_and_gives_the_same_image() {
    let gpu = gpu();
    let webgpu = webgpu_default_device(&gpu);
    assert_eq!(
        webgpu.device.limits().max_storage_buffers_per_shader_stage,
        8,
        "the test device has WebGPU's limits, so the comparison below tests them"
    );
    let mut compared = 0;
    for technique in Technique::all() {
        let base = technique_settings(technique, true);
        let mut variants = vec![("defaults", base)];
        if technique.row().estimator.bent_normals() && technique.schedule() == Schedule::Single {
            variants.push((
                "bent normals",
                AoSettings {
                    bent_normals: true,
                    ..base
                },
            ));
        }
        let mut temporal = base;
        temporal.temporal.enabled = true;
        variants.push(("temporal accumulation", temporal));
        variants.push((
            "half resolution",
            AoSettings {
                resolution: Resolution::Half,
                ..base
            },
        ));
        for (what, settings) in variants {
            let full = second_frame(&gpu, &settings)
                .unwrap_or_else(|e| panic!("{technique}, {what}, adapter limits: {e}"));
            let limited = second_frame(&webgpu, &settings)
                .unwrap_or_else(|e| panic!("{technique}, {what}, WebGPU's limits: {e}"));
            let worst = max_abs_diff(&full.0, &limited.0);
            assert!(
                worst <= 1e-6,
                "{technique}, {what}: the AO differs by {worst} under WebGPU's limits"
            );
            assert_eq!(full.1.is_some(), settings.bent_normals);
            assert_eq!(
                full.1, limited.1,
                "{technique}, {what}: bent normals differ"
            );
            assert_eq!(
                full.2, limited.2,
                "{technique}, {what}: hits per ray differ"
            );
            compared += 1;
        }
    }
    assert!(compared > 3 * Technique::all().count(), "{compared}");
}

/// The engine path on `gpu`: the stairs close-up's depth as an engine's reversed-Z `R32Float`
/// NDC depth, its normals reconstructed from it.
fn engine_ao(gpu: &Gpu, settings: &AoSettings, ndc: &[f32], projection: glam::Mat4) -> Vec<f32> {
    let (w, h, band) = (96, 64, 16);
    let screen = ScreenGeometry::from_projection(projection, w, h, band).unwrap();
    let depth = upload_texture(
        gpu,
        wgpu::TextureFormat::R32Float,
        (w + 2 * band, h + 2 * band),
        bytemuck::cast_slice(ndc),
        4,
    );
    let frame = EngineFrame {
        depth: &depth,
        projection,
        normals: EngineNormals::Reconstruct,
    };
    let (ao, _, _) = engine_path_ao(gpu, screen, settings, &frame);
    gpu.finish().unwrap();
    ao
}

#[test]
fn the_engine_path_runs_within_webgpu_default_limits_and_gives_the_same_image() {
    let gpu = gpu();
    let webgpu = webgpu_default_device(&gpu);
    let stairs = scene::builtin("stairs").unwrap();
    let mut r = Renderer::new(&gpu, &stairs, &AoSettings::default(), 96, 64, 16).unwrap();
    r.render(&stairs.cameras[0].camera, None).unwrap();
    let (g, view) = (r.read_gbuffer().unwrap(), *r.view().unwrap());
    let screen = view.screen();
    let aspect = screen.tan_half_fov.x / screen.tan_half_fov.y;
    let projection = glam::camera::rh::proj::directx::perspective_infinite_reverse(
        view.full_fov_y(),
        aspect,
        view.near,
    );
    let ndc = hardware_depth(&g, &screen, projection, 0.0);
    // The rows that need nothing but depth and normals (the others need the engine's triangles).
    let rows: Vec<Technique> = Technique::all()
        .filter(|t| t.needs() == Needs::default())
        .collect();
    assert!(rows.len() >= 10, "{rows:?}");
    for technique in rows {
        let settings = technique_settings(technique, true);
        let full = engine_ao(&gpu, &settings, &ndc, projection);
        let limited = engine_ao(&webgpu, &settings, &ndc, projection);
        let worst = max_abs_diff(&full, &limited);
        assert!(
            worst <= 1e-6,
            "{technique}: the engine path's AO differs by {worst}"
        );
    }
}
