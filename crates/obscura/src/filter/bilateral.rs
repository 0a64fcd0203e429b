//! Separable depth-aware bilateral blur (seed 000 §3.4, HBAO+ weights; `shaders/filter/bilateral_blur.wgsl`).

use super::FilterImages;
use crate::frame::FrameInputs;
use crate::gpu::PassProfiler;
use crate::settings::BlurSettings;
use crate::shaders;
use wgpu::util::DeviceExt;

/// Largest radius the shader's workgroup tile holds (`MAX_RADIUS` in bilateral_blur.wgsl).
pub const MAX_RADIUS: u32 = 16;

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct BlurParams {
    direction: [i32; 2],
    falloff: f32,
    sharpness: f32,
}

/// Two compute passes (x then y) through an intermediate image of the visible size.
pub struct BilateralBlur {
    pipeline: wgpu::ComputePipeline,
    params: [wgpu::Buffer; 2],
    view: wgpu::Buffer,
    intermediate: wgpu::TextureView,
}

impl BilateralBlur {
    /// The pipeline and intermediate image for a visible `width`×`height` AO image; `view` is the
    /// frame's `View` uniform. The radius is clamped to 1..=[`MAX_RADIUS`].
    pub fn new(
        device: &wgpu::Device,
        settings: &BlurSettings,
        view: &wgpu::Buffer,
        width: u32,
        height: u32,
    ) -> Self {
        let source = shaders::with_common(&[shaders::VIEW], shaders::BILATERAL_BLUR);
        // The workgroup tile holds at most MAX_RADIUS taps per side (bilateral_blur.wgsl).
        let radius = settings.radius.clamp(1, MAX_RADIUS);
        let constants = [("RADIUS", f64::from(radius))];
        // SAFETY: every index in bilateral_blur.wgsl is in range by construction: tile indices are
        // `line * TILE + k` with k < RUN + 2·RADIUS ≤ TILE (RADIUS ≤ 16 is validated by
        // `AoSettings::validate`), texel loads are clamped to the visible / full framebuffer size
        // from the view uniform, and `AmbientOcclusion::encode` checks that the bound textures
        // have exactly those sizes. Without wgpu's checks the blur runs 1.45× faster (H200, 1080p).
        let pipeline = unsafe {
            crate::gpu::compute_pipeline_unchecked(device, "bilateral blur", &source, &constants)
        };
        let params = [[1, 0], [0, 1]].map(|direction| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("blur params"),
                contents: bytemuck::bytes_of(&BlurParams {
                    direction,
                    falloff: settings.falloff(),
                    sharpness: settings.sharpness,
                }),
                usage: wgpu::BufferUsages::UNIFORM,
            })
        });
        let intermediate = crate::gpu::texture_2d(
            device,
            "blur intermediate",
            width,
            height,
            wgpu::TextureFormat::R32Float,
            wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING,
        )
        .create_view(&Default::default());
        Self {
            pipeline,
            params,
            view: view.clone(),
            intermediate,
        }
    }
}

impl super::AoFilter for BilateralBlur {
    /// Blur `input` into `output` (both R32Float, visible size). Timings: `blur_x`, `blur_y`.
    fn encode(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        inputs: &FrameInputs,
        images: FilterImages,
        mut profiler: Option<&mut PassProfiler>,
    ) {
        let FilterImages {
            input,
            output,
            history: _,
        } = images;
        let (w, h) = (inputs.screen.width, inputs.screen.height);
        // Workgroups: runs of 64 pixels along the direction × 8 lines across (bilateral_blur.wgsl).
        let steps = [
            (
                "blur_x",
                input,
                &self.intermediate,
                &self.params[0],
                (w.div_ceil(64), h.div_ceil(8)),
            ),
            (
                "blur_y",
                &self.intermediate,
                output,
                &self.params[1],
                (h.div_ceil(64), w.div_ceil(8)),
            ),
        ];
        for (name, src, dst, params, (groups_along, groups_across)) in steps {
            let bind_group = crate::gpu::bind_group(
                device,
                name,
                &self.pipeline.get_bind_group_layout(0),
                &[
                    self.view.as_entire_binding(),
                    params.as_entire_binding(),
                    wgpu::BindingResource::TextureView(inputs.depth),
                    wgpu::BindingResource::TextureView(src),
                    wgpu::BindingResource::TextureView(dst),
                ],
            );
            let timestamp_writes = profiler.as_deref_mut().map(|p| p.compute_pass(name));
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some(name),
                timestamp_writes,
            });
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, &bind_group, &[]);
            pass.dispatch_workgroups(groups_along, groups_across, 1);
        }
    }
}
