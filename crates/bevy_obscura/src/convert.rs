//! Between Bevy and obscura: matrices (Bevy 0.19 uses glam 0.32, obscura glam 0.34; the same
//! column-major layout), and the AO copy into Bevy's SSAO texture (`shaders/ao_copy.wgsl`).

use obscura::bindings::{self, entry};

/// A Bevy matrix as obscura's.
pub(crate) fn mat4(m: bevy::math::Mat4) -> glam::Mat4 {
    glam::Mat4::from_cols_array(&m.to_cols_array())
}

/// The compute pass that writes obscura's AO into Bevy's SSAO texture.
pub(crate) struct AoCopy {
    format: wgpu::TextureFormat,
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::ComputePipeline,
}

impl AoCopy {
    /// The pass for Bevy's texture format (`R16Float` or `R32Float`).
    pub fn new(device: &wgpu::Device, format: wgpu::TextureFormat) -> Result<Self, String> {
        let name = match format {
            wgpu::TextureFormat::R16Float => "r16float",
            wgpu::TextureFormat::R32Float => "r32float",
            other => {
                return Err(format!(
                    "Bevy's SSAO texture is {other:?}, which obscura cannot write"
                ))
            }
        };
        let source = include_str!("shaders/ao_copy.wgsl").replace("AO_FORMAT", name);
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("obscura ao copy"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let layout = bindings::layout(
            device,
            "obscura ao copy",
            &[entry::texture(0), entry::storage_texture(1, format)],
        );
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("obscura ao copy"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("obscura ao copy"),
            layout: Some(&pipeline_layout),
            module: &module,
            entry_point: Some("copy_ao"),
            compilation_options: Default::default(),
            cache: None,
        });
        Ok(Self {
            format,
            layout,
            pipeline,
        })
    }

    /// The format it writes.
    pub fn format(&self) -> wgpu::TextureFormat {
        self.format
    }

    /// Records the copy of `ao` (obscura's output) into `target` (Bevy's texture, same size).
    pub fn encode(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        ao: &wgpu::Texture,
        target: &wgpu::Texture,
    ) {
        let view = |t: &wgpu::Texture| t.create_view(&Default::default());
        let (ao, target_view) = (view(ao), view(target));
        let bind_group = bindings::group(
            device,
            "obscura ao copy",
            &self.layout,
            &[
                (0, wgpu::BindingResource::TextureView(&ao)),
                (1, wgpu::BindingResource::TextureView(&target_view)),
            ],
        );
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("obscura ao copy"),
            timestamp_writes: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &bind_group, &[]);
        pass.dispatch_workgroups(target.width().div_ceil(8), target.height().div_ceil(8), 1);
    }
}
