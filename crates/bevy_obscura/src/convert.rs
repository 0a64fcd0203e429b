//! Between Bevy and obscura: matrices (Bevy 0.19 uses glam 0.32, obscura glam 0.34; the same
//! column-major layout), and the AO copy into Bevy's SSAO texture (`shaders/ao_copy.wgsl`).

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
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("obscura ao copy"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::COMPUTE,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Float { filterable: false },
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 1,
                    visibility: wgpu::ShaderStages::COMPUTE,
                    ty: wgpu::BindingType::StorageTexture {
                        access: wgpu::StorageTextureAccess::WriteOnly,
                        format,
                        view_dimension: wgpu::TextureViewDimension::D2,
                    },
                    count: None,
                },
            ],
        });
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
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("obscura ao copy"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(
                        &ao.create_view(&Default::default()),
                    ),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(
                        &target.create_view(&Default::default()),
                    ),
                },
            ],
        });
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("obscura ao copy"),
            timestamp_writes: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &bind_group, &[]);
        pass.dispatch_workgroups(target.width().div_ceil(8), target.height().div_ceil(8), 1);
    }
}
