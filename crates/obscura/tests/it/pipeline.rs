//! Pipeline properties: guard-band framing, guard-band reads, determinism, validation errors.

use crate::common::*;
use glam::Vec3;
use obscura::{AoSettings, FrameView, Renderer};

/// Floor plus a wall standing on it just right of the visible frame.
fn floor_and_offscreen_wall() -> obscura::scene::Scene {
    // Facing −x (towards the camera side); its foot is just beyond the visible frame of
    // `top_down`, whose visible half-width is 4 · tan(17.5°) · 96/64 ≈ 1.89 m.
    let wall_x = 2.0;
    let wall = [
        Vec3::new(wall_x, 0.0, -10.0),
        Vec3::new(wall_x, 0.0, 10.0),
        Vec3::new(wall_x, 3.0, 10.0),
        Vec3::new(wall_x, 3.0, -10.0),
    ];
    quads("wall", &[floor(50.0), wall])
}

fn top_down() -> obscura::scene::Camera {
    // Looking straight down at the floor: 2.5 m visible width at 96 px.
    let mut c = camera(Vec3::new(0.0, 4.0, 0.0), Vec3::ZERO, 35.0);
    c.up = Vec3::NEG_Z;
    c
}

#[test]
fn guard_band_keeps_the_visible_framing() {
    let gpu = gpu();
    let scene = floor_and_offscreen_wall();
    let settings = AoSettings::default();
    let cam = camera(Vec3::new(0.3, 1.5, 3.0), Vec3::new(0.0, 0.3, 0.0), 50.0);
    let (w, h) = (96, 64);
    let mut plain = Renderer::new(&gpu, &scene, &settings, w, h, 0).unwrap();
    let mut banded = Renderer::new(&gpu, &scene, &settings, w, h, 24).unwrap();
    plain.render(&cam, None).unwrap();
    banded.render(&cam, None).unwrap();
    let a = plain.read_gbuffer().unwrap();
    let b = banded.read_gbuffer().unwrap();
    assert_eq!((b.width, b.height), (w + 48, h + 48));
    // Same linear depth at every visible pixel = same projected positions.
    for y in 0..h {
        for x in 0..w {
            let za = a.depth[(y * w + x) as usize];
            let zb = b.depth[((y + 24) * b.width + x + 24) as usize];
            assert!(
                (za - zb).abs() <= 1e-4 * za.max(1.0),
                "pixel ({x},{y}): {za} vs {zb}"
            );
        }
    }
    // And a world point lands on the same visible pixel in both projections.
    let p = Vec3::new(0.2, 0.0, -0.4);
    let va = FrameView::new(cam, w, h, 0, 1e-3).view_to_pixel_world(p);
    let vb = FrameView::new(cam, w, h, 24, 1e-3).view_to_pixel_world(p) - 24.0;
    assert!((va - vb).length() < 1e-3);
}

#[test]
fn samples_leaving_the_frame_read_the_guard_band() {
    let gpu = gpu();
    let scene = floor_and_offscreen_wall();
    let mut settings = AoSettings::default();
    settings.blur.enabled = false;
    let (w, h) = (96, 64);
    let cam = top_down();
    let edge_mean = |guard_band: u32| {
        let mut r = Renderer::new(&gpu, &scene, &settings, w, h, guard_band).unwrap();
        r.render(&cam, None).unwrap();
        let ao = r.read_ao().unwrap();
        // The rightmost 3 visible columns: the wall's foot is ~3 px beyond the frame's right edge.
        let values: Vec<f32> = (0..h)
            .flat_map(|y| (w - 3..w).map(move |x| (y * w + x) as usize))
            .map(|i| ao[i])
            .collect();
        values.iter().sum::<f32>() / values.len() as f32
    };
    let without = edge_mean(0);
    let with = edge_mean(32);
    // Without a guard band the wall is never rendered, so the edge sees an open floor.
    assert!(without > 0.999, "no guard band: {without}");
    assert!(with < without - 0.1, "guard band {with} vs none {without}");
}

#[test]
fn two_renders_are_bit_identical() {
    let gpu = gpu();
    let scene = floor_and_offscreen_wall();
    let settings = AoSettings::default();
    let cam = camera(Vec3::new(0.5, 1.2, 2.5), Vec3::new(1.0, 0.4, 0.0), 60.0);
    let render = || {
        let mut r = Renderer::new(&gpu, &scene, &settings, 80, 60, 16).unwrap();
        r.render(&cam, None).unwrap();
        (r.read_raw_ao().unwrap(), r.read_ao().unwrap())
    };
    let (raw_a, ao_a) = render();
    let (raw_b, ao_b) = render();
    assert!(
        raw_a.iter().any(|&v| v < 0.9),
        "the test scene must have occlusion"
    );
    let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&raw_a), bits(&raw_b));
    assert_eq!(bits(&ao_a), bits(&ao_b));
}

#[test]
fn validation_errors_become_errors() {
    let gpu = gpu();
    gpu.check_errors().unwrap();
    // A texture with a zero extent is a validation error in WebGPU.
    let _ = gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("invalid on purpose"),
        size: wgpu::Extent3d {
            width: 0,
            height: 4,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::R32Float,
        usage: wgpu::TextureUsages::TEXTURE_BINDING,
        view_formats: &[],
    });
    let err = gpu.finish().expect_err("a validation error must surface");
    assert!(matches!(err, obscura::GpuError::Validation(_)), "{err}");
    gpu.check_errors().expect("errors are reported once");
}

#[test]
fn size_over_the_adapter_limit_is_a_clear_error() {
    let gpu = gpu();
    let scene = quads("floor", &[floor(1.0)]);
    let max = gpu.summary.max_texture_dimension_2d;
    let err = Renderer::new(&gpu, &scene, &AoSettings::default(), max, 64, 16)
        .err()
        .expect("over the limit");
    let msg = err.to_string();
    assert!(msg.contains("limit") && msg.contains("--size"), "{msg}");
}

#[test]
fn ambient_occlusion_rejects_mismatched_inputs() {
    let gpu = gpu();
    let screen = obscura::ScreenGeometry {
        width: 64,
        height: 48,
        guard_band: 8,
        tan_half_fov: glam::Vec2::new(0.6, 0.45),
        orthographic: false,
    };
    let ao = obscura::AmbientOcclusion::new(
        &gpu,
        &AoSettings::default(),
        screen,
        obscura::SceneResources::default(),
    )
    .unwrap();
    let usage = wgpu::TextureUsages::TEXTURE_BINDING;
    let tex = |w, h, f| obscura::gpu::texture_2d(&gpu.device, "input", w, h, f, usage);
    let normals = tex(80, 64, wgpu::TextureFormat::Rgba16Float);
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    // Depth without the guard band.
    let small = tex(64, 48, wgpu::TextureFormat::R32Float);
    let frame = |depth| obscura::FrameTextures {
        depth,
        normals: &normals,
        second_layer: None,
    };
    let err = ao.encode(&mut encoder, frame(&small), None).unwrap_err();
    assert!(err.to_string().contains("80x64"), "{err}");
    // Hardware depth instead of linear depth.
    let wrong = tex(80, 64, wgpu::TextureFormat::Rgba8Unorm);
    let err = ao.encode(&mut encoder, frame(&wrong), None).unwrap_err();
    assert!(err.to_string().contains("R32Float"), "{err}");
    // The right inputs encode.
    let depth = tex(80, 64, wgpu::TextureFormat::R32Float);
    ao.encode(&mut encoder, frame(&depth), None).unwrap();
    gpu.queue.submit([encoder.finish()]);
    gpu.finish().unwrap();
}

#[test]
fn gbuffer_alpha_test_cuts_masked_texels() {
    let gpu = gpu();
    let scene = masked_quad_before_wall();
    let mut r = Renderer::new(&gpu, &scene, &AoSettings::default(), 64, 64, 0).unwrap();
    // 90° fov from the origin: the quad (±1 at 2 m) covers the middle half of the image.
    r.render(&camera(Vec3::ZERO, Vec3::NEG_Z, 90.0), None)
        .unwrap();
    let g = r.read_gbuffer().unwrap();
    let depth_at = |x: u32, y: u32| g.depth[(y * 64 + x) as usize];
    // uv (0,0) is the quad's first corner (bottom left); texels with u < 0.5 are transparent.
    assert!(
        (depth_at(24, 32) - 3.0).abs() < 1e-3,
        "left half of the quad is cut: {}",
        depth_at(24, 32)
    );
    assert!(
        (depth_at(40, 32) - 2.0).abs() < 1e-3,
        "right half is kept: {}",
        depth_at(40, 32)
    );
    assert!(
        (depth_at(4, 4) - 3.0).abs() < 1e-3,
        "the wall around it: {}",
        depth_at(4, 4)
    );
}
