//! `EngineInput`: an engine's hardware depth buffer and projection (standard or reversed-Z,
//! finite or infinite far plane, perspective or orthographic) and its normals (none, view- or
//! world-space, float or unorm-biased) become the linear depth and normals our G-buffer would have
//! written, and the AO equals the AO of our own pipeline. Bad textures are errors naming them.

use crate::common::*;
use glam::camera::rh::proj::directx as proj;
use glam::{Mat4, Vec3};
use obscura::reference::cpu_vao::GBufferImage;
use obscura::{
    AmbientOcclusion, AoSettings, EngineFrame, EngineInput, EngineNormals, FrameView, Gpu,
    NormalEncoding, Renderer, SceneResources, ScreenGeometry,
};

const W: u32 = 96;
const H: u32 = 64;
const BAND: u32 = 16;

/// Our own pipeline's frame of the stairs close-up: its G-buffer, AO and view.
fn our_frame(gpu: &Gpu, settings: &AoSettings) -> (GBufferImage, Vec<f32>, FrameView) {
    let scene = obscura::scene::builtin("stairs").unwrap();
    let mut r = Renderer::new(gpu, &scene, settings, W, H, BAND).unwrap();
    r.render(&scene.cameras[0].camera, None).unwrap();
    (
        r.read_gbuffer().unwrap(),
        r.read_ao().unwrap(),
        *r.view().unwrap(),
    )
}

fn upload(gpu: &Gpu, format: wgpu::TextureFormat, bytes: &[u8], texel: u32) -> wgpu::Texture {
    upload_texture(gpu, format, (W + 2 * BAND, H + 2 * BAND), bytes, texel)
}

fn settings() -> AoSettings {
    technique_settings(obscura::Technique::Vao, true)
}

#[test]
fn every_depth_convention_gives_our_linear_depth_and_ao() {
    let gpu = gpu();
    let s = settings();
    let (g, our_ao, view) = our_frame(&gpu, &s);
    let screen = view.screen();
    let aspect = screen.tan_half_fov.x / screen.tan_half_fov.y;
    let fov = view.full_fov_y();
    let near = view.near;
    let conventions = [
        (
            "reversed-Z, infinite far",
            proj::perspective_infinite_reverse(fov, aspect, near),
            0.0,
        ),
        (
            "standard Z, far 100",
            proj::perspective(fov, aspect, 0.05, 100.0),
            1.0,
        ),
        (
            "reversed-Z, far 100",
            proj::perspective(fov, aspect, 100.0, 0.05),
            0.0,
        ),
    ];
    for (what, projection, far) in conventions {
        let from = ScreenGeometry::from_projection(projection, W, H, BAND).unwrap();
        assert!(
            (from.tan_half_fov - screen.tan_half_fov)
                .abs()
                .max_element()
                < 1e-5,
            "{what}"
        );
        let ndc = hardware_depth(&g, &screen, projection, far);
        let depth = upload(
            &gpu,
            wgpu::TextureFormat::R32Float,
            bytemuck::cast_slice(&ndc),
            4,
        );
        // The engine's own view-space normals, as floats.
        let normals: Vec<[f32; 4]> = g.normals.iter().map(|n| n.extend(0.0).to_array()).collect();
        let normals = upload(
            &gpu,
            wgpu::TextureFormat::Rgba32Float,
            bytemuck::cast_slice(&normals),
            16,
        );
        let frame = EngineFrame {
            depth: &depth,
            projection,
            normals: EngineNormals::View {
                texture: &normals,
                encoding: NormalEncoding::Signed,
            },
        };
        let (ao, linear, _) = engine_path_ao(&gpu, from, &s, &frame);
        let mut worst = 0.0f32;
        for (a, b) in linear.iter().zip(&g.depth) {
            assert_eq!(*a == 0.0, *b == 0.0, "{what}: background differs");
            if *b > 0.0 {
                worst = worst.max((a - b).abs() / b);
            }
        }
        // f32 NDC z of a standard-Z buffer loses precision with distance: z·ε/near relative.
        assert!(
            worst < 1e-3,
            "{what}: linear depth off by {worst} (relative)"
        );
        let diff: Vec<f32> = ao.iter().zip(&our_ao).map(|(a, b)| (a - b).abs()).collect();
        let mean = diff.iter().sum::<f32>() / diff.len() as f32;
        assert!(
            mean < 2e-3,
            "{what}: AO differs from our pipeline's by {mean} on average"
        );
    }
}

#[test]
fn normals_are_reconstructed_or_converted() {
    let gpu = gpu();
    let s = settings();
    let (g, our_ao, view) = our_frame(&gpu, &s);
    let screen = view.screen();
    let projection = view.projection();
    let ndc = hardware_depth(&g, &screen, projection, 0.0);
    let depth = upload(
        &gpu,
        wgpu::TextureFormat::R32Float,
        bytemuck::cast_slice(&ndc),
        4,
    );
    let angle_stats = |normals: &[Vec3]| {
        let mut angles: Vec<f32> = normals
            .iter()
            .zip(&g.normals)
            .zip(&g.depth)
            .filter(|(_, z)| **z > 0.0)
            .map(|((a, b), _)| a.angle_between(*b).to_degrees())
            .collect();
        angles.sort_by(f32::total_cmp);
        angles[angles.len() - 1]
    };

    // None given: reconstructed from depth. Where, along each axis, one side's two taps lie on
    // the centre's face and the other side is on it too or beyond a depth jump (a silhouette),
    // the face's normal comes back exactly: central differences would bend those next to the
    // jump. Faces narrower than the stencil (the figure's facets at this size) get a smoothed
    // normal instead, and crease pixels lie on both faces.
    let frame = EngineFrame {
        depth: &depth,
        projection,
        normals: EngineNormals::Reconstruct,
    };
    let (ao, _, normals) = engine_path_ao(&gpu, screen, &s, &frame);
    let (fw, fh) = (g.width as i32, g.height as i32);
    let position = |i: i32| {
        let p = glam::IVec2::new(i % fw, i / fw).as_vec2() + 0.5;
        screen.pixel_to_view(p, g.depth[i as usize])
    };
    // The same plane: the same normal, and the neighbour on the centre's plane (stairs have
    // many parallel faces).
    let same_face = |c: i32, x: i32, y: i32| {
        let i = y * fw + x;
        (0..fw).contains(&x)
            && (0..fh).contains(&y)
            && g.depth[i as usize] > 0.0
            && g.normals[i as usize].angle_between(g.normals[c as usize]) < 1e-3
            && g.normals[c as usize].dot(position(i) - position(c)).abs()
                < 1e-3 * g.depth[c as usize]
    };
    let (mut supported, mut one_sided, mut worst) = (0, 0, 0.0f32);
    for y in 0..fh {
        for x in 0..fw {
            let c = y * fw + x;
            if g.depth[c as usize] <= 0.0 {
                continue;
            }
            let side = |dx: i32, dy: i32| {
                same_face(c, x + dx, y + dy) && same_face(c, x + 2 * dx, y + 2 * dy)
            };
            // Beyond a silhouette, not a crease: at a crease the centre lies on both faces, and
            // depth alone cannot tell which one the rasteriser gave the pixel.
            let jump = |dx: i32, dy: i32| {
                let (nx, ny) = (x + dx, y + dy);
                !(0..fw).contains(&nx)
                    || !(0..fh).contains(&ny)
                    || (g.depth[(ny * fw + nx) as usize] - g.depth[c as usize]).abs()
                        > 0.05 * g.depth[c as usize]
            };
            let (left, right, up, down) = (side(-1, 0), side(1, 0), side(0, -1), side(0, 1));
            let axis_ok = |a: bool, b: bool, a_dir: (i32, i32), b_dir: (i32, i32)| {
                (a && (b || jump(b_dir.0, b_dir.1))) || (b && jump(a_dir.0, a_dir.1))
            };
            if !(axis_ok(left, right, (-1, 0), (1, 0)) && axis_ok(up, down, (0, -1), (0, 1))) {
                continue;
            }
            supported += 1;
            one_sided += usize::from(!(left && right && up && down));
            let a = normals[c as usize].angle_between(g.normals[c as usize]);
            worst = worst.max(a);
        }
    }
    assert!(
        one_sided > 100,
        "only {one_sided} pixels next to an edge: the test needs them"
    );
    assert!(
        worst.to_degrees() < 0.5,
        "reconstructed normals of {supported} planar-supported pixels ({one_sided} next to an \
         edge): worst {}°",
        worst.to_degrees()
    );
    let mean = ao
        .iter()
        .zip(&our_ao)
        .map(|(a, b)| (a - b).abs())
        .sum::<f32>()
        / ao.len() as f32;
    // The figure's one-pixel facets and the crease pixels are where the normals differ.
    assert!(
        mean < 0.02,
        "AO with reconstructed normals differs by {mean} on average"
    );

    // World-space normals in a unorm target (n·0.5 + 0.5), turned by the view matrix.
    let to_world = view.view_matrix().inverse();
    let biased: Vec<u8> = g
        .normals
        .iter()
        .flat_map(|n| {
            let w = to_world.transform_vector3(*n);
            [w.x, w.y, w.z, 0.0].map(|c| ((c * 0.5 + 0.5) * 255.0).round() as u8)
        })
        .collect();
    let world = upload(&gpu, wgpu::TextureFormat::Rgba8Unorm, &biased, 4);
    let frame = EngineFrame {
        depth: &depth,
        projection,
        normals: EngineNormals::World {
            texture: &world,
            encoding: NormalEncoding::Biased,
            view_from_world: view.view_matrix(),
        },
    };
    let (_, _, normals) = engine_path_ao(&gpu, screen, &s, &frame);
    let worst = angle_stats(&normals);
    // 8-bit components: at most half a step (1/255) per component.
    assert!(
        worst < 0.5,
        "world normals through the view matrix: worst {worst}°"
    );
}

#[test]
fn orthographic_depth_gives_the_ao_of_a_distant_narrow_camera() {
    // A perspective camera 400 m away with a 0.1° field of view is orthographic to within
    // 1/400 of its depth range: its G-buffer, re-encoded under an orthographic projection of
    // the same extent, must give (nearly) the same AO.
    let gpu = gpu();
    let s = settings();
    let scene = obscura::scene::builtin("stairs").unwrap();
    let base = scene.cameras[0].camera;
    let dir = (base.target - base.eye).normalize();
    let far_camera = obscura::scene::Camera {
        eye: base.target - dir * 400.0,
        target: base.target,
        up: base.up,
        // The close-up's extent at its target, seen from 400 m.
        fov_y_deg: {
            let half_extent =
                (base.target - base.eye).length() * (base.fov_y_deg * 0.5).to_radians().tan();
            2.0 * (half_extent / 400.0).atan().to_degrees()
        },
    };
    let mut r = Renderer::new(&gpu, &scene, &s, W, H, BAND).unwrap();
    r.render(&far_camera, None).unwrap();
    let (g, our_ao, view) = (
        r.read_gbuffer().unwrap(),
        r.read_ao().unwrap(),
        *r.view().unwrap(),
    );
    let persp = view.screen();
    // The same extent at the target's depth, 400 m.
    let half = persp.tan_half_fov * 400.0;
    let projection = proj::orthographic(-half.x, half.x, -half.y, half.y, 300.0, 500.0);
    let screen = ScreenGeometry::from_projection(projection, W, H, BAND).unwrap();
    assert!(screen.orthographic);
    assert!((screen.tan_half_fov - half).abs().max_element() < 1e-3);
    let ndc: Vec<f32> = g
        .depth
        .iter()
        .map(|&z| {
            if z > 0.0 {
                projection.project_point3(Vec3::new(0.0, 0.0, -z)).z
            } else {
                1.0
            }
        })
        .collect();
    let depth = upload(
        &gpu,
        wgpu::TextureFormat::R32Float,
        bytemuck::cast_slice(&ndc),
        4,
    );
    let frame = EngineFrame {
        depth: &depth,
        projection,
        normals: EngineNormals::Reconstruct,
    };
    let (ao, linear, _) = engine_path_ao(&gpu, screen, &s, &frame);
    for (a, b) in linear.iter().zip(&g.depth).filter(|(_, b)| **b > 0.0) {
        assert!(
            (a - b).abs() < 2e-3 * b,
            "orthographic linear depth {a} vs {b}"
        );
    }
    let diff: Vec<f32> = ao.iter().zip(&our_ao).map(|(a, b)| (a - b).abs()).collect();
    let mean = diff.iter().sum::<f32>() / diff.len() as f32;
    assert!(mean < 0.01, "orthographic AO differs by {mean} on average");
    assert!(
        our_ao.iter().any(|a| *a < 0.8),
        "the view must show occlusion"
    );

    // The filters place pixels in view space too (the denoiser's tangent planes and its reach
    // on screen): with the à-trous denoiser the two must agree as well (measured: 0.044 on
    // average while the filters took every view for a perspective one).
    let mut denoised = technique_settings(obscura::Technique::Gtao, false);
    denoised.denoise.enabled = true;
    let mut r = Renderer::new(&gpu, &scene, &denoised, W, H, BAND).unwrap();
    r.render(&far_camera, None).unwrap();
    let perspective = r.read_ao().unwrap();
    let (orthographic, _, _) = engine_path_ao(&gpu, screen, &denoised, &frame);
    let mean = orthographic
        .iter()
        .zip(&perspective)
        .map(|(a, b)| (a - b).abs())
        .sum::<f32>()
        / perspective.len() as f32;
    assert!(
        mean < 0.01,
        "orthographic denoised AO differs by {mean} on average"
    );

    // Hidden-depth techniques need a perspective camera: a clear error.
    let sd = technique_settings(obscura::Technique::SdVao, true);
    let err = AmbientOcclusion::new(&gpu, &sd, screen, SceneResources::default())
        .err()
        .unwrap();
    assert!(err.to_string().contains("orthographic"), "{err}");
}

#[test]
fn bad_engine_inputs_are_errors_naming_them() {
    let gpu = gpu();
    let projection = proj::perspective(1.0, 1.5, 0.1, 100.0);
    let screen = ScreenGeometry::from_projection(projection, W, H, BAND).unwrap();
    let input = EngineInput::new(&gpu, screen);
    let (fw, fh) = (W + 2 * BAND, H + 2 * BAND);
    let make = |w, h, format, usage, samples| bare_texture(&gpu, (w, h), format, usage, samples);
    let binding = wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::RENDER_ATTACHMENT;
    let depth = make(fw, fh, wgpu::TextureFormat::Depth32Float, binding, 1);
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    let mut check = |frame: EngineFrame, needle: &str| {
        let err = input
            .encode(&mut encoder, &frame)
            .err()
            .expect(needle)
            .to_string();
        assert!(err.contains(needle), "'{needle}' not in: {err}");
    };
    let frame = |depth| EngineFrame {
        depth,
        projection,
        normals: EngineNormals::Reconstruct,
    };
    let no_binding = make(
        fw,
        fh,
        wgpu::TextureFormat::Depth32Float,
        wgpu::TextureUsages::RENDER_ATTACHMENT,
        1,
    );
    check(frame(&no_binding), "TEXTURE_BINDING");
    let small = make(W, H, wgpu::TextureFormat::Depth32Float, binding, 1);
    check(frame(&small), &format!("needs {fw}x{fh}"));
    let msaa = make(fw, fh, wgpu::TextureFormat::Depth32Float, binding, 4);
    check(frame(&msaa), "4 samples");
    let colour = make(fw, fh, wgpu::TextureFormat::Rgba8Unorm, binding, 1);
    check(frame(&colour), "Depth32Float");
    let other = EngineFrame {
        projection: proj::perspective(0.5, 1.5, 0.1, 100.0),
        ..frame(&depth)
    };
    check(other, "make a new EngineInput");
    let int_normals = make(fw, fh, wgpu::TextureFormat::Rgba8Uint, binding, 1);
    check(
        EngineFrame {
            normals: EngineNormals::View {
                texture: &int_normals,
                encoding: NormalEncoding::Signed,
            },
            ..frame(&depth)
        },
        "not read as floats",
    );
    // A projection that is not one, or an asymmetric frustum.
    let skewed = Mat4::from_cols_array(&[
        1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.5, 0.0, 0.0, 0.0, 0.5,
    ]);
    let err = ScreenGeometry::from_projection(skewed, W, H, BAND)
        .unwrap_err()
        .to_string();
    assert!(err.contains("neither perspective"), "{err}");
    // Vulkan's y-down clip space is not wgpu's.
    let vulkan = glam::camera::rh::proj::vulkan::perspective(1.0, 1.5, 0.1, 100.0);
    let err = ScreenGeometry::from_projection(vulkan, W, H, BAND)
        .unwrap_err()
        .to_string();
    assert!(err.contains("flips y"), "{err}");
    let shifted = proj::frustum(-1.0, 2.0, -1.0, 1.0, 0.1, 100.0);
    let err = ScreenGeometry::from_projection(shifted, W, H, BAND)
        .unwrap_err()
        .to_string();
    assert!(err.contains("off-centre"), "{err}");
    // The right inputs encode (a real Depth32Float buffer, depth aspect).
    input.encode(&mut encoder, &frame(&depth)).unwrap();
    gpu.queue.submit([encoder.finish()]);
    gpu.finish().unwrap();
}
