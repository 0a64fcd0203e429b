//! Reading the stochastic depth map back for debug images and tests (`shaders/sd_unpack.wgsl`):
//! multisampled textures cannot be copied to a buffer, so a compute pass unpacks one sample layer
//! at a time.

use super::stochastic_depth::{bindings_wgsl, StochasticDepthMap};
use crate::{shaders, Error};
use wgpu::util::DeviceExt;

impl StochasticDepthMap {
    /// Every sample layer of the last map rendered, as linear depth (0 = empty), framebuffer-sized
    /// and row-major: `layers[m * samples_per_map + s]` is sample `s` of map `m`. Waits for the GPU.
    pub fn read_layers(&self, gpu: &crate::Gpu) -> Result<Vec<Vec<f32>>, Error> {
        let device = &gpu.device;
        let source = format!("{}\n{}", bindings_wgsl(self.layout()), shaders::SD_UNPACK);
        let pipeline = crate::gpu::compute_pipeline_with(device, "sd unpack", &source, &[]);
        // The readers' bindings start at 5 (after the VAO frame's 0–4).
        let entries: Vec<_> = self
            .read_resources()
            .into_iter()
            .zip(5..)
            .map(|(resource, binding)| wgpu::BindGroupEntry { binding, resource })
            .collect();
        let group0 = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("sd unpack"),
            layout: &pipeline.get_bind_group_layout(0),
            entries: &entries,
        });
        let (w, h) = self.size();
        let size = u64::from(w) * u64::from(h) * 4;
        let mut layers = Vec::new();
        for m in 0..self.layout().maps {
            for s in 0..self.layout().samples_per_map {
                let layer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("sd unpack layer"),
                    contents: bytemuck::cast_slice(&[m, s, 0, 0]),
                    usage: wgpu::BufferUsages::UNIFORM,
                });
                let out = device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("sd unpacked"),
                    size,
                    usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                    mapped_at_creation: false,
                });
                let staging = device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("sd unpack readback"),
                    size,
                    usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
                    mapped_at_creation: false,
                });
                let group1 = crate::gpu::bind_group(
                    device,
                    "sd unpack layer",
                    &pipeline.get_bind_group_layout(1),
                    &[layer.as_entire_binding(), out.as_entire_binding()],
                );
                let mut encoder = device.create_command_encoder(&Default::default());
                {
                    let mut pass = encoder.begin_compute_pass(&Default::default());
                    pass.set_pipeline(&pipeline);
                    pass.set_bind_group(0, &group0, &[]);
                    pass.set_bind_group(1, &group1, &[]);
                    pass.dispatch_workgroups(w.div_ceil(8), h.div_ceil(8), 1);
                }
                encoder.copy_buffer_to_buffer(&out, 0, &staging, 0, size);
                gpu.queue.submit([encoder.finish()]);
                layers.push(bytemuck::pod_collect_to_vec(&crate::gpu::read_buffer(
                    gpu, &staging,
                )?));
            }
        }
        gpu.check_errors()?;
        Ok(layers)
    }
}
