//! Library misuse (issue 15): each misuse of the public API returns the documented `Err`, naming
//! what is wrong; nothing panics. (Texture size, format, usage and sample count of the engine
//! path: tests/it/engine_input.rs; of `FrameTextures`: here.)

use crate::common;
use crate::common::*;
use obscura::{
    AmbientOcclusion, AoSettings, FrameView, Gpu, SceneResources, ScreenGeometry, Technique,
};

fn screen() -> ScreenGeometry {
    ScreenGeometry {
        width: 32,
        height: 24,
        guard_band: 4,
        tan_half_fov: glam::Vec2::new(0.6, 0.45),
        orthographic: false,
    }
}

fn texture(
    gpu: &Gpu,
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
    samples: u32,
) -> wgpu::Texture {
    let s = screen();
    bare_texture(
        gpu,
        (s.full_width(), s.full_height()),
        format,
        usage,
        samples,
    )
}

fn encode_err(
    gpu: &Gpu,
    ao: &AmbientOcclusion,
    depth: &wgpu::Texture,
    normals: &wgpu::Texture,
) -> String {
    encode_and_submit(gpu, ao, depth, normals)
        .expect_err("an error")
        .to_string()
}

const BINDING: wgpu::TextureUsages = wgpu::TextureUsages::TEXTURE_BINDING;

#[test]
fn textures_without_binding_usage_or_with_samples_are_named() {
    let gpu = gpu();
    let ao = AmbientOcclusion::new(
        &gpu,
        &AoSettings::default(),
        screen(),
        SceneResources::default(),
    )
    .unwrap();
    let depth = texture(&gpu, wgpu::TextureFormat::R32Float, BINDING, 1);
    let normals = texture(&gpu, wgpu::TextureFormat::Rgba16Float, BINDING, 1);
    let unbound = texture(
        &gpu,
        wgpu::TextureFormat::Rgba16Float,
        wgpu::TextureUsages::COPY_DST,
        1,
    );
    let err = encode_err(&gpu, &ao, &depth, &unbound);
    assert!(
        err.contains("AO normals") && err.contains("TEXTURE_BINDING"),
        "{err}"
    );
    let attachment = wgpu::TextureUsages::RENDER_ATTACHMENT | BINDING;
    let msaa = texture(&gpu, wgpu::TextureFormat::Rgba16Float, attachment, 4);
    let err = encode_err(&gpu, &ao, &depth, &msaa);
    assert!(err.contains("4 samples"), "{err}");
    let integer = texture(&gpu, wgpu::TextureFormat::Rgba8Uint, BINDING, 1);
    let err = encode_err(&gpu, &ao, &depth, &integer);
    assert!(err.contains("not read as floats"), "{err}");
    let err = encode_err(&gpu, &ao, &normals, &normals);
    assert!(
        err.contains("AO depth") && err.contains("R32Float"),
        "{err}"
    );
}

#[test]
fn a_texture_of_another_device_is_an_error() {
    let gpu = gpu();
    let other = common::gpu(); // a second device
    let ao = AmbientOcclusion::new(
        &gpu,
        &AoSettings::default(),
        screen(),
        SceneResources::default(),
    )
    .unwrap();
    let depth = texture(&other, wgpu::TextureFormat::R32Float, BINDING, 1);
    let normals = texture(&gpu, wgpu::TextureFormat::Rgba16Float, BINDING, 1);
    // wgpu does not reject it when the frame's bind group is made; it reports it when the
    // commands run. Gpu::finish / Gpu::check_errors (and the next encode) return it.
    let _ = encode_and_submit(&gpu, &ao, &depth, &normals);
    let err = gpu.finish().expect_err("a validation error").to_string();
    assert!(err.contains("Validation"), "{err}");
}

#[test]
fn encoding_a_camera_technique_before_set_camera_is_an_error() {
    let gpu = gpu();
    let scene = obscura::scene::builtin("stairs").unwrap();
    let gpu_scene = obscura::raster::gpu_scene::GpuScene::new(
        &gpu.device,
        &gpu.queue,
        &scene,
        &gpu.device.limits(),
    )
    .unwrap();
    let bvh =
        obscura::bvh::gpu::GpuBvh::new(&gpu.device, &obscura::bvh::Bvh::build(&scene), &scene)
            .unwrap();
    let resources = SceneResources {
        scene: Some(&gpu_scene),
        bvh: Some(&bvh),
    };
    for technique in [Technique::RtVao, Technique::SdVao] {
        let settings = technique_settings(technique, true);
        let ao = AmbientOcclusion::new(&gpu, &settings, screen(), resources).unwrap();
        let depth = texture(&gpu, wgpu::TextureFormat::R32Float, BINDING, 1);
        let normals = texture(&gpu, wgpu::TextureFormat::Rgba16Float, BINDING, 1);
        let err = encode_err(&gpu, &ao, &depth, &normals);
        assert!(err.contains("set_camera"), "{technique}: {err}");
        // Once the camera is set, the same call records.
        let view = FrameView::new(scene.cameras[0].camera, 32, 24, 4, 0.01);
        ao.set_camera(&gpu.queue, &view);
        encode_and_submit(&gpu, &ao, &depth, &normals).unwrap();
        gpu.finish().unwrap();
    }
}

#[test]
fn settings_out_of_range_are_errors_naming_the_field() {
    let gpu = gpu();
    let mut settings = AoSettings::default();
    settings.vao.radius = -1.0;
    let err = match AmbientOcclusion::new(&gpu, &settings, screen(), SceneResources::default()) {
        Ok(_) => panic!("a negative radius was accepted"),
        Err(e) => e.to_string(),
    };
    assert!(err.contains("vao.radius"), "{err}");
    let mut settings = AoSettings::default();
    settings.stochastic_depth.samples = 3;
    assert!(settings
        .validate()
        .unwrap_err()
        .to_string()
        .contains("stochastic_depth.samples"));
}

#[test]
fn a_scene_over_the_adapter_s_buffer_limit_is_an_error_naming_it() {
    let gpu = gpu();
    let scene = obscura::scene::builtin("grass").unwrap();
    // The adapter's limits, with the storage-buffer binding limit just under the scene's need.
    let needed = 16 * scene.positions.len().max(scene.triangles.len()) as u64;
    let limits = wgpu::Limits {
        max_storage_buffer_binding_size: needed - 16,
        ..gpu.device.limits()
    };
    let err =
        match obscura::raster::gpu_scene::GpuScene::new(&gpu.device, &gpu.queue, &scene, &limits) {
            Ok(_) => panic!("a scene over the limit was accepted"),
            Err(e) => e.to_string(),
        };
    assert!(
        err.contains(&format!("({} bytes)", needed - 16))
            && err.contains(&format!("({needed} bytes)"))
            && err.contains("scene 'grass'")
            && err.contains("max_storage_buffer_binding_size"),
        "{err}"
    );
    // Within the limit it uploads.
    let limits = wgpu::Limits {
        max_storage_buffer_binding_size: needed,
        ..gpu.device.limits()
    };
    assert!(
        obscura::raster::gpu_scene::GpuScene::new(&gpu.device, &gpu.queue, &scene, &limits).is_ok()
    );
}

/// Issue 62: a framebuffer whose occlusion pyramid needs more than one storage binding of the
/// device (8K on lavapipe's 128 MiB) is refused before any buffer is made, in one message that
/// names the size, the technique, the buffer and the limit; no validation error is left behind
/// to be printed again (it was printed three times, once per bind group).
#[test]
fn a_size_over_the_storage_binding_limit_is_one_clear_error() {
    let gpu = common::gpu();
    let limits = gpu.device.limits();
    let side = gpu.summary.max_texture_dimension_2d.min(16384);
    // The pyramid's finest level alone is 4 bytes a pixel.
    if 4 * u64::from(side) * u64::from(side) <= limits.max_storage_buffer_binding_size {
        eprintln!("skipped: this device binds a {side}x{side} pyramid");
        return;
    }
    let settings = AoSettings {
        technique: Technique::SdVao,
        ..AoSettings::default()
    };
    let scene = obscura::scene::load("stairs").unwrap();
    let Err(e) = obscura::Renderer::new(&gpu, &scene, &settings, side, side, 0) else {
        panic!("a {side}x{side} renderer was made");
    };
    let message = e.to_string();
    for needle in [
        &format!("{side}x{side}"),
        "sd-vao",
        "occlusion pyramid",
        "max_storage_buffer_binding_size",
        "--size",
    ] {
        assert!(message.contains(needle), "{needle:?} not in: {message}");
    }
    assert!(matches!(e, obscura::Error::Input(_)), "{e:?}");
    gpu.check_errors().expect("no validation error left behind");
}
