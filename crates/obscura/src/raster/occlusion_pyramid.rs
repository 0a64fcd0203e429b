//! The occlusion pyramid (`shaders/occlusion_pyramid.wgsl`, layout in
//! `shaders/common/occlusion_pyramid.wgsl`): the farthest depth per tile of 1 to 64 pixels of a
//! reversed-Z depth buffer, which the second phase of [`super::triangle_cull`]'s occlusion
//! culling tests triangles against; and depth peeling's, per tile the depth a fragment must lie
//! behind to be peeled ([`PyramidSource::Peel`]). A storage buffer rather than a mipmapped
//! texture: one dispatch writes every level, and a texture would need a storage binding per level.

use crate::gpu::PassProfiler;

/// Tile levels, as `PYRAMID_FIRST_LEVEL` and `PYRAMID_LAST_LEVEL` of the shader.
const FIRST_LEVEL: u32 = 0;
const LAST_LEVEL: u32 = 6;

/// Floats in the pyramid of a `width`×`height` framebuffer.
fn len(width: u32, height: u32) -> u64 {
    (FIRST_LEVEL..=LAST_LEVEL)
        .map(|level| {
            let tiles = |n: u32| u64::from(n.div_ceil(1 << level));
            tiles(width) * tiles(height)
        })
        .sum()
}

/// What a pyramid is built from.
pub(crate) enum PyramidSource<'a> {
    /// The farthest depth per tile of a depth buffer (`Depth32Float`, reversed Z, with
    /// `TEXTURE_BINDING`): occlusion culling.
    Farthest(&'a wgpu::Texture),
    /// Per tile the largest reversed-Z depth that depth peeling of `separation` over the first
    /// layer's linear depth (`R32Float`, 0 = background, `size` pixels) still rejects
    /// (`shaders/occlusion_pyramid_peel.wgsl`); the camera's projection is given per frame
    /// ([`OcclusionPyramid::prepare`]) and the first layer itself when the pyramid is built
    /// ([`OcclusionPyramid::encode_from`]): an engine's depth may be another texture each frame.
    Peel { size: (u32, u32), separation: f32 },
}

/// `PeelPyramidParams` of occlusion_pyramid_peel.wgsl.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct PeelParams {
    projection: [[f32; 4]; 4],
    separation: f32,
    _pad: [f32; 3],
}

/// The pyramid of one depth buffer.
pub(crate) struct OcclusionPyramid {
    pipeline: wgpu::ComputePipeline,
    /// Its bindings, for a source fixed at [`OcclusionPyramid::new`] ([`PyramidSource::Farthest`]).
    bind_group: Option<wgpu::BindGroup>,
    /// The levels, one after another (`array<f32>`).
    pub buffer: wgpu::Buffer,
    /// The source's size in pixels.
    size: (u32, u32),
    groups: (u32, u32),
    /// Depth peeling's parameters (projection, separation), for [`PyramidSource::Peel`].
    peel: Option<(wgpu::Buffer, f32)>,
    timing_name: &'static str,
}

impl OcclusionPyramid {
    /// The pyramid of `source`, timed as `timing_name`.
    pub fn new(device: &wgpu::Device, source: PyramidSource, timing_name: &'static str) -> Self {
        let ((width, height), header) = match &source {
            PyramidSource::Farthest(z) => (
                (z.width(), z.height()),
                crate::shaders::OCCLUSION_PYRAMID_FARTHEST,
            ),
            PyramidSource::Peel { size, .. } => (*size, crate::shaders::OCCLUSION_PYRAMID_PEEL),
        };
        let pipeline = crate::gpu::compute_pipeline_with(
            device,
            timing_name,
            &crate::shaders::with_common(
                &[crate::shaders::OCCLUSION_PYRAMID_LAYOUT, header],
                crate::shaders::OCCLUSION_PYRAMID,
            ),
            &[],
        );
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(timing_name),
            size: 4 * len(width, height),
            usage: wgpu::BufferUsages::STORAGE,
            mapped_at_creation: false,
        });
        // Read-only storage, not a uniform: lavapipe's uniform inlining (triangle_cull.wgsl).
        let (bind_group, peel) = match source {
            PyramidSource::Farthest(z) => {
                let view = z.create_view(&Default::default());
                let bind_group = crate::gpu::bind_group_at(
                    device,
                    timing_name,
                    &pipeline.get_bind_group_layout(0),
                    &[
                        (0, wgpu::BindingResource::TextureView(&view)),
                        (1, buffer.as_entire_binding()),
                    ],
                );
                (Some(bind_group), None)
            }
            PyramidSource::Peel { separation, .. } => {
                let params = device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("peel pyramid params"),
                    size: std::mem::size_of::<PeelParams>() as u64,
                    usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                });
                (None, Some((params, separation)))
            }
        };
        let side = 1 << LAST_LEVEL;
        Self {
            pipeline,
            bind_group,
            buffer,
            size: (width, height),
            groups: (width.div_ceil(side), height.div_ceil(side)),
            peel,
            timing_name,
        }
    }

    /// The coming frame's projection (depth peeling's pyramid; nothing for the others).
    pub fn prepare(&self, queue: &wgpu::Queue, projection: glam::Mat4) {
        if let Some((params, separation)) = &self.peel {
            let p = PeelParams {
                projection: projection.to_cols_array_2d(),
                separation: *separation,
                _pad: [0.0; 3],
            };
            queue.write_buffer(params, 0, bytemuck::bytes_of(&p));
        }
    }

    /// Build the pyramid from its source as it is now (timing: the name given to
    /// [`OcclusionPyramid::new`]); a pyramid of [`PyramidSource::Farthest`].
    pub fn encode(&self, encoder: &mut wgpu::CommandEncoder, profiler: Option<&mut PassProfiler>) {
        let bind_group = self
            .bind_group
            .as_ref()
            .expect("a pyramid with a fixed source (PyramidSource::Farthest)");
        self.dispatch(encoder, bind_group, profiler);
    }

    /// Build depth peeling's pyramid ([`PyramidSource::Peel`]) from `first_layer` as it is now:
    /// an `R32Float` view of the size given to [`OcclusionPyramid::new`].
    pub fn encode_from(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        first_layer: &wgpu::TextureView,
        profiler: Option<&mut PassProfiler>,
    ) {
        let (params, _) = self
            .peel
            .as_ref()
            .expect("a pyramid built from a first layer (PyramidSource::Peel)");
        let size = first_layer.texture().size();
        assert_eq!(
            (size.width, size.height),
            self.size,
            "the first layer has the size the pyramid was made for"
        );
        let bind_group = crate::gpu::bind_group_at(
            device,
            self.timing_name,
            &self.pipeline.get_bind_group_layout(0),
            &[
                (0, wgpu::BindingResource::TextureView(first_layer)),
                (1, self.buffer.as_entire_binding()),
                (2, params.as_entire_binding()),
            ],
        );
        self.dispatch(encoder, &bind_group, profiler);
    }

    fn dispatch(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        bind_group: &wgpu::BindGroup,
        profiler: Option<&mut PassProfiler>,
    ) {
        let timestamp_writes = profiler.map(|p| p.compute_pass(self.timing_name));
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(self.timing_name),
            timestamp_writes,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, bind_group, &[]);
        pass.dispatch_workgroups(self.groups.0, self.groups.1, 1);
    }
}
