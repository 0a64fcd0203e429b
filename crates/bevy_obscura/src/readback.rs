//! Reading back what a camera's lighting read: for tests, screenshots of the AO alone (as the
//! peer benchmark's `--ao-screenshot`), and comparisons with Bevy's own SSAO, which writes the
//! same texture.

use crate::convert::AoCopy;
use bevy::ecs::entity::Entity;
use bevy::ecs::world::World;
use bevy::pbr::ScreenSpaceAmbientOcclusionResources;
use bevy::render::renderer::{RenderAdapter, RenderDevice, RenderQueue};
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
    let gpu = Gpu::sharing_device(
        (**render_world.resource::<RenderAdapter>().0).clone(),
        render_world
            .resource::<RenderDevice>()
            .wgpu_device()
            .clone(),
        (**render_world.resource::<RenderQueue>().0).clone(),
    );
    // Bevy's texture cannot be a copy source: copy it through a compute pass (the plugin's own
    // copy, into an R32Float texture that can be).
    let copy = AoCopy::new(&gpu.device, wgpu::TextureFormat::R32Float)?;
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
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    copy.encode(&gpu.device, &mut encoder, texture, &readable);
    gpu.queue.submit([encoder.finish()]);
    let values = obscura::gpu::read_texture_f32(&gpu, &readable, 1).map_err(|e| e.to_string())?;
    Ok(ViewAo {
        width: texture.width(),
        height: texture.height(),
        values,
    })
}
