//! The BVH on the GPU: the flat nodes of [`Bvh::nodes`] and the triangles in leaf order, bound in
//! every ray-tracing pass (`shaders/common/bvh.wgsl`, six bindings from the includer's
//! `BVH_BINDING` in its `BVH_GROUP`) next to the scene's positions, vertex attributes (uv, normal), materials and textures
//! from [`GpuScene`].

use super::Bvh;
use crate::gpu::GpuError;
use crate::raster::gpu_scene::GpuScene;
use crate::scene::Scene;
use wgpu::util::DeviceExt;

/// A [`Bvh`] uploaded for the GPU traversal of `shaders/common/bvh.wgsl`: storage buffers in the
/// layout its bindings read, bound with [`GpuBvh::resources`] next to a [`GpuScene`]. Clones share
/// the buffers.
#[derive(Clone)]
pub struct GpuBvh {
    /// The four-wide tree of [`Bvh::nodes`] ([`super::wide::WideNode`], WGSL `BvhNode`, 128
    /// bytes each; one node of unused slots for an empty tree).
    pub nodes: wgpu::Buffer,
    /// `(i0, i1, i2, material)` per leaf slot.
    pub triangles: wgpu::Buffer,
    /// Leaf slot → index into `scene.triangles`.
    pub primitive_ids: wgpu::Buffer,
    /// Depth of the deepest leaf of the BVH2.
    pub max_depth: usize,
    /// The most stack entries the GPU traversal can need on this tree; the WGSL stack holds
    /// [`STACK_SIZE`] (rays that need more are reported).
    pub stack_bound: usize,
}

/// `BVH_STACK_SIZE` in bvh.wgsl. The four-wide walk of real scenes' trees holds about 1.5 entries
/// per BVH2 level (Crytek Sponza: 52 for a BVH2 36 deep); a tree whose four-wide walk could need
/// more is walked two-wide, which needs no more than its depth ([`super::build::MAX_DEPTH`]). A
/// stack of 96 entries made the ray-traced passes 2–16 % slower on an H200 (BENCHMARKS.md).
pub const STACK_SIZE: usize = 64;

impl GpuBvh {
    /// Uploads `bvh`, built over `scene`, as its four-wide tree ([`super::wide`]), or two-wide
    /// where a four-wide walk could outgrow the GPU stack, with the triangles copied into leaf
    /// order. Logs a warning when even that could need more than the stack's [`STACK_SIZE`]
    /// entries (a tree deeper than the build's bound); overflowing rays are counted.
    ///
    /// Its buffers are checked against the device's limits first
    /// ([`crate::gpu::check_scene_buffers`]).
    pub fn new(device: &wgpu::Device, bvh: &Bvh, scene: &Scene) -> Result<Self, GpuError> {
        // An empty tree still binds: one node of unused slots, which no ray enters.
        let (mut nodes, mut stack_bound) = super::wide::widen(bvh.nodes(), 4);
        if stack_bound > STACK_SIZE {
            // Four-wide, a path can hold up to three entries a level: where that outgrows the
            // stack, two children a node push at most one a level, which a tree of
            // build::MAX_DEPTH levels never outgrows.
            (nodes, stack_bound) = super::wide::widen(bvh.nodes(), 2);
        }
        let ids = bvh.primitive_indices();
        crate::gpu::check_scene_buffers(
            &device.limits(),
            &scene.name,
            &[
                ("bvh nodes", std::mem::size_of_val(nodes.as_slice()) as u64),
                ("bvh triangles", ids.len() as u64 * 16),
                ("bvh primitive ids", std::mem::size_of_val(ids) as u64),
            ],
        )?;
        let triangles: Vec<[u32; 4]> = ids
            .iter()
            .map(|&t| {
                let [a, b, c] = scene.triangles[t as usize];
                [a, b, c, scene.triangle_materials[t as usize]]
            })
            .collect();
        if stack_bound > STACK_SIZE {
            log::warn!(
                "the BVH may need {stack_bound} stack entries, more than the GPU traversal's \
                 {STACK_SIZE}; overflowing rays are counted"
            );
        }
        // Empty buffers (an empty scene) are padded to bind (gpu::storage_buffer_init).
        let storage =
            |label, contents: &[u8]| crate::gpu::storage_buffer_init(device, label, contents);
        Ok(Self {
            nodes: storage("bvh nodes", bytemuck::cast_slice(&nodes)),
            triangles: storage("bvh triangles", bytemuck::cast_slice(&triangles)),
            primitive_ids: storage("bvh primitive ids", bytemuck::cast_slice(ids)),
            max_depth: bvh.max_depth(),
            stack_bound,
        })
    }

    /// Layout entries of `shaders/common/bvh.wgsl`'s six bindings from `first` on (its
    /// `BVH_BINDING`), visible to compute.
    pub fn layout_entries(first: u32) -> Vec<wgpu::BindGroupLayoutEntry> {
        use crate::bindings::entry;
        vec![
            entry::storage(first, true),
            entry::storage(first + 1, true),
            entry::storage(first + 2, true),
            entry::storage(first + 3, true),
            entry::storage(first + 4, true),
            entry::texture_array(first + 5),
        ]
    }

    /// The resources of those bindings: nodes and triangles, then the scene's positions, vertex attributes,
    /// materials and alpha-mask atlas.
    pub fn resources<'a>(
        &'a self,
        first: u32,
        scene: &'a GpuScene,
    ) -> Vec<(u32, wgpu::BindingResource<'a>)> {
        vec![
            (first, self.nodes.as_entire_binding()),
            (first + 1, self.triangles.as_entire_binding()),
            (first + 2, scene.positions.as_entire_binding()),
            (first + 3, scene.attributes.as_entire_binding()),
            (first + 4, scene.materials.as_entire_binding()),
            (
                first + 5,
                wgpu::BindingResource::TextureView(&scene.textures),
            ),
        ]
    }
}

/// One ray of a [`trace_batch`] (t in units of `dir`, `t_min >= 0`).
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct QueryRay {
    /// Ray origin, world space.
    pub origin: [f32; 3],
    /// Start of the interval searched, in units of `dir`.
    pub t_min: f32,
    /// Ray direction, world space; need not be normalised.
    pub dir: [f32; 3],
    /// End of the interval searched, in units of `dir`.
    pub t_max: f32,
}

/// What [`trace_batch`] found for one ray (mirrors `QueryResult` in `shaders/bvh/ray_query.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct QueryResult {
    /// Closest hit's t, or -1 for none (closest mode).
    pub t: f32,
    /// Closest hit's index into `scene.triangles` (`u32::MAX` for none).
    pub triangle: u32,
    /// Closest hit's barycentric weight of the triangle's vertex 1 (as [`super::Hit::u`]).
    pub u: f32,
    /// Closest hit's barycentric weight of the triangle's vertex 2 (as [`super::Hit::v`]).
    pub v: f32,
    /// 1 when the closest hit is a front face (counter-clockwise seen from the origin), else 0.
    pub front_face: u32,
    /// All-hits mode: the number of hits, the first 16 triangles in `triangles`.
    pub hit_count: u32,
    /// Non-zero when the traversal stack overflowed (the result is then incomplete).
    pub stack_overflow: u32,
    _pad: u32,
    /// All-hits mode: the first 16 hits' indices into `scene.triangles` (`hit_count` may be more).
    pub triangles: [u32; 16],
}

/// What [`trace_batch`] asks of every ray.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum QueryMode {
    /// The nearest hit in `[t_min, t_max]`: `t`, `triangle`, `u`, `v`, `front_face`.
    ClosestHit = 0,
    /// Every hit in `[t_min, t_max]`: `hit_count` and the first 16 in `triangles`.
    AllHits = 1,
}

/// Trace `rays` through the GPU BVH: the traversal every GPU ray-tracing pass uses, exposed for
/// checking it against the CPU oracle.
pub fn trace_batch(
    gpu: &crate::gpu::Gpu,
    scene: &GpuScene,
    bvh: &GpuBvh,
    rays: &[QueryRay],
    mode: QueryMode,
) -> Result<Vec<QueryResult>, crate::gpu::GpuError> {
    let device = &gpu.device;
    let source = crate::shaders::with_common(
        &[crate::shaders::MATERIAL, crate::shaders::BVH],
        crate::shaders::RAY_QUERY,
    );
    // ray_query.wgsl names its own BVH group (1) and first binding (0).
    let pipeline = crate::gpu::compute_pipeline_with(device, "ray query", &source, &[]);
    let params = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("ray query params"),
        contents: bytemuck::cast_slice(&[rays.len() as u32, mode as u32, 0, 0]),
        usage: wgpu::BufferUsages::UNIFORM,
    });
    let ray_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("query rays"),
        contents: bytemuck::cast_slice(rays),
        usage: wgpu::BufferUsages::STORAGE,
    });
    let size = (rays.len().max(1) * std::mem::size_of::<QueryResult>()) as u64;
    let results = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("query results"),
        size,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let staging = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("query readback"),
        size,
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let group0 = crate::gpu::bind_group(
        device,
        "ray query",
        &pipeline.get_bind_group_layout(0),
        &[
            params.as_entire_binding(),
            ray_buffer.as_entire_binding(),
            results.as_entire_binding(),
            bvh.primitive_ids.as_entire_binding(),
        ],
    );
    let group1 = crate::bindings::group(
        device,
        "bvh",
        &pipeline.get_bind_group_layout(1),
        &bvh.resources(0, scene),
    );
    let mut encoder = device.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_compute_pass(&Default::default());
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &group0, &[]);
        pass.set_bind_group(1, &group1, &[]);
        pass.dispatch_workgroups((rays.len() as u32).div_ceil(64), 1, 1);
    }
    encoder.copy_buffer_to_buffer(&results, 0, &staging, 0, size);
    gpu.queue.submit([encoder.finish()]);
    let bytes = crate::gpu::read_buffer(gpu, &staging)?;
    let mut out: Vec<QueryResult> = bytemuck::pod_collect_to_vec(&bytes);
    out.truncate(rays.len());
    Ok(out)
}
