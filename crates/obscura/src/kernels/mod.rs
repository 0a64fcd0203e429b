//! AO kernels: one module per technique, each a compute pass from the frame inputs (linear depth,
//! view-space normals, screen geometry) to a raw AO image of the visible size (R32Float,
//! 1 = unoccluded). Filtering happens after, in [`crate::filter`].

pub mod svao;
pub mod vao;

use crate::gpu::PassProfiler;
use crate::view::ScreenGeometry;

/// What every kernel reads. Textures cover the whole guard-banded framebuffer.
pub struct FrameInputs<'a> {
    /// Linear view depth (`R32Float`, world units, 0 = background).
    pub depth: &'a wgpu::TextureView,
    /// View-space unit normals facing the camera (any float format; xyz used).
    pub normals: &'a wgpu::TextureView,
    /// The second depth layer from depth peeling (`R32Float`, linear, 0 = none), for `vao-dual`.
    pub second_layer: Option<&'a wgpu::TextureView>,
    pub screen: ScreenGeometry,
}

/// A compute kernel that turns [`FrameInputs`] into raw AO.
pub trait AoKernel {
    /// The name its timings are reported under.
    fn pass_name(&self) -> &'static str;

    /// The camera of the coming frame, for kernels that trace rays or rasterise the scene.
    fn set_camera(&self, _queue: &wgpu::Queue, _view: &crate::view::FrameView) {}

    /// For kernels that read a stochastic depth map: the map (its last frame can be read back).
    fn stochastic_depth(&self) -> Option<&crate::raster::stochastic_depth::StochasticDepthMap> {
        None
    }

    /// For SD-SVAO: phase 1's SD-request mask (one u32 per framebuffer pixel, non-zero where the
    /// stochastic depth map was asked for).
    fn sd_requests(&self) -> Option<&wgpu::Buffer> {
        None
    }

    /// For kernels that trace rays: a `u32` buffer counting the rays of the last frame whose BVH
    /// traversal overflowed its stack (their results may be incomplete).
    fn stack_overflows(&self) -> Option<&wgpu::Buffer> {
        None
    }

    /// For two-phase kernels: phase 1's per-pixel records (16 bytes each, the sample bit mask
    /// first), to show which samples needed rays.
    fn phase1_records(&self) -> Option<&wgpu::Buffer> {
        None
    }

    /// Record the kernel. `output` is `R32Float` storage of the visible size.
    fn encode(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        inputs: &FrameInputs,
        output: &wgpu::TextureView,
        profiler: Option<&mut PassProfiler>,
    );
}

/// Workgroups covering `width`×`height` with 32×8 threads. Measured on an H200 (BENCHMARKS.md):
/// 8×8 groups cost 0.025 ms at 1080p even for a pass that only reads and writes one texel per
/// pixel, 32×8 groups 0.013 ms (fewer workgroup launches).
pub(crate) fn workgroups_32x8(width: u32, height: u32) -> (u32, u32, u32) {
    (width.div_ceil(32), height.div_ceil(8), 1)
}
