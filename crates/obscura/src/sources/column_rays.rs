//! Hidden-depth source "column rays" (seed 000 §3.6, Fig. 6): occluded and off-screen VAO samples
//! trace their camera ray through the scene's BVH (`shaders/sources/column_rays.wgsl`, the tracing
//! in `column_trace.wgsl`). It reads the VAO estimator's columns, so it is a VAO-only source (the
//! technique table checks it). The ground truth traces the same columns from the near plane
//! (`all_layers.wgsl`).

use crate::bindings::{
    entry, SOURCE_BVH, SOURCE_DRAWN_TRIANGLES, SOURCE_RAY_CAMERA, SOURCE_STACK_OVERFLOWS,
    SOURCE_VISIBLE_TRIANGLES,
};
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
/// tracing, and with `proofs` phase 1's screen-space proofs (two-phase phase 1), else none. It
/// binds what column rays bind ([`layout_entries`], [`ColumnRays`]); phase 1
/// [`proof_layout_entries`].
pub(crate) fn bvh_rays_wgsl(proofs: bool) -> [&'static str; 5] {
    use crate::shaders;
    [
        shaders::MATERIAL,
        shaders::BVH,
        shaders::SOURCE_RAY_CAMERA,
        shaders::SOURCE_BVH_RAYS,
        if proofs {
            shaders::SOURCE_BVH_RAYS_PROOF
        } else {
            shaders::SOURCE_BVH_RAYS_NO_PROOF
        },
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

/// Group-2 layout entries of phase 1 of two-phase BVH rays (`shaders/sources/bvh_rays_proof.wgsl`'s
/// proofs): the camera; of the BVH's bindings the scene's vertices, attributes, materials and
/// alpha atlas (phase 1 tests single triangles and never walks the tree, so not the nodes and
/// leaf triangles: WebGPU's eight storage buffers a stage); then the visible triangles and the
/// drawn triangles they index.
pub(crate) fn proof_layout_entries() -> Vec<wgpu::BindGroupLayoutEntry> {
    let mut entries = vec![entry::uniform(SOURCE_RAY_CAMERA)];
    entries.extend(GpuBvh::layout_entries(SOURCE_BVH).into_iter().skip(2));
    entries.push(entry::texture_uint(SOURCE_VISIBLE_TRIANGLES));
    entries.push(entry::storage(SOURCE_DRAWN_TRIANGLES, true));
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
    /// Phase 1's visible triangles where the frame has none (1×1, 0: the blocked proof off).
    no_triangles: wgpu::TextureView,
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
        let no_triangles = crate::gpu::texture_2d(
            device,
            "no visible triangles",
            1,
            1,
            wgpu::TextureFormat::R32Uint,
            wgpu::TextureUsages::TEXTURE_BINDING,
        )
        .create_view(&Default::default());
        Self {
            no_triangles,
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

    /// Phase 1's group of two-phase BVH rays ([`proof_layout_entries`]) for a frame whose pixels'
    /// visible triangles are `visible` (`R32Uint`, the framebuffer's size: the G-buffer's
    /// [`crate::raster::gbuffer::GBuffer::visible_triangles`]); `None` where the frame has none
    /// (a 1×1 stand-in then turns the blocked proof off).
    pub fn proof_group(
        &self,
        device: &wgpu::Device,
        layout: &wgpu::BindGroupLayout,
        visible: Option<&wgpu::TextureView>,
    ) -> wgpu::BindGroup {
        let visible = visible.unwrap_or(&self.no_triangles);
        let drawn = self.scene.draw_ordered();
        let mut resources = vec![(SOURCE_RAY_CAMERA, self.camera.as_entire_binding())];
        resources.extend(
            self.bvh
                .resources(SOURCE_BVH, &self.scene)
                .into_iter()
                .skip(2),
        );
        resources.push((
            SOURCE_VISIBLE_TRIANGLES,
            wgpu::BindingResource::TextureView(visible),
        ));
        resources.push((SOURCE_DRAWN_TRIANGLES, drawn.triangles.as_entire_binding()));
        crate::bindings::group(device, "bvh ray proofs", layout, &resources)
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
