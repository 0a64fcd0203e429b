//! The G-buffer pass (`shaders/gbuffer.wgsl`): linear depth (`R32Float`), camera-facing view-space
//! face normals (`Rgba16Float`) and base colour (`Rgba8UnormSrgb`) over the guard-banded
//! framebuffer, with a reversed-Z `Depth32Float` buffer for visibility.

use super::gpu_scene::GpuScene;
use crate::gpu::PassProfiler;
use crate::shaders;
use crate::view::FrameView;

pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Float;
pub const NORMAL_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
pub const ALBEDO_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;
const Z_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct CameraUniform {
    view: [[f32; 4]; 4],
    projection: [[f32; 4]; 4],
}

pub struct GBuffer {
    pub depth: wgpu::Texture,
    pub normals: wgpu::Texture,
    pub albedo: wgpu::Texture,
    z: wgpu::Texture,
    /// Back faces culled / kept (double-sided and alpha-tested materials).
    pipelines: [wgpu::RenderPipeline; 2],
    camera: wgpu::Buffer,
}

impl GBuffer {
    /// Targets for a framebuffer of `width`×`height` (guard band included).
    pub fn new(device: &wgpu::Device, width: u32, height: u32) -> Self {
        let target = |label, format| {
            crate::gpu::texture_2d(
                device,
                label,
                width,
                height,
                format,
                wgpu::TextureUsages::RENDER_ATTACHMENT
                    | wgpu::TextureUsages::TEXTURE_BINDING
                    | wgpu::TextureUsages::COPY_SRC,
            )
        };
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("gbuffer"),
            source: wgpu::ShaderSource::Wgsl(
                shaders::with_common(&[shaders::MATERIAL], shaders::GBUFFER).into(),
            ),
        });
        let pipeline = |cull_mode| {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some("gbuffer"),
                layout: None,
                vertex: wgpu::VertexState {
                    module: &module,
                    entry_point: Some("vs_main"),
                    compilation_options: Default::default(),
                    buffers: &[],
                },
                primitive: wgpu::PrimitiveState {
                    cull_mode,
                    ..Default::default()
                },
                depth_stencil: Some(wgpu::DepthStencilState {
                    format: Z_FORMAT,
                    depth_write_enabled: Some(true),
                    depth_compare: Some(wgpu::CompareFunction::Greater),
                    stencil: Default::default(),
                    bias: Default::default(),
                }),
                multisample: Default::default(),
                fragment: Some(wgpu::FragmentState {
                    module: &module,
                    entry_point: Some("fs_main"),
                    compilation_options: Default::default(),
                    targets: &[DEPTH_FORMAT, NORMAL_FORMAT, ALBEDO_FORMAT].map(|f| Some(f.into())),
                }),
                multiview_mask: None,
                cache: None,
            })
        };
        Self {
            depth: target("linear depth", DEPTH_FORMAT),
            normals: target("normals", NORMAL_FORMAT),
            albedo: target("albedo", ALBEDO_FORMAT),
            z: target("z", Z_FORMAT),
            pipelines: [pipeline(Some(wgpu::Face::Back)), pipeline(None)],
            camera: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("gbuffer camera"),
                size: std::mem::size_of::<CameraUniform>() as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
        }
    }

    /// Rasterise `scene` seen through `view`. Timing: `gbuffer`.
    pub fn render(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        scene: &GpuScene,
        view: &FrameView,
        profiler: Option<&mut PassProfiler>,
    ) {
        let camera = CameraUniform {
            view: view.view_matrix().to_cols_array_2d(),
            projection: view.projection().to_cols_array_2d(),
        };
        queue.write_buffer(&self.camera, 0, bytemuck::bytes_of(&camera));
        let bind_groups = self.pipelines.each_ref().map(|p| {
            crate::gpu::bind_group(
                device,
                "gbuffer",
                &p.get_bind_group_layout(0),
                &[
                    self.camera.as_entire_binding(),
                    scene.positions.as_entire_binding(),
                    scene.uvs.as_entire_binding(),
                    scene.triangles.as_entire_binding(),
                    scene.materials.as_entire_binding(),
                    wgpu::BindingResource::TextureView(&scene.textures),
                ],
            )
        });
        let views =
            [&self.depth, &self.normals, &self.albedo].map(|t| t.create_view(&Default::default()));
        let clears = [
            wgpu::Color::TRANSPARENT,
            wgpu::Color::TRANSPARENT,
            wgpu::Color::WHITE,
        ];
        let attachments: Vec<_> = views
            .iter()
            .zip(clears)
            .map(|(view, clear)| {
                Some(wgpu::RenderPassColorAttachment {
                    view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(clear),
                        store: wgpu::StoreOp::Store,
                    },
                })
            })
            .collect();
        let z_view = self.z.create_view(&Default::default());
        let timestamp_writes = profiler.map(|p| p.render_pass("gbuffer"));
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("gbuffer"),
            color_attachments: &attachments,
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &z_view,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(0.0),
                    store: wgpu::StoreOp::Discard,
                }),
                stencil_ops: None,
            }),
            timestamp_writes,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        let ranges = [
            0..scene.culled_count,
            scene.culled_count..scene.triangle_count,
        ];
        for ((pipeline, bind_group), range) in self.pipelines.iter().zip(&bind_groups).zip(ranges) {
            if range.is_empty() {
                continue;
            }
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, bind_group, &[]);
            pass.draw(range.start * 3..range.end * 3, 0..1);
        }
    }
}
