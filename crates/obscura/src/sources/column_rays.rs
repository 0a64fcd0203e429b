//! Hidden-depth source "column rays" (seed 000 §3.6, Fig. 6): occluded and off-screen VAO samples
//! trace their camera ray through the scene's BVH (`shaders/sources/column_rays.wgsl`, the tracing
//! in `column_trace.wgsl`). It reads the VAO estimator's columns, so it is a VAO-only source (the
//! technique table checks it). The ground truth traces the same columns from the near plane
//! (`all_layers.wgsl`).

use crate::bindings::{entry, SOURCE_BVH, SOURCE_RAY_CAMERA, SOURCE_STACK_OVERFLOWS};
use crate::bvh::gpu::GpuBvh;
use crate::raster::gpu_scene::GpuScene;

/// GPU mirror of `RayCamera` in `shaders/sources/column_trace.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct RayCamera {
    camera_to_world: [[f32; 4]; 4],
    near: f32,
    _pad: [f32; 3],
}

/// The WGSL in front of the source functions: the BVH traversal, its bindings and the column
/// tracing.
pub(crate) fn trace_wgsl() -> [&'static str; 4] {
    use crate::shaders;
    [
        shaders::MATERIAL,
        shaders::BVH,
        shaders::SOURCE_RAY_CAMERA,
        shaders::SOURCE_COLUMN_TRACE,
    ]
}

/// The BVH rays source's WGSL (`rtao`): the BVH traversal, its bindings and the hemisphere rays'
/// tracing. It binds what column rays bind ([`layout_entries`], [`ColumnRays`]).
pub(crate) fn bvh_rays_wgsl() -> [&'static str; 4] {
    use crate::shaders;
    [
        shaders::MATERIAL,
        shaders::BVH,
        shaders::SOURCE_RAY_CAMERA,
        shaders::SOURCE_BVH_RAYS,
    ]
}

/// Group-2 layout entries: camera, overflow counter, then the BVH.
pub(crate) fn layout_entries() -> Vec<wgpu::BindGroupLayoutEntry> {
    let mut entries = vec![
        entry::uniform(SOURCE_RAY_CAMERA),
        entry::storage(SOURCE_STACK_OVERFLOWS, false),
    ];
    entries.extend(GpuBvh::layout_entries(SOURCE_BVH));
    entries
}

/// What the column rays bind: the camera, the overflow counter and the BVH.
pub(crate) struct ColumnRays {
    camera: wgpu::Buffer,
    /// `stack_overflows` of column_trace.wgsl (cleared every frame).
    pub stack_overflows: wgpu::Buffer,
    layout: wgpu::BindGroupLayout,
    scene: GpuScene,
    bvh: GpuBvh,
}

impl ColumnRays {
    pub fn new(
        device: &wgpu::Device,
        layout: &wgpu::BindGroupLayout,
        scene: &GpuScene,
        bvh: &GpuBvh,
    ) -> Self {
        let camera = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("ray camera"),
            size: std::mem::size_of::<RayCamera>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let stack_overflows = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("stack overflows"),
            size: 4,
            usage: wgpu::BufferUsages::STORAGE
                | wgpu::BufferUsages::COPY_DST
                | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        Self {
            camera,
            stack_overflows,
            layout: layout.clone(),
            scene: scene.clone(),
            bvh: bvh.clone(),
        }
    }

    /// The group of one frame. Made anew each frame, as the other sources make theirs: with one
    /// bind group kept for the renderer's life, resident memory sometimes grew by ~240 bytes a
    /// frame on an H200 over 100k frames (RELIABILITY.md); a fresh one costs microseconds.
    pub fn group(&self, device: &wgpu::Device) -> wgpu::BindGroup {
        let mut resources = vec![
            (SOURCE_RAY_CAMERA, self.camera.as_entire_binding()),
            (
                SOURCE_STACK_OVERFLOWS,
                self.stack_overflows.as_entire_binding(),
            ),
        ];
        resources.extend(self.bvh.resources(SOURCE_BVH, &self.scene));
        crate::bindings::group(device, "column rays", &self.layout, &resources)
    }

    pub fn set_camera(&self, queue: &wgpu::Queue, camera_to_world: glam::Mat4, near: f32) {
        let camera = RayCamera {
            camera_to_world: camera_to_world.to_cols_array_2d(),
            near,
            _pad: [0.0; 3],
        };
        queue.write_buffer(&self.camera, 0, bytemuck::bytes_of(&camera));
    }
}
