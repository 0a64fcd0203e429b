//! Filters applied to raw AO: the tail of the pass list ([`crate::AmbientOcclusion`]).

pub mod atrous;
pub mod bilateral;
pub mod half_resolution;
pub mod ray_budget;
pub mod temporal;

use crate::frame::FrameInputs;
use crate::gpu::PassProfiler;

/// A pass from one AO image to the next (`R32Float`, visible size), with the frame's inputs at
/// hand (depth for edge-aware weights, the screen geometry).
pub trait AoFilter {
    /// Record the filter's passes from `input` to `output` (both `R32Float`, visible size), timed
    /// by `profiler` when given.
    fn encode(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameInputs,
        input: &wgpu::TextureView,
        output: &wgpu::TextureView,
        profiler: Option<&mut PassProfiler>,
    );

    /// The camera of the coming frame (`AmbientOcclusion::set_camera`), for filters that
    /// reproject; the others ignore it.
    fn set_camera(&self, _queue: &wgpu::Queue, _view: &crate::view::FrameView) {}

    /// The filter as temporal accumulation, if it is that (for its history and pattern offset).
    fn as_temporal(&self) -> Option<&temporal::TemporalAccumulation> {
        None
    }
}
