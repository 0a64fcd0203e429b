//! Half resolution (`resolution = "half"`; seed 001 Tab. 1–2 run every stochastic-depth variant at
//! 960×540 for 1080p and note the ~4× saving, §5): the pass list around a technique that runs at
//! half the width and height. Before it, `downsample` reduces the frame's depth, normals and
//! second layer 2×2 → 1 (`shaders/filter/half_resolution/downsample.wgsl`: exact depth where the four lie
//! on a plane, the nearest of the four elsewhere); the technique's source, schedule and blur then
//! run on that half frame; after them `upsample` writes the full-size output with a depth-aware
//! (joint bilateral) upsample guided by the full-resolution depth and normals
//! (`shaders/filter/half_resolution/upsample.wgsl`). How the paper made its half-resolution inputs and
//! upsampled is not said; both rules are ours and documented in the shaders.

use crate::error::Error;
use crate::frame::{workgroups_32x8, FrameInputs};
use crate::gpu::PassProfiler;
use crate::shaders;
use crate::view::ScreenGeometry;
use wgpu::util::DeviceExt;

/// The half-resolution frame (depth, normals, second layer and their view) and the passes that
/// make it and bring its AO back.
pub struct HalfResolution {
    screen: ScreenGeometry,
    half_view: wgpu::Buffer,
    full_view: wgpu::Buffer,
    depth: wgpu::Texture,
    normals: wgpu::Texture,
    second: wgpu::Texture,
    /// Bound in place of the second layer for rows without one (the shader reads it clamped).
    no_second: wgpu::Texture,
    output: wgpu::Texture,
    downsample: wgpu::ComputePipeline,
    upsample: wgpu::ComputePipeline,
}

impl HalfResolution {
    /// For inputs of `full` geometry (visible size and guard band even: an error naming them
    /// otherwise); `full_view` is its `View` uniform.
    pub fn new(
        device: &wgpu::Device,
        full: &ScreenGeometry,
        full_view: &wgpu::Buffer,
    ) -> Result<Self, Error> {
        let screen = full.half()?;
        let half_view = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("half-resolution view"),
            contents: bytemuck::bytes_of(&screen.uniform()),
            // COPY_DST: set_camera writes the near plane and, with temporal accumulation, the
            // pattern offset and the frame number.
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        });
        let frame_texture = |label, format, width, height, storage: bool| {
            let mut usage = wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_SRC;
            if storage {
                usage |= wgpu::TextureUsages::STORAGE_BINDING;
            }
            crate::gpu::texture_2d(device, label, width, height, format, usage)
        };
        let (fw, fh) = (screen.full_width(), screen.full_height());
        let r32 = wgpu::TextureFormat::R32Float;
        let pipeline = |label, source| {
            crate::gpu::compute_pipeline_with(
                device,
                label,
                &shaders::with_common(&[shaders::VIEW], source),
                &full.view_constants(),
            )
        };
        Ok(Self {
            screen,
            half_view,
            full_view: full_view.clone(),
            depth: frame_texture("half-resolution depth", r32, fw, fh, true),
            normals: frame_texture(
                "half-resolution normals",
                wgpu::TextureFormat::Rgba16Float,
                fw,
                fh,
                true,
            ),
            second: frame_texture("half-resolution second layer", r32, fw, fh, true),
            no_second: frame_texture("no second layer", r32, 1, 1, false),
            output: frame_texture("ao upsampled", r32, full.width, full.height, true),
            downsample: pipeline("half-resolution downsample", shaders::HALF_DOWNSAMPLE),
            upsample: pipeline("half-resolution upsample", shaders::HALF_UPSAMPLE),
        })
    }

    /// The geometry the technique runs at: half the visible size and guard band, the same frustum.
    pub fn screen(&self) -> ScreenGeometry {
        self.screen
    }

    /// The half-resolution frame's `View` uniform.
    pub fn view(&self) -> &wgpu::Buffer {
        &self.half_view
    }

    /// The half-resolution depth, normals and second layer (made by [`Self::downsample`]).
    pub fn textures(&self) -> (&wgpu::Texture, &wgpu::Texture, &wgpu::Texture) {
        (&self.depth, &self.normals, &self.second)
    }

    /// The full-size output [`Self::upsample`] writes (`R32Float`, visible size).
    pub fn output(&self) -> &wgpu::Texture {
        &self.output
    }

    /// Record the 2×2 → 1 reduction of `full`'s depth, normals and second layer. Timing:
    /// `half_downsample`.
    pub fn downsample(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        full: &FrameInputs,
        profiler: Option<&mut PassProfiler>,
    ) {
        let no_second = self.no_second.create_view(&Default::default());
        let view = |t: &wgpu::Texture| t.create_view(&Default::default());
        let (depth, normals, second) = (view(&self.depth), view(&self.normals), view(&self.second));
        let group = crate::gpu::bind_group(
            device,
            "half-resolution downsample",
            &self.downsample.get_bind_group_layout(0),
            &[
                self.full_view.as_entire_binding(),
                wgpu::BindingResource::TextureView(full.depth),
                wgpu::BindingResource::TextureView(full.normals),
                wgpu::BindingResource::TextureView(full.second_layer.unwrap_or(&no_second)),
                wgpu::BindingResource::TextureView(&depth),
                wgpu::BindingResource::TextureView(&normals),
                wgpu::BindingResource::TextureView(&second),
            ],
        );
        // One invocation per half-resolution texel (the half frame, guard band included).
        let (x, y, z) = workgroups_32x8(self.depth.width(), self.depth.height());
        self.dispatch(
            encoder,
            "half_downsample",
            &self.downsample,
            &group,
            (x, y, z),
            profiler,
        );
    }

    /// Record the depth-aware upsample of the half-resolution AO `half_ao` (visible half size)
    /// into [`Self::output`], guided by `full`'s depth and normals. Timing: `half_upsample`.
    pub fn upsample(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        full: &FrameInputs,
        half_ao: &wgpu::TextureView,
        profiler: Option<&mut PassProfiler>,
    ) {
        let depth = self.depth.create_view(&Default::default());
        let output = self.output.create_view(&Default::default());
        let group = crate::gpu::bind_group(
            device,
            "half-resolution upsample",
            &self.upsample.get_bind_group_layout(0),
            &[
                self.full_view.as_entire_binding(),
                wgpu::BindingResource::TextureView(full.depth),
                wgpu::BindingResource::TextureView(full.normals),
                wgpu::BindingResource::TextureView(&depth),
                wgpu::BindingResource::TextureView(half_ao),
                wgpu::BindingResource::TextureView(&output),
            ],
        );
        let groups = workgroups_32x8(self.output.width(), self.output.height());
        self.dispatch(
            encoder,
            "half_upsample",
            &self.upsample,
            &group,
            groups,
            profiler,
        );
    }

    fn dispatch(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        name: &str,
        pipeline: &wgpu::ComputePipeline,
        group: &wgpu::BindGroup,
        (x, y, z): (u32, u32, u32),
        profiler: Option<&mut PassProfiler>,
    ) {
        let timestamp_writes = profiler.map(|p| p.compute_pass(name));
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(name),
            timestamp_writes,
        });
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, group, &[]);
        pass.dispatch_workgroups(x, y, z);
    }
}
