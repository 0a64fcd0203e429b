//! Source "depth pyramid" (seed 004 §3.3; McGuire et al., "Scalable Ambient Obscurance", 2012 §3):
//! levels 1 … L − 1 of linear depth, each texel the mean of K × K texels of the level below (level
//! 0 is the frame's depth), built by compute before the AO pass (`shaders/sources/depth_pyramid/`)
//! and read by the estimators that choose a level per sample (`sao`, `pyramid-hbao`). Kept as the
//! layers of one array texture, each layer the size of level 1, so the AO pass binds one texture.

use crate::bindings::{self, entry, SOURCE_PYRAMID_LEVELS, SOURCE_PYRAMID_PARAMS};
use crate::estimators::pyramid_level_size;
use crate::gpu::PassProfiler;
use crate::settings::PyramidSettings;
use crate::shaders;
use wgpu::util::DeviceExt;

/// The most levels, level 0 included (`PyramidParams.levels` in the WGSL holds eight).
pub const MAX_LEVELS: u32 = 8;

/// GPU mirror of `PyramidLevel` in build.wgsl.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct BuildLevel {
    below_size: [u32; 2],
    size: [u32; 2],
    factor: u32,
    _pad: [u32; 3],
}

/// Group-2 layout entries of the AO pass.
pub(crate) fn layout_entries() -> Vec<wgpu::BindGroupLayoutEntry> {
    vec![
        entry::uniform(SOURCE_PYRAMID_PARAMS),
        entry::texture_array(SOURCE_PYRAMID_LEVELS),
    ]
}

/// The pyramid's textures and the passes that fill them.
pub(crate) struct DepthPyramid {
    levels: u32,
    factor: u32,
    full: (u32, u32),
    texture: wgpu::Texture,
    /// All of `texture`, as the AO pass binds it.
    levels_view: wgpu::TextureView,
    params: wgpu::Buffer,
    build: wgpu::ComputePipeline,
    build_layout: wgpu::BindGroupLayout,
    /// Per level l ≥ 1: its `PyramidLevel` uniform.
    build_params: Vec<wgpu::Buffer>,
    /// Per level l ≥ 2: its build group (the level below is a layer of `texture`, fixed).
    build_groups: Vec<wgpu::BindGroup>,
}

impl DepthPyramid {
    pub fn new(device: &wgpu::Device, settings: &PyramidSettings, full: (u32, u32)) -> Self {
        let (levels, factor) = (settings.levels, settings.factor);
        let first = pyramid_level_size(full, factor, 1);
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("depth pyramid"),
            size: wgpu::Extent3d {
                width: first.0,
                height: first.1,
                depth_or_array_layers: (levels - 1).max(1),
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::R32Float,
            usage: wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::STORAGE_BINDING
                | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        let mut table = [[0.0f32; 4]; MAX_LEVELS as usize];
        for (l, row) in table.iter_mut().enumerate().take(levels as usize) {
            let (w, h) = pyramid_level_size(full, factor, l as u32);
            *row = [factor.pow(l as u32) as f32, w as f32, h as f32, 0.0];
        }
        let params = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("depth pyramid params"),
            contents: bytemuck::cast_slice(&table),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let build_layout = bindings::layout(
            device,
            "depth pyramid build",
            &[
                entry::uniform(0),
                entry::texture(1),
                entry::storage_texture_r32f(2),
            ],
        );
        let build = bindings::compute_pipeline(
            device,
            "depth pyramid build",
            shaders::DEPTH_PYRAMID_BUILD,
            &[],
            &[Some(&build_layout)],
        );
        let build_params: Vec<wgpu::Buffer> = (1..levels)
            .map(|l| {
                let (below, size) = (
                    pyramid_level_size(full, factor, l - 1),
                    pyramid_level_size(full, factor, l),
                );
                let level = BuildLevel {
                    below_size: [below.0, below.1],
                    size: [size.0, size.1],
                    factor,
                    _pad: [0; 3],
                };
                device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("depth pyramid level"),
                    contents: bytemuck::bytes_of(&level),
                    usage: wgpu::BufferUsages::UNIFORM,
                })
            })
            .collect();
        let levels_view = texture.create_view(&wgpu::TextureViewDescriptor {
            label: Some("depth pyramid levels"),
            dimension: Some(wgpu::TextureViewDimension::D2Array),
            ..Default::default()
        });
        let mut pyramid = Self {
            levels,
            factor,
            full,
            texture,
            levels_view,
            params,
            build,
            build_layout,
            build_params,
            build_groups: Vec::new(),
        };
        pyramid.build_groups = (2..levels)
            .map(|l| {
                let below = pyramid.layer_view(l - 1);
                pyramid.build_group(device, l, &below)
            })
            .collect();
        pyramid
    }

    /// A 2D view of level `l` ≥ 1 (layer l − 1).
    fn layer_view(&self, level: u32) -> wgpu::TextureView {
        self.texture.create_view(&wgpu::TextureViewDescriptor {
            label: Some("depth pyramid level"),
            dimension: Some(wgpu::TextureViewDimension::D2),
            base_array_layer: level - 1,
            array_layer_count: Some(1),
            ..Default::default()
        })
    }

    fn build_group(
        &self,
        device: &wgpu::Device,
        level: u32,
        below: &wgpu::TextureView,
    ) -> wgpu::BindGroup {
        bindings::group(
            device,
            "depth pyramid build",
            &self.build_layout,
            &[
                (0, self.build_params[level as usize - 1].as_entire_binding()),
                (1, wgpu::BindingResource::TextureView(below)),
                (
                    2,
                    wgpu::BindingResource::TextureView(&self.layer_view(level)),
                ),
            ],
        )
    }

    /// Records levels 1 … L − 1 from the frame's linear depth, one dispatch each.
    pub fn build(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        depth: &wgpu::TextureView,
        profiler: Option<&mut PassProfiler>,
    ) {
        if self.levels < 2 {
            return;
        }
        let first = self.build_group(device, 1, depth);
        let timestamp_writes = profiler.map(|p| p.compute_pass("depth_pyramid"));
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("depth pyramid"),
            timestamp_writes,
        });
        pass.set_pipeline(&self.build);
        for level in 1..self.levels {
            let group = if level == 1 {
                &first
            } else {
                &self.build_groups[level as usize - 2]
            };
            pass.set_bind_group(0, group, &[]);
            let (w, h) = pyramid_level_size(self.full, self.factor, level);
            pass.dispatch_workgroups(w.div_ceil(8), h.div_ceil(8), 1);
        }
    }

    /// The AO pass's group-2 resources.
    pub fn read_resources(&self) -> [(u32, wgpu::BindingResource<'_>); 2] {
        [
            (SOURCE_PYRAMID_PARAMS, self.params.as_entire_binding()),
            (
                SOURCE_PYRAMID_LEVELS,
                wgpu::BindingResource::TextureView(&self.levels_view),
            ),
        ]
    }

    /// Levels 1 … L − 1 of the last frame, each row-major over its own size
    /// ([`pyramid_level_size`]). Waits for the GPU.
    pub fn read_levels(&self, gpu: &crate::gpu::Gpu) -> Result<Vec<Vec<f32>>, crate::error::Error> {
        let width = self.texture.width() as usize;
        (1..self.levels)
            .map(|level| {
                let bytes = crate::gpu::read_texture_layer_bytes(gpu, &self.texture, level - 1, 4)?;
                let texels: Vec<f32> = bytemuck::pod_collect_to_vec(&bytes);
                let (w, h) = pyramid_level_size(self.full, self.factor, level);
                Ok((0..h as usize)
                    .flat_map(|y| texels[y * width..y * width + w as usize].to_vec())
                    .collect())
            })
            .collect()
    }
}
