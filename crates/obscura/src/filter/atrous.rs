//! The edge-avoiding à-trous denoiser made for AO (`shaders/filter/atrous.wgsl`: Dammertz et al.
//! 2010 with the edge stops and variance guidance of Schied et al. 2017, §4.4): a moments pass,
//! then `denoise.iterations` passes of a 5×5 kernel with taps 1, 2, 4, … pixels apart, stopped
//! at depth, normal and AO edges. Made for the noisy hemisphere rows (one ray a pixel): it reaches
//! across a surface where the AO is noisy and less where it is already smooth (a long history).

use super::FilterImages;
use crate::frame::FrameInputs;
use crate::gpu::PassProfiler;
use crate::settings::DenoiseSettings;
use crate::shaders;
use wgpu::util::DeviceExt;

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct AtrousParams {
    step: i32,
    sigma: f32,
    _pad: [f32; 2],
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
    /// The pipelines and images for a visible `width`×`height` AO image; `view` is the frame's
    /// `View` uniform.
    /// `history_rays`: behind temporal accumulation of hemisphere rays, the rays a pixel casts a
    /// frame (its history then bounds its variance); `None` otherwise.
    pub fn new(
        device: &wgpu::Device,
        settings: &DenoiseSettings,
        view: &wgpu::Buffer,
        width: u32,
        height: u32,
        history_rays: Option<u32>,
    ) -> Self {
        let source = shaders::with_common(
            &[shaders::VIEW, shaders::VISIBILITY_VARIANCE],
            shaders::ATROUS,
        );
        let module = crate::gpu::shader_module(device, "atrous", &source);
        let rays = [("RAYS", f64::from(history_rays.unwrap_or(0)))];
        let pipeline =
            |entry: &str| crate::gpu::entry_pipeline(device, "atrous", &module, entry, &rays, None);
        let params = (0..settings.iterations)
            .map(|i| {
                device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("atrous params"),
                    contents: bytemuck::bytes_of(&AtrousParams {
                        step: 1 << i,
                        sigma: settings.sigma,
                        _pad: [0.0; 2],
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
            // Each entry point's layout (made from what it uses): the moments pass and the last
            // iteration read the history, the iterations the parameters.
            if !std::ptr::eq(pipeline, &self.iterate) {
                entries.push((7, wgpu::BindingResource::TextureView(history)));
            }
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
