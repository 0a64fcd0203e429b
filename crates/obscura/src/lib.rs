//! obscura: screen-space ambient occlusion that keeps the geometry a depth buffer hides.
//!
//! The pieces, in the order a frame uses them (DESIGN.md "Data flow"):
//! [`scene`] (loaders, procedural scenes, cameras) → [`raster`] (G-buffer with a guard band) →
//! [`kernels`] (AO compute passes; [`hidden`] depth sources) → [`filter`] (bilateral blur).
//! [`AmbientOcclusion`] is the piece an engine embeds; [`Renderer`] renders our own scenes.
//!
//! The evidence: [`bvh`] (CPU SAH BVH), [`reference`] (ray-traced ground truth and CPU mirrors of
//! the GPU passes), [`metrics`] (MSE, MAE, PSNR, SSIM, halo metric) and [`report`] (the
//! `compare` report: JSON, Markdown, HTML with heat maps).
//!
//! Conventions: right-handed view space looking down −Z, linear depth = −z in world units,
//! AO = 1 unoccluded / 0 fully occluded, exponent applied last.

pub mod bvh;
pub mod filter;
pub mod gpu;
pub mod hidden;
pub mod kernels;
pub mod metrics;
pub mod output;
pub mod pipeline;
pub mod raster;
pub mod reference;
pub mod report;
pub mod scene;
pub mod settings;
pub(crate) mod shaders;
pub mod technique;
pub mod view;

pub use gpu::{Gpu, GpuError, GpuOptions, PassProfiler};
pub use pipeline::{renderer::Renderer, AmbientOcclusion};
pub use settings::{
    AoSettings, BlurSettings, Normalization, SettingsError, Technique, VaoSettings,
};
pub use view::{default_guard_band, near_plane, FrameView, ScreenGeometry};

use std::path::PathBuf;

/// Everything that can go wrong, each with a message that names the input and the fix.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    #[error(transparent)]
    Gpu(#[from] GpuError),
    #[error(transparent)]
    Settings(#[from] SettingsError),
    #[error("{0}")]
    Input(String),
    #[error("could not write '{path}': {message}")]
    Output { path: PathBuf, message: String },
}
