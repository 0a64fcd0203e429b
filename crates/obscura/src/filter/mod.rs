//! Filters applied to raw AO: the tail of the pass list ([`crate::AmbientOcclusion`]).

pub mod atrous;
pub mod bilateral;
pub mod half_resolution;
pub mod ray_budget;
mod shared_cell;
pub mod temporal;

use crate::frame::FrameInputs;
use crate::gpu::PassProfiler;

/// What a filter reads and writes.
#[derive(Clone, Copy)]
pub struct FilterImages<'a> {
    /// The previous image (`R32Float`, visible size).
    pub input: &'a wgpu::TextureView,
    /// Its own (`R32Float`, visible size).
    pub output: &'a wgpu::TextureView,
    /// Temporal accumulation's history as this frame wrote it (`Rg32Uint`,
    /// [`temporal::HistoryTexel`]), for the filters after it.
    pub history: Option<&'a wgpu::TextureView>,
}

/// A pass from one AO image to the next (`R32Float`, visible size), with the frame's inputs at
/// hand (depth for edge-aware weights, the screen geometry). Send and Sync where wgpu's handles
/// are (not on the web), so that an `AmbientOcclusion` can live in an engine's render world.
pub trait AoFilter: wgpu::WasmNotSendSync {
    /// Record the filter's passes from `images.input` to `images.output`, timed by `profiler`
    /// when given.
    fn encode(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameInputs,
        images: FilterImages,
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
