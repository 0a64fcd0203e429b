//! Shared helpers for the GPU integration tests (lavapipe in CI).
#![allow(dead_code)]

use glam::{Mat4, UVec2, Vec2, Vec3};
use obscura::gpu::{read_texture_bytes, read_texture_f32};
use obscura::reference::cpu_vao::GBufferImage;
use obscura::scene::{Camera, Material, Scene};
use obscura::settings::AoSettings;
use obscura::{
    AmbientOcclusion, EngineFrame, EngineInput, Gpu, GpuOptions, Renderer, SceneResources,
    ScreenGeometry, Technique,
};

/// The test GPU: whatever adapter `Gpu::new` picks (lavapipe on CI). `Gpu::new` gives Mesa's
/// Vulkan window-system layer a runtime directory when XDG_RUNTIME_DIR is unset
/// (`gpu::quiet_headless_vulkan`), so the test log is free of its complaint.
pub fn gpu() -> Gpu {
    Gpu::new(&GpuOptions::default()).expect("a GPU adapter (install mesa-vulkan-drivers)")
}

/// Appends the quad `a, b, c, d` (counter-clockwise seen from the front) to `scene`.
pub fn push_quad(scene: &mut Scene, [a, b, c, d]: [Vec3; 4], material: u32) {
    let base = scene.positions.len() as u32;
    scene.positions.extend([a, b, c, d]);
    scene.uvs.extend([Vec2::ZERO, Vec2::X, Vec2::ONE, Vec2::Y]);
    scene.triangles.push([base, base + 1, base + 2]);
    scene.triangles.push([base, base + 2, base + 3]);
    scene.triangle_materials.extend([material, material]);
}

/// A scene with one default material and the given quads.
pub fn quads(name: &str, quads: &[[Vec3; 4]]) -> Scene {
    let mut scene = Scene {
        name: name.into(),
        materials: vec![Material::default()],
        ..Default::default()
    };
    for q in quads {
        push_quad(&mut scene, *q, 0);
    }
    scene
}

/// A large floor at y = 0 facing +y.
pub fn floor(half: f32) -> [Vec3; 4] {
    [
        Vec3::new(-half, 0.0, half),
        Vec3::new(half, 0.0, half),
        Vec3::new(half, 0.0, -half),
        Vec3::new(-half, 0.0, -half),
    ]
}

pub fn camera(eye: Vec3, target: Vec3, fov_y_deg: f32) -> Camera {
    Camera {
        eye,
        target,
        up: Vec3::Y,
        fov_y_deg,
    }
}

/// Built-in scene `name` and its first camera, both scaled by `k` about the origin (the same
/// scene in other units).
pub fn scaled_builtin(name: &str, k: f32) -> (Scene, Camera) {
    let mut scene = obscura::scene::builtin(name).unwrap();
    for p in &mut scene.positions {
        *p *= k;
    }
    let mut camera = scene.cameras[0].camera;
    camera.eye *= k;
    camera.target *= k;
    (scene, camera)
}

/// `technique` with default settings, its bilateral blur on or off.
pub fn technique_settings(technique: Technique, blur: bool) -> AoSettings {
    let mut s = AoSettings {
        technique,
        ..AoSettings::default()
    };
    s.blur.enabled = blur;
    s
}

/// AO (96×64 visible, guard band 16) of an unoccluded floor plane seen from a tilted view, at
/// every angle from ~20° to ~60° below the horizon: every pixel should be 1.
pub fn tilted_floor_ao(gpu: &Gpu, settings: &AoSettings) -> Vec<f32> {
    let scene = quads("floor", &[floor(100.0)]);
    let camera = camera(Vec3::new(0.0, 2.0, 4.0), Vec3::new(0.0, 0.0, -1.0), 50.0);
    let mut r = Renderer::new(gpu, &scene, settings, 96, 64, 16).unwrap();
    r.render(&camera, None).unwrap();
    r.read_ao().unwrap()
}

/// A smooth height field seen from straight above: every camera ray meets one surface.
pub fn height_field() -> obscura::scene::Scene {
    let n = 96;
    let size = 8.0;
    let mut s = quads("heightfield", &[]);
    let h =
        |x: f32, z: f32| 0.35 * (1.7 * x).sin() * (1.3 * z).cos() + 0.2 * (0.9 * x + 2.1 * z).sin();
    for j in 0..=n {
        for i in 0..=n {
            let (x, z) = (
                size * (i as f32 / n as f32 - 0.5),
                size * (j as f32 / n as f32 - 0.5),
            );
            s.positions.push(Vec3::new(x, h(x, z), z));
            s.uvs.push(Vec2::ZERO);
        }
    }
    for j in 0..n {
        for i in 0..n {
            let v = j * (n + 1) + i;
            s.triangles.push([v, v + n + 1, v + 1]);
            s.triangles.push([v + 1, v + n + 1, v + n + 2]);
            s.triangle_materials.extend([0, 0]);
        }
    }
    s
}

/// A 2×2 m alpha-masked quad at z = −2 (its texture's left column transparent, cutoff 0.5) before a
/// 10×10 m wall at z = −3, both facing +z.
pub fn masked_quad_before_wall() -> Scene {
    use obscura::scene::{AlphaMode, Texture};
    let quad = |half: f32, z: f32| {
        [
            Vec3::new(-half, -half, z),
            Vec3::new(half, -half, z),
            Vec3::new(half, half, z),
            Vec3::new(-half, half, z),
        ]
    };
    let mut scene = quads("mask", &[quad(5.0, -3.0)]);
    scene.materials.push(Material {
        name: "leaf".into(),
        base_color: [1.0; 4],
        base_color_texture: Some(0),
        alpha_mode: AlphaMode::Mask { cutoff: 0.5 },
        double_sided: true,
    });
    scene.textures.push(Texture {
        name: "checker".into(),
        width: 2,
        height: 2,
        rgba8: vec![
            255, 255, 255, 0, 255, 255, 255, 255, 255, 255, 255, 0, 255, 255, 255, 255,
        ],
    });
    push_quad(&mut scene, quad(1.0, -2.0), 1);
    scene
}

/// NDC z of every framebuffer pixel of `g` under `projection` (the engine's depth buffer), the
/// background at `far`.
pub fn hardware_depth(
    g: &GBufferImage,
    screen: &ScreenGeometry,
    projection: Mat4,
    far: f32,
) -> Vec<f32> {
    (0..g.height)
        .flat_map(|y| (0..g.width).map(move |x| UVec2::new(x, y)))
        .map(|p| {
            let z = g.depth_at(p);
            if z <= 0.0 {
                return far;
            }
            let v = screen.pixel_to_view(p.as_vec2() + 0.5, z);
            projection.project_point3(v).z
        })
        .collect()
}

/// The engine path (`EngineInput`, then `AmbientOcclusion`) for `frame` with `settings`: the AO,
/// and the linear depth and view-space normals `EngineInput` made.
pub fn engine_path_ao(
    gpu: &Gpu,
    screen: ScreenGeometry,
    settings: &AoSettings,
    frame: &EngineFrame,
) -> (Vec<f32>, Vec<f32>, Vec<Vec3>) {
    let input = EngineInput::new(gpu, screen);
    let ao = AmbientOcclusion::new(gpu, settings, screen, SceneResources::default()).unwrap();
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    let textures = input.encode(&mut encoder, frame).unwrap();
    ao.encode(&mut encoder, textures, None).unwrap();
    gpu.queue.submit([encoder.finish()]);
    let depth = read_texture_f32(gpu, textures.depth, 1).unwrap();
    let bytes = read_texture_bytes(gpu, textures.normals, 8).unwrap();
    let halves: &[half::f16] = bytemuck::cast_slice(&bytes);
    let normals = halves
        .chunks_exact(4)
        .map(|c| Vec3::new(c[0].to_f32(), c[1].to_f32(), c[2].to_f32()))
        .collect();
    (ao.read_output().unwrap(), depth, normals)
}

/// A `width`×`height` texture of `format` (`texel` bytes each) holding `bytes`, with the usages
/// an engine's inputs have (sampled, and written here).
pub fn upload_texture(
    gpu: &Gpu,
    format: wgpu::TextureFormat,
    (width, height): (u32, u32),
    bytes: &[u8],
    texel: u32,
) -> wgpu::Texture {
    let t = obscura::gpu::texture_2d(
        &gpu.device,
        "uploaded",
        width,
        height,
        format,
        wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
    );
    gpu.queue.write_texture(
        t.as_image_copy(),
        bytes,
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(width * texel),
            rows_per_image: None,
        },
        t.size(),
    );
    t
}

/// A 2D texture of `format` with any usage and sample count (for the misuse tests' bad inputs).
pub fn bare_texture(
    gpu: &Gpu,
    (width, height): (u32, u32),
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
    samples: u32,
) -> wgpu::Texture {
    gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("test texture"),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: samples,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage,
        view_formats: &[],
    })
}

/// Records `ao` over `depth` and `normals` (no second layer) and submits it if the recording
/// succeeded; the recording's result.
pub fn encode_and_submit(
    gpu: &Gpu,
    ao: &obscura::AmbientOcclusion,
    depth: &wgpu::Texture,
    normals: &wgpu::Texture,
) -> Result<(), obscura::Error> {
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    let frame = obscura::FrameTextures {
        depth,
        normals,
        second_layer: None,
    };
    let result = ao.encode(&mut encoder, frame, None);
    if result.is_ok() {
        gpu.queue.submit([encoder.finish()]);
    }
    result
}

/// GPU against CPU: within 1/255 except where a sample lay on a pixel edge (at most 1 in 500
/// pixels), and the view shows occlusion.
pub fn assert_mirrors(name: &str, gpu_ao: &[f32], cpu: (Vec<f32>, Vec<bool>)) {
    let (cpu_ao, ambiguous) = cpu;
    let (mut worst, mut mismatches) = (0.0f32, 0);
    for (i, (&g, &c)) in gpu_ao.iter().zip(&cpu_ao).enumerate() {
        let diff = (g - c).abs();
        if diff > 1.0 / 255.0 {
            assert!(ambiguous[i], "{name}: pixel {i} GPU {g} CPU {c}");
            mismatches += 1;
        } else {
            worst = worst.max(diff);
        }
    }
    println!("{name}: max |GPU − CPU| {worst:.2e}, {mismatches} edge-snapping mismatches");
    assert!(mismatches <= gpu_ao.len() / 500, "{name}: {mismatches}");
    let occluded = gpu_ao.iter().filter(|&&v| v < 0.9).count();
    assert!(
        occluded > gpu_ao.len() / 50,
        "{name}: the view must show occlusion ({occluded} pixels)"
    );
}

/// Metrics of `settings`' blurred AO (128×80, guard band 16, the scene's first camera) against
/// the cosine-weighted hemisphere ground truth of radius `radius` (256 rays per pixel), with the
/// report's halo band (4 px around relative depth jumps over 0.1); and the MAE of an image of ones
/// (no occlusion) against the same truth.
pub fn hemisphere_metrics(
    gpu: &Gpu,
    scene: &Scene,
    settings: &AoSettings,
    radius: f32,
) -> (obscura::metrics::Summary, f64) {
    use obscura::metrics::{mae, summarize, Image};
    let (w, h) = (128, 80);
    let mut r = Renderer::new(gpu, scene, settings, w, h, 16).unwrap();
    r.render(&scene.cameras[0].camera, None).unwrap();
    let ao = r.read_ao().unwrap();
    let depth = r.read_gbuffer().unwrap().visible_depth(16);
    let truth = hemisphere_truth(gpu, scene, *r.view().unwrap(), radius);
    let image = |d: &[f32]| Image::new(w as usize, h as usize, d.to_vec().leak()).unwrap();
    let ones = vec![1.0; ao.len()];
    (
        summarize(&image(&ao), &image(&truth), &image(&depth), 4, 0.1).unwrap(),
        mae(&image(&ones), &image(&truth)).unwrap(),
    )
}

/// MSE of each of `runs`' blurred AO (160×96, guard band 32, the scene's first camera) against
/// the `vao` ground truth through the same bilateral blur (on the same depth, with the first
/// run's blur settings), as `obscura compare` measures it: only hidden geometry differs.
pub fn mse_against_blurred_vao_truth(gpu: &Gpu, scene: &Scene, runs: &[AoSettings]) -> Vec<f64> {
    mse_against_blurred_vao_truth_at(gpu, scene, runs, (160, 96, 32))
}

/// [`mse_against_blurred_vao_truth`] at a `width`×`height` image with `guard_band` px.
pub fn mse_against_blurred_vao_truth_at(
    gpu: &Gpu,
    scene: &Scene,
    runs: &[AoSettings],
    (w, h, guard_band): (u32, u32, u32),
) -> Vec<f64> {
    use obscura::bvh::Bvh;
    use obscura::metrics::{mse, Image};
    use obscura::reference::cpu_blur::cpu_blur;
    use obscura::reference::ground_truth::{render_reference, ReferenceSettings};
    let bvh = Bvh::build(scene);
    let mut reference = Vec::new();
    let image = |d: &[f32]| Image::new(w as usize, h as usize, d.to_vec().leak()).unwrap();
    runs.iter()
        .map(|s| {
            let mut r = Renderer::new(gpu, scene, s, w, h, guard_band).unwrap();
            r.render(&scene.cameras[0].camera, None).unwrap();
            if reference.is_empty() {
                let view = *r.view().unwrap();
                let raw =
                    render_reference(scene, &bvh, view, &ReferenceSettings::default(), &|_| {});
                let gbuffer = r.read_gbuffer().unwrap();
                reference = cpu_blur(&raw, &gbuffer, &view.screen(), &runs[0].blur);
            }
            mse(&image(&r.read_ao().unwrap()), &image(&reference)).unwrap()
        })
        .collect()
}

/// The cosine-weighted hemisphere ground truth of radius `radius` (256 rays per pixel) of `view`,
/// traced on the GPU: the visible image, row-major.
pub fn hemisphere_truth(
    gpu: &Gpu,
    scene: &Scene,
    view: obscura::FrameView,
    radius: f32,
) -> Vec<f32> {
    use obscura::bvh::Bvh;
    use obscura::reference::gpu::render_reference_gpu;
    use obscura::reference::ground_truth::{ReferenceModel, ReferenceSettings};
    use std::collections::HashMap;
    use std::sync::{Arc, Mutex, OnceLock};
    // Several tests compare their rows with the same truth (each built-in scene's first camera at
    // the same size, most estimators' default radius): each is traced once per test process, by
    // whichever test asks first (the others asking for it wait for that one; a different truth is
    // not held up). The trace is deterministic, so a kept truth is the one a test would trace.
    type Cell = Arc<OnceLock<Vec<f32>>>;
    static TRUTHS: OnceLock<Mutex<HashMap<String, Cell>>> = OnceLock::new();
    // The scene's geometry is part of the key: tests change built-in scenes under their names.
    let geometry = {
        use std::hash::{Hash, Hasher};
        let mut h = std::collections::hash_map::DefaultHasher::new();
        bytemuck::cast_slice::<_, u8>(&scene.positions).hash(&mut h);
        bytemuck::cast_slice::<_, u8>(&scene.triangles).hash(&mut h);
        h.finish()
    };
    let key = format!("{} {geometry:x} {view:?} {}", scene.name, radius.to_bits());
    let cell = TRUTHS
        .get_or_init(Default::default)
        .lock()
        .unwrap()
        .entry(key)
        .or_default()
        .clone();
    cell.get_or_init(|| {
        let mut reference = ReferenceSettings {
            model: ReferenceModel::Hemisphere,
            spp: 256,
            ..Default::default()
        };
        reference.vao.radius = radius;
        render_reference_gpu(gpu, scene, &Bvh::build(scene), view, &reference, &|_, _| {})
            .unwrap()
            .0
    })
    .clone()
}

/// [`hemisphere_metrics`]' MAE, and that of no occlusion.
pub fn hemisphere_mae(gpu: &Gpu, scene: &Scene, settings: &AoSettings, radius: f32) -> (f64, f64) {
    let (summary, baseline) = hemisphere_metrics(gpu, scene, settings, radius);
    (summary.mae, baseline)
}

/// A step seen from straight above in [`step_ao`]: the floor y = 0 for x < `d`, a block of height
/// `h` beyond (its top at y = h, its face x = d towards the floor).
pub fn step_scene(d: f32, h: f32) -> Scene {
    let far = 30.0;
    quads(
        "step",
        &[
            [
                Vec3::new(-far, 0.0, far),
                Vec3::new(d, 0.0, far),
                Vec3::new(d, 0.0, -far),
                Vec3::new(-far, 0.0, -far),
            ],
            [
                Vec3::new(d, h, far),
                Vec3::new(far, h, far),
                Vec3::new(far, h, -far),
                Vec3::new(d, h, -far),
            ],
            [
                Vec3::new(d, 0.0, far),
                Vec3::new(d, h, far),
                Vec3::new(d, h, -far),
                Vec3::new(d, 0.0, -far),
            ],
        ],
    )
}

/// The maps' guard band case (seed 002 §3.5): a step whose face lies just past the right edge
/// of a 96×64 frame with a 4 px guard band, seen from 10 m straight above (30° field: 8.4 cm
/// per pixel; the visible floor spans x in ±4.02 m, the framebuffer ±4.36 m, the step's face at
/// x = 4.55 m, 0.8 m high), VAO with a 1 m radius (its samples reach about 12 px).
pub struct EdgeBandCase {
    pub scene: Scene,
    pub camera: Camera,
    pub vao: obscura::settings::VaoSettings,
    /// Visible width and height, and the framebuffer's guard band.
    pub size: (u32, u32, u32),
}

pub fn edge_band_case() -> EdgeBandCase {
    EdgeBandCase {
        scene: step_scene(4.55, 0.8),
        camera: Camera {
            eye: Vec3::new(0.0, 10.0, 0.0),
            target: Vec3::ZERO,
            up: Vec3::NEG_Z,
            fov_y_deg: 30.0,
        },
        vao: obscura::settings::VaoSettings {
            radius: 1.0,
            ..Default::default()
        },
        size: (96, 64, 4),
    }
}

impl EdgeBandCase {
    /// The mean squared error of `ao` against `reference` over the 12 visible columns at the
    /// right edge: what the samples off the framebuffer shade.
    pub fn edge_error(&self, ao: &[f32], reference: &[f32]) -> f64 {
        let (w, h, _) = self.size;
        let mut sum = 0.0f64;
        for y in 0..h {
            for x in w - 12..w {
                let i = (y * w + x) as usize;
                sum += f64::from(ao[i] - reference[i]).powi(2);
            }
        }
        sum / f64::from(12 * h)
    }

    /// A renderer that has drawn the case with `technique` (blur off), after `configure` has set
    /// the source's band.
    pub fn render(
        &self,
        gpu: &Gpu,
        technique: Technique,
        configure: impl FnOnce(&mut AoSettings),
    ) -> Renderer {
        let mut s = AoSettings {
            technique,
            vao: self.vao,
            ..Default::default()
        };
        s.blur.enabled = false;
        configure(&mut s);
        let (w, h, frame_guard) = self.size;
        let mut r = Renderer::new(gpu, &self.scene, &s, w, h, frame_guard).unwrap();
        r.render(&self.camera, None).unwrap();
        r
    }

    /// The ray-traced `vao` truth over `view` (the view a renderer of the case reports).
    pub fn reference(&self, view: obscura::FrameView) -> Vec<f32> {
        use obscura::reference::ground_truth::{render_reference, ReferenceSettings};
        let settings = ReferenceSettings {
            vao: self.vao,
            ..Default::default()
        };
        let bvh = obscura::bvh::Bvh::build(&self.scene);
        render_reference(&self.scene, &bvh, view, &settings, &|_| {})
    }

    /// The largest difference of `a` and `b` over the left half, whose samples never leave the
    /// framebuffer.
    pub fn left_half_difference(&self, a: &[f32], b: &[f32]) -> f32 {
        let (w, h, _) = self.size;
        (0..h)
            .flat_map(|y| (0..w / 2).map(move |x| (y * w + x) as usize))
            .map(|i| (a[i] - b[i]).abs())
            .fold(0.0f32, f32::max)
    }
}

/// How many texels of a `width`-wide request mask are set in its outer `band` texels.
pub fn requested_in_band(requests: &[u32], width: u32, band: u32) -> usize {
    let height = requests.len() as u32 / width;
    requests
        .iter()
        .enumerate()
        .filter(|&(i, &q)| {
            let (x, y) = (i as u32 % width, i as u32 / width);
            q != 0 && !((band..width - band).contains(&x) && (band..height - band).contains(&y))
        })
        .count()
}

/// The centre block's AO seen from 20 m straight above (4° field: 1.5 cm per pixel), and the
/// mean of `model(distance to the step, visible pixel)` over the block's pixels.
pub fn step_ao(
    settings: &AoSettings,
    d: f32,
    h: f32,
    model: impl Fn(f32, UVec2) -> f32,
) -> (f32, f32) {
    let gpu = gpu();
    let (w, ht) = (96, 96);
    // 20 m up, 4° field: 96 px cover 1.40 m, 1.5 cm per pixel, and the view ray is within 0.1°
    // of the normal over the block.
    let mut r = Renderer::new(&gpu, &step_scene(d, h), settings, w, ht, 32).unwrap();
    let camera = Camera {
        eye: Vec3::new(0.0, 20.0, 0.0),
        target: Vec3::ZERO,
        up: Vec3::NEG_Z,
        fov_y_deg: 4.0,
    };
    r.render(&camera, None).unwrap();
    let ao = r.read_raw_ao().unwrap();
    let g = r.read_gbuffer().unwrap();
    let screen = r.view().unwrap().screen();
    let world = r.view().unwrap().view_matrix().inverse();
    let (cx, cy) = (w / 2, ht / 2);
    let (mut got, mut want) = (0.0, 0.0);
    for y in cy..cy + 4 {
        for x in cx..cx + 4 {
            let pixel = UVec2::new(x, y) + screen.guard_band;
            let z = g.depth_at(pixel);
            let p = world.transform_point3(screen.pixel_to_view(pixel.as_vec2() + 0.5, z));
            assert!(p.y.abs() < 1e-3 && p.x < d, "a floor pixel: {p}");
            got += ao[(y * w + x) as usize] / 16.0;
            want += model(d - p.x, UVec2::new(x, y)) / 16.0;
        }
    }
    (got, want)
}

/// World size of a pixel at the floor in [`step_ao`]'s view: 2·20 m·tan 2° over 96 px.
pub fn step_pixel_size() -> f32 {
    2.0 * 20.0 * 2.0f32.to_radians().tan() / 96.0
}

/// Asserts `technique`'s blurred AO (defaults) is closer to the hemisphere ground truth of its
/// radius than an image of ones on `stairs`, `colonnade`, `grass` and `tower`, by 15 % where the
/// truth has much occlusion (MAE of ones over 0.1): a broken kernel (no occlusion, or occlusion
/// everywhere) is not. Prints every MAE.
pub fn assert_beats_no_occlusion(
    gpu: &Gpu,
    technique: Technique,
    radius: impl Fn(&AoSettings) -> f32,
) {
    for name in ["stairs", "colonnade", "grass", "tower"] {
        let scene = obscura::scene::builtin(name).unwrap();
        let s = technique_settings(technique, true);
        let (error, baseline) = hemisphere_mae(gpu, &scene, &s, radius(&s));
        println!("{name}: MAE {technique} {error:.4}, no occlusion {baseline:.4}");
        let factor = if baseline > 0.1 { 0.85 } else { 1.0 };
        assert!(
            error < factor * baseline,
            "{name} {technique}: {error} vs {baseline}"
        );
    }
}

/// A floor (y = 0, z > 0) meeting a tall wall (z = 0) seen obliquely from (0.6, 2, 3): the mean
/// raw AO of `settings` over the floor pixels within 2 cm of the corner line (away from the image
/// edge), how many they are, and the view's world-to-view matrix.
pub fn corner_ao(settings: &AoSettings) -> (f32, usize, glam::Mat4) {
    let (got, _, count, view) = corner_ao_and_model(settings, |_, _| 0.0);
    (got, count, view)
}

/// [`corner_ao`]'s view as the models see it: its screen geometry and world-to-view matrix, with
/// the surface the camera ray through any framebuffer position meets, computed exactly.
pub struct CornerView {
    pub screen: obscura::ScreenGeometry,
    pub view: glam::Mat4,
}

impl CornerView {
    /// The view-space point of the floor or the wall the ray through framebuffer position `px`
    /// meets first, and that surface's view-space normal (None: the ray misses both).
    pub fn surface(&self, px: Vec2) -> Option<(Vec3, Vec3)> {
        let dir = self.screen.pixel_to_view(px, 1.0);
        let world = self.view.inverse();
        let mut best: Option<(f32, Vec3, Vec3)> = None;
        for normal in [Vec3::Y, Vec3::Z] {
            let n = self.view.transform_vector3(normal);
            let corner = self.view.transform_point3(Vec3::ZERO);
            let denominator = n.dot(dir);
            if denominator.abs() < 1e-9 {
                continue;
            }
            let t = n.dot(corner) / denominator;
            let hit = dir * t;
            let w = world.transform_point3(hit);
            let inside = if normal == Vec3::Y {
                w.z >= 0.0
            } else {
                w.y >= 0.0
            };
            if t > 0.0 && inside && best.is_none_or(|(b, _, _)| t < b) {
                best = Some((t, hit, n.normalize()));
            }
        }
        best.map(|(_, hit, n)| (hit, n))
    }
}

/// [`corner_ao`]'s scene: a floor (y = 0, z > 0) meeting a tall wall (z = 0), 40 m wide.
pub fn corner_scene() -> Scene {
    let wall = [
        Vec3::new(-20.0, 0.0, 0.0),
        Vec3::new(20.0, 0.0, 0.0),
        Vec3::new(20.0, 20.0, 0.0),
        Vec3::new(-20.0, 20.0, 0.0),
    ];
    let floor = [
        Vec3::new(-20.0, 0.0, 20.0),
        Vec3::new(20.0, 0.0, 20.0),
        Vec3::new(20.0, 0.0, 0.0),
        Vec3::new(-20.0, 0.0, 0.0),
    ];
    quads("corner", &[wall, floor])
}

/// [`corner_ao`], and the mean of `model(visible pixel, view)` over the same pixels.
pub fn corner_ao_and_model(
    settings: &AoSettings,
    model: impl Fn(UVec2, &CornerView) -> f32,
) -> (f32, f32, usize, glam::Mat4) {
    let gpu = gpu();
    let scene = corner_scene();
    let (w, h) = (96, 96);
    let mut r = Renderer::new(&gpu, &scene, settings, w, h, 32).unwrap();
    r.render(&camera(Vec3::new(0.6, 2.0, 3.0), Vec3::ZERO, 20.0), None)
        .unwrap();
    let ao = r.read_raw_ao().unwrap();
    let g = r.read_gbuffer().unwrap();
    let corner = CornerView {
        screen: r.view().unwrap().screen(),
        view: r.view().unwrap().view_matrix(),
    };
    let world = corner.view.inverse();
    let (mut got, mut want, mut count) = (0.0, 0.0, 0);
    for y in 0..h {
        for x in 0..w {
            let pixel = UVec2::new(x, y) + corner.screen.guard_band;
            let z = g.depth_at(pixel);
            let p = world.transform_point3(corner.screen.pixel_to_view(pixel.as_vec2() + 0.5, z));
            let on_floor = p.y.abs() < 1e-3 && p.z > 0.0 && p.z < 0.02;
            if on_floor && (x as i32 - 48).abs() < 24 {
                got += ao[(y * w + x) as usize];
                want += model(UVec2::new(x, y), &corner);
                count += 1;
            }
        }
    }
    assert!(count >= 16, "{count} corner pixels");
    (got / count as f32, want / count as f32, count, corner.view)
}

/// The slice of [`corner_ao`]'s view through the corner point in screen direction θ (view space):
/// V towards the camera, D the screen direction made orthogonal to V, the floor's normal, the
/// floor's and the wall's lines in the slice on the +D side, and whether that floor line runs
/// into the wall (where the samples on that side see the wall's line).
pub struct CornerSlice {
    pub v: Vec3,
    pub d: Vec3,
    pub floor_n: Vec3,
    pub floor_line: Vec3,
    pub wall_line: Vec3,
    pub into_wall: bool,
}

pub fn corner_slice(view: glam::Mat4, theta: f32) -> CornerSlice {
    let v = (-view.transform_point3(Vec3::ZERO)).normalize();
    let floor_n = view.transform_vector3(Vec3::Y).normalize();
    let wall_n = view.transform_vector3(Vec3::Z).normalize();
    let d3 = Vec3::new(theta.cos(), theta.sin(), 0.0);
    let d = (d3 - v * d3.dot(v)).normalize();
    let m = d.cross(v);
    let along = |n: Vec3| {
        let l = n.cross(m).normalize();
        if l.dot(d) < 0.0 {
            -l
        } else {
            l
        }
    };
    let floor_line = along(floor_n);
    CornerSlice {
        v,
        d,
        floor_n,
        floor_line,
        wall_line: along(wall_n),
        into_wall: view.inverse().transform_vector3(floor_line).z < 0.0,
    }
}

/// Full-screen layers facing a camera at the origin that looks down −z: one triangle per layer at
/// each depth (a single triangle, so every sample of a pixel sees the same fragment).
pub fn facing_layers(depths: &[f32]) -> Scene {
    let mut scene = Scene {
        name: "layers".into(),
        materials: vec![Material::default()],
        ..Default::default()
    };
    for &d in depths {
        let base = scene.positions.len() as u32;
        scene.positions.extend([
            Vec3::new(-10.0 * d, -10.0 * d, -d),
            Vec3::new(10.0 * d, -10.0 * d, -d),
            Vec3::new(0.0, 10.0 * d, -d),
        ]);
        scene.uvs.extend([glam::Vec2::ZERO; 3]);
        scene.triangles.push([base, base + 1, base + 2]);
        scene.triangle_materials.push(0);
    }
    scene
}

/// The largest |a − b| over the pixels of two images (0 for empty ones).
pub fn max_abs_diff(a: &[f32], b: &[f32]) -> f32 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0f32, f32::max)
}
