//! Reading back what a camera's lighting read: for tests, screenshots of the AO alone (as the
//! peer benchmark's `--ao-screenshot`), and comparisons with Bevy's own SSAO, which writes the
//! same texture.

use bevy::asset::Handle;
use bevy::ecs::entity::Entity;
use bevy::ecs::world::World;
use bevy::image::Image;
use bevy::pbr::ScreenSpaceAmbientOcclusionResources;
use bevy::render::render_asset::RenderAssets;
use bevy::render::renderer::{RenderAdapter, RenderDevice, RenderQueue};
use bevy::render::texture::GpuImage;
use obscura::bindings::{self, entry};
use obscura::Gpu;

/// One view's AO, 1 = unoccluded, row-major, top row first.
#[derive(Clone, Debug, PartialEq)]
pub struct ViewAo {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width × height` values.
    pub values: Vec<f32>,
}

/// The SSAO texture of `view` (an entity of the render world: the camera's `RenderEntity`) as
/// its lighting read it in the last frame, whether obscura or Bevy's SSAO wrote it. Call it
/// between frames, with pipelined rendering off (`PipelinedRenderingPlugin` disabled) so that
/// the render world is reachable (`app.sub_app(RenderApp).world()`). Waits for the GPU.
pub fn read_view_ao(render_world: &World, view: Entity) -> Result<ViewAo, String> {
    let resources = render_world
        .get::<ScreenSpaceAmbientOcclusionResources>(view)
        .ok_or_else(|| {
            format!(
                "render entity {view} has no SSAO texture: give the camera ObscuraAo or \
                 ScreenSpaceAmbientOcclusion, with Msaa::Off, and render a frame first"
            )
        })?;
    let texture = &resources.screen_space_ambient_occlusion_texture.texture;
    let gpu = render_gpu(render_world);
    // Bevy's own texture cannot be a copy source: copy it through a compute pass into an
    // R32Float texture that can be.
    let readable = gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("obscura view ao readback"),
        size: texture.size(),
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::R32Float,
        usage: wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    });
    gpu.queue
        .submit([copy_to_r32float(&gpu.device, texture, &readable)]);
    let values = obscura::gpu::read_texture_f32(&gpu, &readable, 1).map_err(|e| e.to_string())?;
    Ok(ViewAo {
        width: texture.width(),
        height: texture.height(),
        values,
    })
}

/// One compute dispatch copying `from` (an SSAO texture: R16Float, R32Float) into `to`
/// (R32Float storage, the same size) (`shaders/ssao_readback.wgsl`).
fn copy_to_r32float(
    device: &wgpu::Device,
    from: &wgpu::Texture,
    to: &wgpu::Texture,
) -> wgpu::CommandBuffer {
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("obscura ssao readback"),
        source: wgpu::ShaderSource::Wgsl(include_str!("shaders/ssao_readback.wgsl").into()),
    });
    let layout = bindings::layout(
        device,
        "obscura ssao readback",
        &[
            entry::texture(0),
            entry::storage_texture(1, wgpu::TextureFormat::R32Float),
        ],
    );
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("obscura ssao readback"),
        bind_group_layouts: &[Some(&layout)],
        immediate_size: 0,
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("obscura ssao readback"),
        layout: Some(&pipeline_layout),
        module: &module,
        entry_point: Some("copy_ao"),
        compilation_options: Default::default(),
        cache: None,
    });
    let view = |t: &wgpu::Texture| t.create_view(&Default::default());
    let (from_view, to_view) = (view(from), view(to));
    let bind_group = bindings::group(
        device,
        "obscura ssao readback",
        &layout,
        &[
            (0, wgpu::BindingResource::TextureView(&from_view)),
            (1, wgpu::BindingResource::TextureView(&to_view)),
        ],
    );
    let mut encoder = device.create_command_encoder(&Default::default());
    let mut pass = encoder.begin_compute_pass(&Default::default());
    pass.set_pipeline(&pipeline);
    pass.set_bind_group(0, &bind_group, &[]);
    pass.dispatch_workgroups(to.width().div_ceil(8), to.height().div_ceil(8), 1);
    drop(pass);
    encoder.finish()
}

/// obscura's handle on the render world's device (Bevy's), leaving Bevy's error handler alone.
pub fn render_gpu(render_world: &World) -> Gpu {
    sharing(
        render_world.resource::<RenderAdapter>(),
        render_world.resource::<RenderDevice>(),
        render_world.resource::<RenderQueue>(),
    )
}

/// [`render_gpu`] from the three resources (the plugin's systems hold them as parameters).
pub(crate) fn sharing(adapter: &RenderAdapter, device: &RenderDevice, queue: &RenderQueue) -> Gpu {
    Gpu::sharing_device(
        (**adapter.0).clone(),
        device.wgpu_device().clone(),
        (**queue.0).clone(),
    )
}

/// A camera's image target as rendered in the last frame: its width, height and RGBA8 texels,
/// row-major. The image needs `COPY_SRC` among its usages. Waits for the GPU.
pub fn read_target_rgba8(
    render_world: &World,
    image: &Handle<Image>,
) -> Result<(u32, u32, Vec<u8>), String> {
    let gpu_image = render_world
        .resource::<RenderAssets<GpuImage>>()
        .get(image.id())
        .ok_or("the image is not on the GPU: render a frame first")?;
    let texture = &gpu_image.texture;
    let bytes = obscura::gpu::read_texture_rgba8(&render_gpu(render_world), texture)
        .map_err(|e| e.to_string())?;
    Ok((texture.width(), texture.height(), bytes))
}
