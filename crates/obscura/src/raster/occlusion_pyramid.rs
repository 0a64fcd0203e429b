//! The occlusion pyramid (`shaders/raster/occlusion_pyramid.wgsl`, layout in
//! `shaders/common/occlusion_pyramid.wgsl`): the farthest depth per tile of 1 to 64 pixels of a
//! reversed-Z depth buffer, which the second phase of [`super::triangle_cull`]'s occlusion
//! culling tests triangles against. A storage buffer rather than a mipmapped texture: one
//! dispatch writes every level, and a texture would need a storage binding per level.

use crate::gpu::PassProfiler;

/// Tile levels, as `PYRAMID_FIRST_LEVEL` and `PYRAMID_LAST_LEVEL` of the shader.
const FIRST_LEVEL: u32 = 0;
const LAST_LEVEL: u32 = 6;

/// Bytes of the pyramid of a `width`×`height` framebuffer (its one storage buffer).
pub(crate) fn bytes(width: u32, height: u32) -> u64 {
    4 * len(width, height)
}

/// Floats in the pyramid of a `width`×`height` framebuffer.
fn len(width: u32, height: u32) -> u64 {
    (FIRST_LEVEL..=LAST_LEVEL)
        .map(|level| {
            let tiles = |n: u32| u64::from(n.div_ceil(1 << level));
            tiles(width) * tiles(height)
        })
        .sum()
}

/// The pyramid of one depth buffer.
pub(crate) struct OcclusionPyramid {
    pipeline: wgpu::ComputePipeline,
    bind_group: wgpu::BindGroup,
    /// The levels, one after another (`array<f32>`).
    pub buffer: wgpu::Buffer,
    groups: (u32, u32),
}

impl OcclusionPyramid {
    /// The pyramid of `z` (`Depth32Float`, reversed Z, with `TEXTURE_BINDING`).
    pub fn new(device: &wgpu::Device, z: &wgpu::Texture) -> Self {
        let pipeline = crate::gpu::compute_pipeline_with(
            device,
            "occlusion pyramid",
            &crate::shaders::with_common(
                &[crate::shaders::OCCLUSION_PYRAMID_LAYOUT],
                crate::shaders::OCCLUSION_PYRAMID,
            ),
            &[],
        );
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("occlusion pyramid"),
            size: bytes(z.width(), z.height()),
            usage: wgpu::BufferUsages::STORAGE,
            mapped_at_creation: false,
        });
        let view = z.create_view(&Default::default());
        let bind_group = crate::gpu::bind_group(
            device,
            "occlusion pyramid",
            &pipeline.get_bind_group_layout(0),
            &[
                wgpu::BindingResource::TextureView(&view),
                buffer.as_entire_binding(),
            ],
        );
        let side = 1 << LAST_LEVEL;
        Self {
            pipeline,
            bind_group,
            buffer,
            groups: (z.width().div_ceil(side), z.height().div_ceil(side)),
        }
    }

    /// Build the pyramid from the depth buffer as it is now (timing: `occlusion_pyramid`).
    pub fn encode(&self, encoder: &mut wgpu::CommandEncoder, profiler: Option<&mut PassProfiler>) {
        let timestamp_writes = profiler.map(|p| p.compute_pass("occlusion_pyramid"));
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("occlusion pyramid"),
            timestamp_writes,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &self.bind_group, &[]);
        pass.dispatch_workgroups(self.groups.0, self.groups.1, 1);
    }
}
