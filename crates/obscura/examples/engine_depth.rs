//! Embedding obscura the way an engine would: a hardware depth buffer and a projection matrix in,
//! an AO texture out, with no obscura scene, camera or G-buffer involved.
//!
//! The "engine" here is a few lines of CPU code that write the reversed-Z depth buffer and the
//! world-space normals (an `Rgba8Unorm` target, n·0.5 + 0.5) of a floor, a wall and a box: what
//! a G-buffer prepass leaves behind. obscura linearises the depth, turns the normals into view
//! space, computes `gtao-vb` AO and writes `engine_depth.png`. Without a normal target, pass
//! `EngineNormals::Reconstruct` and obscura derives them from the depth.
//!
//! ```sh
//! cargo run --release -p obscura --example engine_depth [-- out.png]
//! ```

use glam::camera::rh::proj::directx::perspective_infinite_reverse;
use glam::{Mat4, Vec2, Vec3};
use obscura::{
    AmbientOcclusion, AoSettings, EngineFrame, EngineInput, EngineNormals, Gpu, GpuOptions,
    NormalEncoding, SceneResources, ScreenGeometry, Technique,
};

fn main() {
    let out = std::env::args().nth(1).unwrap_or("engine_depth.png".into());
    match run(std::path::Path::new(&out)) {
        Ok(mean) => println!("wrote {out}: mean AO {mean:.3}"),
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(1);
        }
    }
}

/// Renders the AO of the toy depth buffer into `out`; returns its mean over covered pixels.
pub fn run(out: &std::path::Path) -> Result<f32, Box<dyn std::error::Error>> {
    let (width, height, guard_band) = (320u32, 180u32, 16u32);
    let (fw, fh) = (width + 2 * guard_band, height + 2 * guard_band);
    // The engine's camera: reversed-Z with an infinite far plane, as many engines use.
    let projection = perspective_infinite_reverse(60f32.to_radians(), fw as f32 / fh as f32, 0.1);
    let view = glam::camera::rh::view::look_at_mat4(
        Vec3::new(2.5, 2.0, 4.0),
        Vec3::new(0.0, 0.5, 0.0),
        Vec3::Y,
    );

    let gpu = Gpu::new(&GpuOptions::default())?;
    let screen = ScreenGeometry::from_projection(projection, width, height, guard_band)?;
    let (depth, normals) = prepass(&gpu, fw, fh, projection, view);

    let input = EngineInput::new(&gpu, screen);
    let settings = AoSettings::preset(Technique::GtaoVb, obscura::settings::Preset::High);
    let ao = AmbientOcclusion::new(&gpu, &settings, screen, SceneResources::default())?;
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    let frame = EngineFrame {
        depth: &depth,
        projection,
        normals: EngineNormals::World {
            texture: &normals,
            encoding: NormalEncoding::Biased,
            view_from_world: view,
        },
    };
    let textures = input.encode(&mut encoder, &frame)?;
    ao.encode(&mut encoder, textures, None)?;
    gpu.queue.submit([encoder.finish()]);

    // An engine would sample `ao.output()` in its lighting pass; here it goes to a file.
    let values = ao.read_output()?;
    obscura::output::write_ao(out, width, height, &values)?;
    let covered: Vec<f32> = values.iter().copied().filter(|v| *v < 1.0).collect();
    Ok(covered.iter().sum::<f32>() / covered.len().max(1) as f32)
}

/// The "engine": ray-casts a floor (y = 0), a wall (z = −1.5) and a unit box on the floor, and
/// stores each pixel's NDC depth (0 = nothing, reversed-Z) and world normal, as a G-buffer
/// prepass would.
fn prepass(
    gpu: &Gpu,
    fw: u32,
    fh: u32,
    projection: Mat4,
    view: Mat4,
) -> (wgpu::Texture, wgpu::Texture) {
    let clip_to_world = (projection * view).inverse();
    let eye = view.inverse().transform_point3(Vec3::ZERO);
    let mut ndc_depth = vec![0.0f32; (fw * fh) as usize];
    let mut normals = vec![0u8; (4 * fw * fh) as usize];
    for y in 0..fh {
        for x in 0..fw {
            let ndc = Vec2::new(
                (x as f32 + 0.5) / fw as f32 * 2.0 - 1.0,
                1.0 - (y as f32 + 0.5) / fh as f32 * 2.0,
            );
            let far = clip_to_world.project_point3(ndc.extend(0.5));
            let dir = (far - eye).normalize();
            if let Some((t, n)) = nearest_hit(eye, dir) {
                let i = (y * fw + x) as usize;
                let p = view.transform_point3(eye + dir * t);
                ndc_depth[i] = projection.project_point3(p).z;
                let biased = (n * 0.5 + 0.5) * 255.0;
                normals[4 * i..4 * i + 3]
                    .copy_from_slice(&biased.round().to_array().map(|c| c as u8));
            }
        }
    }
    // A prepass writes Depth32Float; the CPU can only upload into a colour format.
    let depth = upload(
        gpu,
        (fw, fh),
        wgpu::TextureFormat::R32Float,
        bytemuck::cast_slice(&ndc_depth),
    );
    let normals = upload(gpu, (fw, fh), wgpu::TextureFormat::Rgba8Unorm, &normals);
    (depth, normals)
}

/// A texture the passes can read, holding `texels` (4 bytes each).
fn upload(
    gpu: &Gpu,
    (w, h): (u32, u32),
    format: wgpu::TextureFormat,
    texels: &[u8],
) -> wgpu::Texture {
    let texture = obscura::gpu::texture_2d(
        &gpu.device,
        "engine target",
        w,
        h,
        format,
        wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
    );
    gpu.queue.write_texture(
        texture.as_image_copy(),
        texels,
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(4 * w),
            rows_per_image: None,
        },
        texture.size(),
    );
    texture
}

/// Distance along the ray to the nearest of the floor, the wall and the box, and the normal
/// there.
fn nearest_hit(o: Vec3, d: Vec3) -> Option<(f32, Vec3)> {
    let plane = |n: Vec3, offset: f32| {
        let t = (offset - n.dot(o)) / n.dot(d);
        (t > 0.0).then_some((t, n))
    };
    // Slab test of the box [−0.5, 0.5] × [0, 1] × [−0.5, 0.5]; the entry face is the axis whose
    // slab the ray enters last.
    let (lo, hi) = (Vec3::new(-0.5, 0.0, -0.5), Vec3::new(0.5, 1.0, 0.5));
    let (t0, t1) = ((lo - o) / d, (hi - o) / d);
    let entry = t0.min(t1);
    let (near, far) = (entry.max_element(), t0.max(t1).min_element());
    let axis = Vec3::AXES[(0..3)
        .max_by(|&a, &b| entry[a].total_cmp(&entry[b]))
        .unwrap_or(0)];
    let cube = (near <= far && near > 0.0).then(|| (near, -axis * d.dot(axis).signum()));
    [plane(Vec3::Y, 0.0), plane(Vec3::Z, -1.5), cube]
        .into_iter()
        .flatten()
        .min_by(|a, b| a.0.total_cmp(&b.0))
}
