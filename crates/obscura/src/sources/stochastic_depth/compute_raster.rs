//! The stochastic depth map rasterised in compute (`shaders/sources/stochastic_depth/
//! compute_raster.wgsl`, ours; issue 16): the map's triangles binned and rasterised by compute
//! passes instead of the hardware's rasteriser, each fragment handled by the same Alg. 1 code
//! (`map.wgsl`'s `sd_fragment`); triangles that cross the near plane are clipped there too. Any
//! whose record or items do not fit the passes' buffers are listed for the hardware
//! ([`ComputeRaster::record_left`]). Timed as `sd_bin` and `sd_tiles`.

use crate::gpu::PassProfiler;
use crate::raster::gpu_scene::GpuScene;

/// `SdComputeRaster` of compute_raster.wgsl.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct SdComputeRaster {
    size: [u32; 2],
    triangle_count: u32,
    culled_count: u32,
    opaque_count: u32,
    item_capacity: u32,
    record_capacity: u32,
    _pad: u32,
}

/// `cr_counts` of compute_raster.wgsl: items, records, triangles left to the hardware,
/// overflows, fragments shaded by the bin pass and by the tile pass.
const COUNTERS: usize = 6;

/// Bytes of one `CrRecord`.
const RECORD_BYTES: u64 = 128;
/// Room for items and records per 8×8 tile of the map. Crytek Sponza from BENCHMARKS.md's camera
/// needed 4.7 items and 3.5 records a tile at 480×270 (+ 16 px band), 3.7 and 2.3 at 960×540
/// (+ 32), 3.0 and 1.6 at 1920×1080 (Sibenik there: 1.3 and 0.8); triangles that do not fit are
/// drawn by the hardware (correct, only slower).
const ITEMS_PER_TILE: u64 = 16;
const RECORDS_PER_TILE: u64 = 8;
/// Workgroups of the tile pass (each takes every `TILE_GROUPS`-th item): enough to fill a large
/// GPU (an H200 holds 132 × 32 workgroups of 64 invocations at once).
const TILE_GROUPS: u32 = 8192;
/// Bin workgroups (64 triangles each) per dispatch row.
const ROW: u32 = 65535;

#[cfg(test)]
thread_local! {
    /// Tests: the item and record capacity of the passes made on this thread (to make them
    /// overflow).
    pub(crate) static ITEM_CAPACITY: std::cell::Cell<Option<u64>> = const { std::cell::Cell::new(None) };
    /// Tests: false makes the passes on this thread hand on and test every tile of a box, as if
    /// the triangle touched them all (`CR_TILE_TESTS`), to hold the tests to skipping work only.
    pub(crate) static TILE_TESTS: std::cell::Cell<bool> = const { std::cell::Cell::new(true) };
    /// Tests: how many items a triangle's own invocation writes before its workgroup writes
    /// them together (`CR_OWN_ITEMS`); test frames are too small to reach the default.
    pub(crate) static OWN_ITEMS: std::cell::Cell<u32> = const { std::cell::Cell::new(OWN_ITEMS_DEFAULT) };
}

/// `CR_OWN_ITEMS` of compute_raster.wgsl.
const OWN_ITEMS_DEFAULT: u32 = 16;

pub(crate) struct ComputeRaster {
    bin: wgpu::ComputePipeline,
    tiles: wgpu::ComputePipeline,
    /// Items written, records written, triangles left to the hardware, overflows, and the
    /// fragments the bin and tile passes shaded.
    counts: wgpu::Buffer,
    own_group: wgpu::BindGroup,
    /// `draw_indirect` arguments of the triangles left to the hardware, per group of
    /// [`GpuScene::visibility_ranges`], and what they start from each frame (no triangle).
    left_args: wgpu::Buffer,
    left_args_empty: wgpu::Buffer,
    /// The left triangles as the raster pipelines' group 1 (`drawn_triangles`).
    left_group: wgpu::BindGroup,
    triangle_count: u32,
}

/// Storage buffers the passes bind in one shader stage: the scene's four, the mask table, the
/// map, the request mask where the map is limited to it, and the passes' own five.
fn storage_buffers_needed(requested: bool) -> u32 {
    11 + u32::from(requested)
}

/// Whether `device` can run the passes (for a map limited to requested pixels with `requested`).
pub(crate) fn available(device: &wgpu::Device, requested: bool) -> bool {
    device.limits().max_storage_buffers_per_shader_stage >= storage_buffers_needed(requested)
}

impl ComputeRaster {
    /// The passes for a map of `map_size` pixels (its band included) over the draw-ordered
    /// `scene`, from `source` (map.wgsl and what it needs, without this file), binding the map
    /// pass's `map_bindings` after the scene's (the request mask last where `requested`). Errors
    /// where the device binds too few storage buffers per shader stage.
    pub fn new(
        adapter: &wgpu::Adapter,
        device: &wgpu::Device,
        source: &str,
        scene: &GpuScene,
        map_size: (u32, u32),
        map_bindings: &[(wgpu::ShaderStages, wgpu::BindingType)],
        requested: bool,
    ) -> Result<Self, crate::error::Error> {
        use crate::bindings::entry;
        if !available(device, requested) {
            let needed = storage_buffers_needed(requested);
            let allowed = device.limits().max_storage_buffers_per_shader_stage;
            return Err(crate::error::SettingsError::Unsupported {
                field: "stochastic_depth.rasterizer",
                value: "compute".into(),
                adapter: adapter.get_info().name,
                reason: format!(
                    "the compute rasteriser binds {needed} storage buffers in one shader stage and this device allows {allowed}; use rasterizer = \"hardware\""
                ),
            }
            .into());
        }
        let requested_fn = if requested {
            "fn cr_requested(pixel: vec2<u32>) -> bool { return sd_requested(pixel); }\n"
        } else {
            "fn cr_requested(pixel: vec2<u32>) -> bool { return true; }\n"
        };
        #[cfg(not(test))]
        let (tile_tests, own_items) = (true, OWN_ITEMS_DEFAULT);
        #[cfg(test)]
        let (tile_tests, own_items) = (TILE_TESTS.with(|t| t.get()), OWN_ITEMS.with(|o| o.get()));
        let source = format!(
            "{source}\n{requested_fn}const CR_TILE_TESTS: bool = {tile_tests};\n\
             const CR_OWN_ITEMS: u32 = {own_items}u;\n{}",
            crate::shaders::STOCHASTIC_DEPTH_COMPUTE_RASTER
        );
        let module = crate::gpu::shader_module(device, "sd compute raster", &source);
        let compute = wgpu::ShaderStages::COMPUTE;
        let map_bindings: Vec<_> = map_bindings.iter().map(|&(_, ty)| (compute, ty)).collect();
        let scene_group =
            crate::raster::gbuffer::scene_group_layout(device, compute, &map_bindings);
        let empty = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("empty"),
            entries: &[],
        });
        let own_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("sd compute raster"),
            entries: &[
                entry::uniform(0),
                entry::storage(1, false),
                entry::storage(2, false),
                entry::storage(3, false),
                entry::storage(4, false),
                entry::storage(5, false),
            ]
            .map(|mut e| {
                e.visibility = wgpu::ShaderStages::COMPUTE;
                e
            }),
        });
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("sd compute raster"),
            bind_group_layouts: &[Some(&scene_group), Some(&empty), Some(&own_layout)],
            immediate_size: 0,
        });
        let pipeline = |entry_point| {
            crate::gpu::dump_constants("sd compute raster", entry_point, &[]);
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(entry_point),
                layout: Some(&layout),
                module: &module,
                entry_point: Some(entry_point),
                compilation_options: Default::default(),
                cache: None,
            })
        };
        let tiles = u64::from(map_size.0.div_ceil(8)) * u64::from(map_size.1.div_ceil(8));
        let max = device.limits().max_storage_buffer_binding_size;
        let item_capacity = (tiles * ITEMS_PER_TILE).max(1024).min(max / 8);
        #[cfg(test)]
        let item_capacity = ITEM_CAPACITY.with(|c| c.get()).unwrap_or(item_capacity);
        let record_capacity = (tiles * RECORDS_PER_TILE).max(1024).min(max / RECORD_BYTES);
        #[cfg(test)]
        let record_capacity = ITEM_CAPACITY.with(|c| c.get()).unwrap_or(record_capacity);
        let buffer = |label, size: u64| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: size.max(16),
                usage: wgpu::BufferUsages::STORAGE
                    | wgpu::BufferUsages::COPY_DST
                    | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            })
        };
        let params = SdComputeRaster {
            size: [map_size.0, map_size.1],
            triangle_count: scene.triangle_count,
            culled_count: scene.culled_count,
            opaque_count: scene.opaque_count,
            item_capacity: item_capacity as u32,
            record_capacity: record_capacity as u32,
            _pad: 0,
        };
        let params = wgpu::util::DeviceExt::create_buffer_init(
            device,
            &wgpu::util::BufferInitDescriptor {
                label: Some("sd compute raster params"),
                contents: bytemuck::bytes_of(&params),
                usage: wgpu::BufferUsages::UNIFORM,
            },
        );
        let counts = buffer("sd compute raster counts", 4 * COUNTERS as u64);
        let items = buffer("sd compute raster items", item_capacity * 8);
        let records = buffer("sd compute raster records", record_capacity * RECORD_BYTES);
        let left = buffer(
            "sd compute raster left",
            u64::from(scene.triangle_count) * 4,
        );
        // Each group's list starts at its first triangle: a draw's vertex v reads entry v / 3.
        let empty_args: Vec<u32> = scene
            .visibility_ranges()
            .iter()
            .flat_map(|r| [0, 1, 3 * r.start, 0])
            .collect();
        let left_args_empty = wgpu::util::DeviceExt::create_buffer_init(
            device,
            &wgpu::util::BufferInitDescriptor {
                label: Some("sd compute raster left args, empty"),
                contents: bytemuck::cast_slice(&empty_args),
                usage: wgpu::BufferUsages::COPY_SRC,
            },
        );
        let left_args = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("sd compute raster left args"),
            size: 48,
            usage: wgpu::BufferUsages::STORAGE
                | wgpu::BufferUsages::INDIRECT
                | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let left_group = crate::gpu::bind_group(
            device,
            "sd compute raster left",
            &crate::raster::triangle_cull::drawn_layout(device),
            &[left.as_entire_binding()],
        );
        let own_group = crate::gpu::bind_group(
            device,
            "sd compute raster",
            &own_layout,
            &[
                params.as_entire_binding(),
                counts.as_entire_binding(),
                items.as_entire_binding(),
                records.as_entire_binding(),
                left.as_entire_binding(),
                left_args.as_entire_binding(),
            ],
        );
        Ok(Self {
            bin: pipeline("sd_raster_bin"),
            tiles: pipeline("sd_raster_tiles"),
            counts,
            own_group,
            left_args,
            left_args_empty,
            left_group,
            triangle_count: scene.triangle_count,
        })
    }

    /// Bins and rasterises the frame's triangles into the map; `resources`: the map pass's
    /// bindings of group 0.
    pub fn encode(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        resources: &[wgpu::BindingResource],
        mut profiler: Option<&mut PassProfiler>,
    ) {
        let scene_group = crate::gpu::bind_group(
            device,
            "sd compute raster scene",
            &self.bin.get_bind_group_layout(0),
            resources,
        );
        encoder.clear_buffer(&self.counts, 0, None);
        encoder.copy_buffer_to_buffer(&self.left_args_empty, 0, &self.left_args, 0, 48);
        let groups = self.triangle_count.div_ceil(64).max(1);
        for (name, pipeline, (x, y)) in [
            ("sd_bin", &self.bin, (groups.min(ROW), groups.div_ceil(ROW))),
            ("sd_tiles", &self.tiles, (TILE_GROUPS, 1)),
        ] {
            let timestamp_writes = profiler.as_deref_mut().map(|p| p.compute_pass(name));
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some(name),
                timestamp_writes,
            });
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, &scene_group, &[]);
            pass.set_bind_group(2, &self.own_group, &[]);
            pass.dispatch_workgroups(x, y, 1);
        }
        if let Some(p) = profiler {
            p.copy_fragments(encoder, "sd_bin", &self.counts, 16);
            p.copy_fragments(encoder, "sd_tiles", &self.counts, 20);
        }
    }

    /// Draws the triangles the bin pass left to the hardware with `pipelines` (the map's, one
    /// per group of [`GpuScene::visibility_ranges`]), their group 0 being `group`.
    pub fn record_left(
        &self,
        pass: &mut wgpu::RenderPass,
        pipelines: &[wgpu::RenderPipeline; 3],
        group: &wgpu::BindGroup,
    ) {
        pass.set_bind_group(0, group, &[]);
        pass.set_bind_group(1, &self.left_group, &[]);
        for (g, pipeline) in pipelines.iter().enumerate() {
            pass.set_pipeline(pipeline);
            pass.draw_indirect(&self.left_args, 16 * g as u64);
        }
    }

    /// The counters of the last frame (items, records, triangles left to the hardware, records
    /// or item runs that did not fit, fragments shaded by the bin and the tile pass). Waits for
    /// the GPU.
    #[cfg(test)]
    pub fn read_counts(
        &self,
        gpu: &crate::gpu::Gpu,
    ) -> Result<[u32; COUNTERS], crate::error::Error> {
        let bytes = crate::gpu::read_buffer_copy(gpu, &self.counts)?;
        let v: Vec<u32> = bytemuck::pod_collect_to_vec(&bytes);
        Ok(std::array::from_fn(|i| v[i]))
    }
}

#[cfg(test)]
mod tests;
