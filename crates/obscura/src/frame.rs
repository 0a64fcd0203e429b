//! What every AO pass reads: the frame's first depth layer and normals (guard-banded framebuffer)
//! and its screen geometry, bound as group 0 (`shaders/frame/frame.wgsl`) with the AO output.

use crate::bindings::{self, FRAME_AO_OUT, FRAME_DEPTH, FRAME_NORMALS, FRAME_VIEW};
use crate::view::ScreenGeometry;

/// The frame inputs of one encode. Textures cover the whole guard-banded framebuffer.
pub struct FrameInputs<'a> {
    /// Linear view depth (`R32Float`, world units, 0 = background).
    pub depth: &'a wgpu::TextureView,
    /// View-space unit normals facing the camera (any float format; xyz used).
    pub normals: &'a wgpu::TextureView,
    /// The second depth layer from depth peeling (`R32Float`, linear, 0 = none), for `vao-dual`.
    pub second_layer: Option<&'a wgpu::TextureView>,
    pub screen: ScreenGeometry,
    /// The uniform of `screen` (`View` in `shaders/common/view.wgsl`).
    pub view: &'a wgpu::Buffer,
}

impl FrameInputs<'_> {
    /// Group 0 of an AO pass writing `output` (`R32Float` storage of the visible size).
    pub(crate) fn group(
        &self,
        device: &wgpu::Device,
        layout: &wgpu::BindGroupLayout,
        output: &wgpu::TextureView,
    ) -> wgpu::BindGroup {
        bindings::group(
            device,
            "frame",
            layout,
            &[
                (FRAME_VIEW, self.view.as_entire_binding()),
                (FRAME_DEPTH, wgpu::BindingResource::TextureView(self.depth)),
                (
                    FRAME_NORMALS,
                    wgpu::BindingResource::TextureView(self.normals),
                ),
                (FRAME_AO_OUT, wgpu::BindingResource::TextureView(output)),
            ],
        )
    }
}

/// Workgroups covering `width`×`height` with 32×8 threads. Measured on an H200 (BENCHMARKS.md):
/// 8×8 groups cost 0.025 ms at 1080p even for a pass that only reads and writes one texel per
/// pixel, 32×8 groups 0.013 ms (fewer workgroup launches).
pub(crate) fn workgroups_32x8(width: u32, height: u32) -> (u32, u32, u32) {
    (width.div_ceil(32), height.div_ceil(8), 1)
}
