//! Volumetric Ambient Occlusion (seed 000 §3.1–3.5): the sample kernel, the per-pixel rotation
//! pattern and the compute pass (`shaders/vao.wgsl`). The same tables feed the CPU mirror in
//! [`crate::reference::cpu_vao`].

use super::{workgroups_32x8, AoKernel, FrameInputs};
use crate::gpu::PassProfiler;
use crate::hidden::HiddenDepth;
use crate::raster::stochastic_depth::{bindings_wgsl, SdLayout, StochasticDepthMap};
use crate::settings::{Normalization, VaoSettings};
use crate::shaders;
use crate::view::FrameView;
use glam::{Vec2, Vec3};
use std::f32::consts::TAU;
use wgpu::util::DeviceExt;

/// Base-2 van der Corput radical inverse of `i`.
pub fn van_der_corput(i: u32) -> f32 {
    (f64::from(i.reverse_bits()) / 4_294_967_296.0) as f32
}

/// Sample `i` of `n` before the per-pixel rotation: unit direction at angle 2πi/n and radius
/// `sqrt(1 - ψ^(2/3))` with ψ = van der Corput(n + i) (seed 000 Eq. 4–5, §7.1; offset n "skips 0"
/// as in the authors' code, giving 1/16, 9/16, 5/16, … for n = 8).
pub fn kernel_sample(i: u32, n: u32) -> (Vec2, f32) {
    let angle = TAU * i as f32 / n as f32;
    let psi = van_der_corput(n + i);
    let radius = (1.0 - psi.powf(2.0 / 3.0)).sqrt();
    (Vec2::new(angle.cos(), angle.sin()), radius)
}

/// 4×4 ordered-dither (Bayer) matrix, row-major; pixel (x, y) rotates its samples by
/// 2π·BAYER[x%4 + 4(y%4)]/16 (the 4×4 pattern of seed 000 §3.1; the values of the authors' 2024
/// code, seed-code-notes §2.2).
pub const BAYER_4X4: [u32; 16] = [0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5];

/// (cos, sin) of the rotation of pixel (x, y) of the visible image.
pub fn pixel_rotation(x: u32, y: u32) -> Vec2 {
    let a = TAU * BAYER_4X4[((x % 4) + 4 * (y % 4)) as usize] as f32 / 16.0;
    Vec2::new(a.cos(), a.sin())
}

/// Samples whose hemisphere-clipped column is shorter than this fraction of R are skipped
/// (seed 000 §3.2 "a_i = 0"; the authors' 2022 code used an absolute 0.01 world units, which
/// does not scale with the scene, so we make it relative to R).
pub const MIN_COLUMN_FRACTION: f32 = 0.01;

/// Orthonormal basis (t, b) perpendicular to unit `n`; Duff et al. 2017 (JCGT 6(1)), Listing 3.
/// Mirrors `orthonormal_basis` in `shaders/common/basis.wgsl`.
pub fn orthonormal_basis(n: Vec3) -> (Vec3, Vec3) {
    let s = if n.z >= 0.0 { 1.0 } else { -1.0 };
    let a = -1.0 / (s + n.z);
    let b = n.x * n.y * a;
    (
        Vec3::new(1.0 + s * n.x * n.x * a, s * b, -s * n.x),
        Vec3::new(b, s + n.y * n.y * a, -n.y),
    )
}

/// GPU mirror of `VaoParams` in `shaders/vao.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
pub struct VaoParams {
    radius: f32,
    thickness: f32,
    exponent: f32,
    _pad0: u32,
    min_column: f32,
    normalization: u32,
    _pad: [u32; 2],
    kernel: [[f32; 4]; 32],
    rotations: [[f32; 4]; 16],
}

impl VaoParams {
    pub fn new(s: &VaoSettings) -> Self {
        let mut kernel = [[0.0; 4]; 32];
        for (i, k) in kernel.iter_mut().enumerate().take(s.samples as usize) {
            let (dir, r) = kernel_sample(i as u32, s.samples);
            *k = [dir.x, dir.y, r, 0.0];
        }
        let mut rotations = [[0.0; 4]; 16];
        for (i, rot) in rotations.iter_mut().enumerate() {
            let c = pixel_rotation(i as u32 % 4, i as u32 / 4);
            *rot = [c.x, c.y, 0.0, 0.0];
        }
        Self {
            radius: s.radius,
            thickness: s.thickness,
            exponent: s.exponent,
            _pad0: 0,
            min_column: MIN_COLUMN_FRACTION * s.radius,
            normalization: match s.normalization {
                Normalization::Hemisphere => 0,
                Normalization::Clipped => 1,
            },
            _pad: [0; 2],
            kernel,
            rotations,
        }
    }
}

/// A VAO entry point's source: the kernel's functions, the hidden-depth source (first depth layer
/// only, dual depth, column rays through the BVH, or the stochastic depth map of `sd_layout`) and
/// `entry` (single pass or one of the SVAO phases).
pub(crate) fn vao_source(hidden: HiddenDepth, sd_layout: Option<SdLayout>, entry: &str) -> String {
    let sd_bindings = sd_layout.map(bindings_wgsl).unwrap_or_default();
    let mut parts = vec![shaders::VIEW, shaders::BASIS];
    match hidden {
        HiddenDepth::None => parts.extend([shaders::VAO, shaders::HIDDEN_DEPTH_BUFFER]),
        HiddenDepth::DualDepth => parts.extend([shaders::VAO, shaders::HIDDEN_DUAL_DEPTH]),
        HiddenDepth::ColumnRays => parts.extend([
            shaders::MATERIAL,
            shaders::BVH,
            shaders::VAO,
            shaders::HIDDEN_COLUMN_RAYS,
        ]),
        HiddenDepth::StochasticDepth => parts.extend([
            shaders::VAO,
            sd_bindings.as_str(),
            shaders::HIDDEN_STOCHASTIC_DEPTH,
        ]),
    }
    shaders::with_common(&parts, entry)
}

/// Bindings 0–4 of group 0 shared by every VAO entry point (vao.wgsl): view, parameters, depth,
/// normals, AO output.
pub(crate) fn frame_resources<'a>(
    view: &'a wgpu::Buffer,
    params: &'a wgpu::Buffer,
    inputs: &FrameInputs<'a>,
    output: &'a wgpu::TextureView,
) -> Vec<wgpu::BindingResource<'a>> {
    vec![
        view.as_entire_binding(),
        params.as_entire_binding(),
        wgpu::BindingResource::TextureView(inputs.depth),
        wgpu::BindingResource::TextureView(inputs.normals),
        wgpu::BindingResource::TextureView(output),
    ]
}

/// GPU mirror of `RayCamera` in `shaders/hidden/column_rays.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct RayCamera {
    camera_to_world: [[f32; 4]; 4],
    near: f32,
    _pad: [f32; 3],
}

/// The scene as the column-ray source traces it.
pub struct RayTracedScene<'a> {
    pub scene: &'a crate::raster::gpu_scene::GpuScene,
    pub bvh: &'a crate::bvh::gpu::GpuBvh,
}

/// What the column-ray source (RT-VAO) binds beyond plain VAO: the camera (group 0, binding 5)
/// and the BVH (group 1).
pub(crate) struct ColumnRays {
    pub camera: wgpu::Buffer,
    pub bvh_group: wgpu::BindGroup,
    /// `stack_overflows` of column_rays.wgsl (cleared every frame).
    pub stack_overflows: wgpu::Buffer,
}

impl ColumnRays {
    pub fn new(
        device: &wgpu::Device,
        bvh_layout: &wgpu::BindGroupLayout,
        r: &RayTracedScene,
    ) -> Self {
        Self {
            camera: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("ray camera"),
                size: std::mem::size_of::<RayCamera>() as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            bvh_group: r.bvh.bind_group(device, bvh_layout, r.scene),
            stack_overflows: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("stack overflows"),
                size: 4,
                usage: wgpu::BufferUsages::STORAGE
                    | wgpu::BufferUsages::COPY_DST
                    | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            }),
        }
    }

    pub fn set_camera(&self, queue: &wgpu::Queue, camera_to_world: glam::Mat4, near: f32) {
        let camera = RayCamera {
            camera_to_world: camera_to_world.to_cols_array_2d(),
            near,
            _pad: [0.0; 3],
        };
        queue.write_buffer(&self.camera, 0, bytemuck::bytes_of(&camera));
    }
}

/// The uniform buffer of `VaoParams`.
pub(crate) fn params_buffer(device: &wgpu::Device, settings: &VaoSettings) -> wgpu::Buffer {
    device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("vao params"),
        contents: bytemuck::bytes_of(&VaoParams::new(settings)),
        usage: wgpu::BufferUsages::UNIFORM,
    })
}

/// What a kernel's hidden-depth source is built from.
pub enum HiddenSource<'a> {
    /// The first depth layer only (`vao`).
    DepthBuffer,
    /// The second depth layer of [`FrameInputs::second_layer`] (`vao-dual`).
    DualDepth,
    /// Column rays through this scene (`rt-vao`, `rt-svao`).
    ColumnRays(RayTracedScene<'a>),
    /// This stochastic depth map, which the kernel renders before it reads it (`sd-vao`,
    /// `sd-svao`).
    StochasticDepth(Box<StochasticDepthMap>),
}

/// A hidden-depth source as a kernel holds it: what it binds beyond the frame (group 0 from
/// binding 5 on, and group 1 for the BVH) and what it renders first.
pub(crate) enum Hidden {
    DepthBuffer,
    DualDepth,
    ColumnRays(ColumnRays),
    StochasticDepth(Box<StochasticDepthMap>),
}

impl Hidden {
    /// The held form of `source`; `pipeline`'s group 1 is the BVH's layout for column rays.
    pub fn new(
        device: &wgpu::Device,
        source: HiddenSource,
        pipeline: &wgpu::ComputePipeline,
    ) -> Self {
        match source {
            HiddenSource::DepthBuffer => Hidden::DepthBuffer,
            HiddenSource::DualDepth => Hidden::DualDepth,
            HiddenSource::ColumnRays(r) => Hidden::ColumnRays(ColumnRays::new(
                device,
                &pipeline.get_bind_group_layout(1),
                &r,
            )),
            HiddenSource::StochasticDepth(map) => Hidden::StochasticDepth(map),
        }
    }

    pub fn set_camera(&self, queue: &wgpu::Queue, view: &FrameView) {
        match self {
            Hidden::ColumnRays(rays) => {
                rays.set_camera(queue, view.view_matrix().inverse(), view.near)
            }
            Hidden::StochasticDepth(map) => map.set_camera(queue, view),
            Hidden::DepthBuffer | Hidden::DualDepth => {}
        }
    }

    pub fn stack_overflows(&self) -> Option<&wgpu::Buffer> {
        match self {
            Hidden::ColumnRays(rays) => Some(&rays.stack_overflows),
            _ => None,
        }
    }

    /// Group 0 from binding 5 on for the passes that resolve hidden samples. Clears the
    /// per-frame counters it binds.
    pub fn resources<'a>(
        &'a self,
        encoder: &mut wgpu::CommandEncoder,
        inputs: &FrameInputs<'a>,
    ) -> Vec<wgpu::BindingResource<'a>> {
        match self {
            Hidden::DepthBuffer => Vec::new(),
            Hidden::DualDepth => vec![wgpu::BindingResource::TextureView(
                inputs
                    .second_layer
                    .expect("AmbientOcclusion checks that vao-dual gets a second depth layer"),
            )],
            Hidden::ColumnRays(rays) => {
                encoder.clear_buffer(&rays.stack_overflows, 0, None);
                vec![
                    rays.camera.as_entire_binding(),
                    rays.stack_overflows.as_entire_binding(),
                ]
            }
            Hidden::StochasticDepth(map) => map.read_resources(),
        }
    }
}

/// The single-pass VAO compute pass (`vao`, `vao-dual`, `rt-vao`, `sd-vao`).
pub struct VaoKernel {
    pipeline: wgpu::ComputePipeline,
    params: wgpu::Buffer,
    view: wgpu::Buffer,
    hidden: Hidden,
    name: &'static str,
}

impl VaoKernel {
    /// VAO whose occluded samples consult `hidden`.
    pub fn new(
        device: &wgpu::Device,
        settings: &VaoSettings,
        view: &wgpu::Buffer,
        hidden: HiddenSource,
    ) -> Self {
        let (kind, sd_layout, name) = match &hidden {
            HiddenSource::DepthBuffer => (HiddenDepth::None, None, "vao"),
            HiddenSource::DualDepth => (HiddenDepth::DualDepth, None, "vao-dual"),
            HiddenSource::ColumnRays(_) => (HiddenDepth::ColumnRays, None, "rt-vao"),
            HiddenSource::StochasticDepth(map) => {
                (HiddenDepth::StochasticDepth, Some(map.layout()), "sd-vao")
            }
        };
        let source = vao_source(kind, sd_layout, shaders::VAO_SINGLE);
        let constants = [("SAMPLE_COUNT", f64::from(settings.samples))];
        let pipeline = crate::gpu::compute_pipeline_with(device, name, &source, &constants);
        Self {
            params: params_buffer(device, settings),
            view: view.clone(),
            hidden: Hidden::new(device, hidden, &pipeline),
            pipeline,
            name,
        }
    }
}

impl AoKernel for VaoKernel {
    fn set_camera(&self, queue: &wgpu::Queue, view: &FrameView) {
        self.hidden.set_camera(queue, view);
    }

    fn stack_overflows(&self) -> Option<&wgpu::Buffer> {
        self.hidden.stack_overflows()
    }

    fn stochastic_depth(&self) -> Option<&StochasticDepthMap> {
        match &self.hidden {
            Hidden::StochasticDepth(map) => Some(map),
            _ => None,
        }
    }

    fn pass_name(&self) -> &'static str {
        self.name
    }

    fn encode(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        inputs: &FrameInputs,
        output: &wgpu::TextureView,
        mut profiler: Option<&mut PassProfiler>,
    ) {
        if let Hidden::StochasticDepth(map) = &self.hidden {
            map.render(device, encoder, inputs.depth, None, profiler.as_deref_mut());
        }
        let mut resources = frame_resources(&self.view, &self.params, inputs, output);
        resources.extend(self.hidden.resources(encoder, inputs));
        let bind_group = crate::gpu::bind_group(
            device,
            self.name,
            &self.pipeline.get_bind_group_layout(0),
            &resources,
        );
        let timestamp_writes = profiler.map(|p| p.compute_pass(self.name));
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(self.name),
            timestamp_writes,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &bind_group, &[]);
        if let Hidden::ColumnRays(rays) = &self.hidden {
            pass.set_bind_group(1, &rays.bvh_group, &[]);
        }
        let (x, y, z) = workgroups_32x8(inputs.screen.width, inputs.screen.height);
        pass.dispatch_workgroups(x, y, z);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn radii_match_the_authors_table() {
        // seed-code-notes §1.3: sampleRadius[8] of the 2022 SVAO shader.
        let table = [
            0.917883, 0.564429, 0.734504, 0.359545, 0.820004, 0.470149, 0.650919, 0.205215,
        ];
        for (i, expected) in table.iter().enumerate() {
            let (_, r) = kernel_sample(i as u32, 8);
            assert!((r - expected).abs() < 1e-5, "sample {i}: {r} vs {expected}");
        }
        // 16 and 32 samples start at 0.949098… and 0.968246… (seed-code-notes §2.2).
        assert!((kernel_sample(0, 16).1 - 0.949098).abs() < 1e-5);
        assert!((kernel_sample(0, 32).1 - 0.968246).abs() < 1e-5);
    }

    #[test]
    fn basis_is_orthonormal() {
        for n in [
            Vec3::Z,
            -Vec3::Z,
            Vec3::X,
            Vec3::new(0.3, -0.5, 0.8).normalize(),
        ] {
            let (t, b) = orthonormal_basis(n);
            assert!((t.length() - 1.0).abs() < 1e-5 && (b.length() - 1.0).abs() < 1e-5);
            assert!(t.dot(b).abs() < 1e-5 && t.dot(n).abs() < 1e-5 && b.dot(n).abs() < 1e-5);
        }
    }
}
