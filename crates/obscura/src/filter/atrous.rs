//! The edge-avoiding à-trous denoiser made for AO (`shaders/filter/atrous.wgsl`: Dammertz et al.
//! 2010 with the edge stops and variance guidance of Schied et al. 2017, §4.4): a moments pass,
//! then up to `denoise.iterations` passes of a 5×5 kernel with taps 1, 2, 4, … pixels apart,
//! stopped at depth, normal and AO edges. Made for the noisy hemisphere rows (one ray a pixel):
//! each pixel widens until its footprint holds about `denoise.samples` rays (its own history's
//! included) or reaches a quarter of the AO radius on screen, so a pixel with a long history is
//! left nearly as it is and the reach means the same at any resolution.

use super::FilterImages;
use crate::frame::FrameInputs;
use crate::gpu::PassProfiler;
use crate::settings::DenoiseSettings;
use crate::shaders;
use crate::view::ScreenGeometry;
use wgpu::util::DeviceExt;

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct AtrousParams {
    step: i32,
    sigma: f32,
    radius: f32,
    samples: f32,
}

/// The moments pass and the iterations, ping-ponging between two (AO, variance) images.
pub struct Atrous {
    moments: wgpu::ComputePipeline,
    iterate: wgpu::ComputePipeline,
    last: wgpu::ComputePipeline,
    /// One parameter block per iteration (its tap spacing).
    params: Vec<wgpu::Buffer>,
    view: wgpu::Buffer,
    images: [wgpu::TextureView; 2],
    /// The history's stand-in where no temporal accumulation runs before (1×1, never read).
    no_history: wgpu::TextureView,
}

impl Atrous {
    /// The pipelines and images for the AO image of `screen` (its visible size); `view` is its
    /// `View` uniform; `radius` the estimator's world radius R (the filter's reach stays within
    /// a fraction of it on screen).
    /// `rays`: for hemisphere rows, the rays a pixel casts a frame (they bound its variance and
    /// its reach; 0 for the others); `history`: temporal accumulation runs before.
    pub fn new(
        device: &wgpu::Device,
        settings: &DenoiseSettings,
        view: &wgpu::Buffer,
        screen: &ScreenGeometry,
        radius: f32,
        rays: u32,
        history: bool,
    ) -> Self {
        let source = shaders::with_common(
            &[shaders::VIEW, shaders::VISIBILITY_VARIANCE],
            shaders::ATROUS,
        );
        let module = crate::gpu::shader_module(device, "atrous", &source);
        let (width, height) = (screen.width, screen.height);
        let mut constants = screen.view_constants();
        constants.push(("RAYS", f64::from(rays)));
        constants.push(("HISTORY", f64::from(u8::from(history))));
        let pipeline = |entry: &str| {
            crate::gpu::entry_pipeline(device, "atrous", &module, entry, &constants, None)
        };
        let params = (0..settings.iterations)
            .map(|i| {
                device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("atrous params"),
                    contents: bytemuck::bytes_of(&AtrousParams {
                        step: 1 << i,
                        sigma: settings.sigma,
                        radius,
                        samples: settings.samples,
                    }),
                    usage: wgpu::BufferUsages::UNIFORM,
                })
            })
            .collect();
        let image = || {
            crate::gpu::texture_2d(
                device,
                "atrous moments",
                width,
                height,
                wgpu::TextureFormat::Rg32Float,
                wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING,
            )
            .create_view(&Default::default())
        };
        Self {
            moments: pipeline("moments"),
            iterate: pipeline("main"),
            last: pipeline("main_last"),
            params,
            view: view.clone(),
            images: [image(), image()],
            no_history: crate::gpu::texture_2d(
                device,
                "no history",
                1,
                1,
                wgpu::TextureFormat::Rg32Uint,
                wgpu::TextureUsages::TEXTURE_BINDING,
            )
            .create_view(&Default::default()),
        }
    }
}

impl super::AoFilter for Atrous {
    /// Denoise `input` into `output` (both R32Float, visible size). Timings: `atrous_moments`,
    /// `atrous` (every iteration).
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
            history,
        } = images;
        let (w, h) = (inputs.screen.width, inputs.screen.height);
        // (pipeline, its input, where it writes (binding 5 or 6), parameters, timing name)
        let mut passes = vec![(
            &self.moments,
            input,
            (5, &self.images[0]),
            &self.params[0],
            "atrous_moments",
        )];
        let n = self.params.len();
        for (i, params) in self.params.iter().enumerate() {
            let read = &self.images[i % 2];
            let (pipeline, target) = match i + 1 == n {
                true => (&self.last, (6, output)),
                false => (&self.iterate, (5, &self.images[(i + 1) % 2])),
            };
            passes.push((pipeline, read, target, params, "atrous"));
        }
        let history = history.unwrap_or(&self.no_history);
        for (pipeline, read, (binding, target), params, name) in passes {
            let layout = pipeline.get_bind_group_layout(0);
            let mut entries = vec![
                (0, self.view.as_entire_binding()),
                (2, wgpu::BindingResource::TextureView(inputs.depth)),
                (3, wgpu::BindingResource::TextureView(inputs.normals)),
                (4, wgpu::BindingResource::TextureView(read)),
                (binding, wgpu::BindingResource::TextureView(target)),
            ];
            // Each entry point's layout (made from what it uses): every pass reads the history,
            // the iterations the parameters.
            entries.push((7, wgpu::BindingResource::TextureView(history)));
            if !std::ptr::eq(pipeline, &self.moments) {
                entries.push((1, params.as_entire_binding()));
            }
            let group = crate::gpu::bind_group_at(device, name, &layout, &entries);
            let timestamp_writes = profiler.as_deref_mut().map(|p| p.compute_pass(name));
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some(name),
                timestamp_writes,
            });
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, &group, &[]);
            pass.dispatch_workgroups(w.div_ceil(8), h.div_ceil(8), 1);
        }
    }
}
