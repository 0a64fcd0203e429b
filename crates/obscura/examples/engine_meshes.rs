//! The hidden-depth techniques inside an engine: the engine draws its meshes from its own vertex
//! and index buffers into a reversed-Z `Depth32Float` buffer (a depth prepass, here a dozen lines
//! of wgpu), then hands obscura that depth buffer, its matrices and the same buffers. obscura
//! reads the buffers back once, builds its BVH and computes `rt-vao`, which traces the geometry
//! the depth buffer hides, and writes `engine_meshes.png`.
//!
//! ```sh
//! cargo run --release -p obscura --example engine_meshes [-- out.png]
//! ```

use glam::camera::rh::proj::directx::perspective_infinite_reverse;
use glam::{Mat4, Vec3};
use obscura::{
    AmbientOcclusion, AoSettings, EngineFrame, EngineGeometry, EngineInput, EngineMesh,
    EngineNormals, FrameView, Gpu, GpuOptions, IndexData, ScreenGeometry, Technique,
    VertexAttribute,
};
use wgpu::util::DeviceExt;

fn main() {
    let out = std::env::args()
        .nth(1)
        .unwrap_or("engine_meshes.png".into());
    match run(std::path::Path::new(&out), Technique::RtVao) {
        Ok(mean) => println!("wrote {out}: mean AO {mean:.3}"),
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(1);
        }
    }
}

/// The engine's meshes: a floor, a back wall and a pillar in front of it, one indexed triangle
/// list (counter-clockwise from outside).
fn meshes() -> (Vec<[f32; 3]>, Vec<u32>) {
    let mut positions = Vec::new();
    let mut indices = Vec::new();
    let mut quad = |corners: [[f32; 3]; 4]| {
        let base = positions.len() as u32;
        positions.extend(corners);
        indices.extend([base, base + 1, base + 2, base, base + 2, base + 3]);
    };
    quad([
        [-4.0, 0.0, 4.0],
        [4.0, 0.0, 4.0],
        [4.0, 0.0, -4.0],
        [-4.0, 0.0, -4.0],
    ]);
    quad([
        [-4.0, 0.0, -2.0],
        [4.0, 0.0, -2.0],
        [4.0, 3.0, -2.0],
        [-4.0, 3.0, -2.0],
    ]);
    // The pillar: four sides of a 0.6 m square column, 2.5 m high, at z = -1.
    let (x0, x1, z0, z1, h) = (-0.3, 0.3, -1.3, -0.7, 2.5);
    quad([[x0, 0.0, z1], [x1, 0.0, z1], [x1, h, z1], [x0, h, z1]]);
    quad([[x1, 0.0, z1], [x1, 0.0, z0], [x1, h, z0], [x1, h, z1]]);
    quad([[x1, 0.0, z0], [x0, 0.0, z0], [x0, h, z0], [x1, h, z0]]);
    quad([[x0, 0.0, z0], [x0, 0.0, z1], [x0, h, z1], [x0, h, z0]]);
    (positions, indices)
}

/// Renders the AO into `out` with `technique` (a row that traces or rasterises hidden depth, or
/// any other); returns the mean AO of the covered pixels.
pub fn run(out: &std::path::Path, technique: Technique) -> Result<f32, Box<dyn std::error::Error>> {
    let (width, height, guard_band) = (320u32, 180u32, 16u32);
    let (fw, fh) = (width + 2 * guard_band, height + 2 * guard_band);
    let near = 0.05;
    let projection = perspective_infinite_reverse(55f32.to_radians(), fw as f32 / fh as f32, near);
    let view = glam::camera::rh::view::look_at_mat4(
        Vec3::new(0.0, 1.4, 3.5),
        Vec3::new(0.0, 0.8, -1.0),
        Vec3::Y,
    );
    let gpu = Gpu::new(&GpuOptions::default())?;

    // The engine's buffers and its depth prepass.
    let (positions, indices) = meshes();
    let usage = wgpu::BufferUsages::COPY_SRC;
    let vertex_buffer = gpu
        .device
        .create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("engine vertices"),
            contents: bytemuck::cast_slice(&positions),
            usage: wgpu::BufferUsages::VERTEX | usage,
        });
    let index_buffer = gpu
        .device
        .create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("engine indices"),
            contents: bytemuck::cast_slice(&indices),
            usage: wgpu::BufferUsages::INDEX | usage,
        });
    let depth = depth_prepass(
        &gpu,
        (fw, fh),
        projection * view,
        &vertex_buffer,
        &index_buffer,
        indices.len() as u32,
    );

    // obscura: the geometry once (again when meshes move: EngineGeometry::set_transforms).
    let settings = AoSettings {
        technique,
        ..AoSettings::default()
    };
    let vertex_bytes = EngineGeometry::buffer_bytes(&gpu, &vertex_buffer)?;
    let index_bytes = EngineGeometry::buffer_bytes(&gpu, &index_buffer)?;
    let mesh = EngineMesh {
        positions: VertexAttribute {
            bytes: &vertex_bytes,
            offset: 0,
            stride: 12,
            format: wgpu::VertexFormat::Float32x3,
        },
        indices: Some(IndexData {
            bytes: &index_bytes,
            format: wgpu::IndexFormat::Uint32,
        }),
        transform: Mat4::IDENTITY,
        double_sided: false,
        alpha_mask: None,
    };
    let geometry = EngineGeometry::new(&gpu, &[mesh], technique.needs())?;
    let screen = ScreenGeometry::from_projection(projection, width, height, guard_band)?;
    let input = EngineInput::new(&gpu, screen);
    let ao = AmbientOcclusion::new(&gpu, &settings, screen, geometry.resources())?;

    // Every frame: the camera, then the two obscura passes after the prepass.
    ao.set_camera(&gpu.queue, &FrameView::from_matrices(view, screen, near)?);
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    let frame = EngineFrame {
        depth: &depth,
        projection,
        normals: EngineNormals::Reconstruct,
    };
    let textures = input.encode(&mut encoder, &frame)?;
    ao.encode(&mut encoder, textures, None)?;
    gpu.queue.submit([encoder.finish()]);

    let values = ao.read_output()?;
    obscura::output::write_ao(out, width, height, &values)?;
    let covered: Vec<f32> = values.iter().copied().filter(|v| *v < 1.0).collect();
    Ok(covered.iter().sum::<f32>() / covered.len().max(1) as f32)
}

/// The engine's depth prepass: its triangles into a reversed-Z `Depth32Float` buffer.
fn depth_prepass(
    gpu: &Gpu,
    (fw, fh): (u32, u32),
    clip_from_world: Mat4,
    vertices: &wgpu::Buffer,
    indices: &wgpu::Buffer,
    index_count: u32,
) -> wgpu::Texture {
    let device = &gpu.device;
    let shader = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("depth prepass"),
        source: wgpu::ShaderSource::Wgsl(
            "@group(0) @binding(0) var<uniform> clip_from_world: mat4x4<f32>;
             @vertex fn vs(@location(0) p: vec3<f32>) -> @builtin(position) vec4<f32> {
                 return clip_from_world * vec4<f32>(p, 1.0);
             }"
            .into(),
        ),
    });
    let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("depth prepass"),
        layout: None,
        vertex: wgpu::VertexState {
            module: &shader,
            entry_point: Some("vs"),
            compilation_options: Default::default(),
            buffers: &[wgpu::VertexBufferLayout {
                array_stride: 12,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: &wgpu::vertex_attr_array![0 => Float32x3],
            }],
        },
        primitive: wgpu::PrimitiveState {
            cull_mode: Some(wgpu::Face::Back),
            ..Default::default()
        },
        depth_stencil: Some(wgpu::DepthStencilState {
            format: wgpu::TextureFormat::Depth32Float,
            depth_write_enabled: Some(true),
            depth_compare: Some(wgpu::CompareFunction::Greater),
            stencil: Default::default(),
            bias: Default::default(),
        }),
        multisample: Default::default(),
        fragment: None,
        multiview_mask: None,
        cache: None,
    });
    let matrix = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("clip from world"),
        contents: bytemuck::cast_slice(&clip_from_world.to_cols_array()),
        usage: wgpu::BufferUsages::UNIFORM,
    });
    let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("depth prepass"),
        layout: &pipeline.get_bind_group_layout(0),
        entries: &[wgpu::BindGroupEntry {
            binding: 0,
            resource: matrix.as_entire_binding(),
        }],
    });
    // obscura reads the depth buffer: it needs TEXTURE_BINDING besides RENDER_ATTACHMENT.
    let depth = obscura::gpu::texture_2d(
        device,
        "engine depth",
        fw,
        fh,
        wgpu::TextureFormat::Depth32Float,
        wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
    );
    let view = depth.create_view(&Default::default());
    let mut encoder = device.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("depth prepass"),
            color_attachments: &[],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &view,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(0.0),
                    store: wgpu::StoreOp::Store,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &bind_group, &[]);
        pass.set_vertex_buffer(0, vertices.slice(..));
        pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint32);
        pass.draw_indexed(0..index_count, 0, 0..1);
    }
    gpu.queue.submit([encoder.finish()]);
    depth
}
