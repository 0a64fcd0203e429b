//! Reading the stochastic depth map back for debug images and tests
//! (`shaders/sources/stochastic_depth/unpack.wgsl`): multisampled textures cannot be copied to a
//! buffer, so a compute pass unpacks one sample layer at a time.

use super::{bindings_wgsl, read_layout_entries, StochasticDepthMap};
use crate::bindings::{self, entry, GROUP_SCHEDULE, GROUP_SOURCE, UNPACK_LAYER, UNPACK_OUT};
use crate::{shaders, Error};
use wgpu::util::DeviceExt;

impl StochasticDepthMap {
    /// Every sample layer of the last map rendered, as linear depth (0 = empty), framebuffer-sized
    /// and row-major: `layers[m * samples_per_map + s]` is sample `s` of map `m`. Waits for the GPU.
    pub fn read_layers(&self, gpu: &crate::Gpu) -> Result<Vec<Vec<f32>>, Error> {
        let device = &gpu.device;
        let wgsl = bindings_wgsl(self.layout());
        let source = shaders::compose(&[&wgsl, shaders::STOCHASTIC_DEPTH_UNPACK]);
        // The map binds as the source group (as the AO passes read it), the layer as group 3.
        let map_layout = bindings::layout(device, "sd map", &read_layout_entries(self.layout()));
        let layer_layout = bindings::layout(
            device,
            "sd unpack layer",
            &[
                entry::uniform(UNPACK_LAYER),
                entry::storage(UNPACK_OUT, false),
            ],
        );
        let pipeline = bindings::compute_pipeline(
            device,
            "sd unpack",
            &source,
            &[],
            &bindings::by_group(&[(GROUP_SOURCE, &map_layout), (GROUP_SCHEDULE, &layer_layout)]),
        );
        let map_group = bindings::group(device, "sd map", &map_layout, &self.read_resources());
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
                let layer_group = bindings::group(
                    device,
                    "sd unpack layer",
                    &layer_layout,
                    &[
                        (UNPACK_LAYER, layer.as_entire_binding()),
                        (UNPACK_OUT, out.as_entire_binding()),
                    ],
                );
                let mut encoder = device.create_command_encoder(&Default::default());
                {
                    let mut pass = encoder.begin_compute_pass(&Default::default());
                    pass.set_pipeline(&pipeline);
                    pass.set_bind_group(GROUP_SOURCE, &map_group, &[]);
                    pass.set_bind_group(GROUP_SCHEDULE, &layer_group, &[]);
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
