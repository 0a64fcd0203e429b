//! obscura: screen-space ambient occlusion that keeps the geometry a depth buffer hides.
//!
//! The pieces, in the order a frame uses them (docs/ARCHITECTURE.md):
//! [`scene`] (loaders, procedural scenes, cameras) → [`raster`] (G-buffer with a guard band) →
//! the AO passes of a [`technique`] row: its hidden-depth [`sources`] prepare, its [`schedules`]
//! run its [`estimators`] → [`filter`] (bilateral blur). [`AmbientOcclusion`] is the piece an
//! engine embeds; [`Renderer`] renders our own scenes.
//!
//! The evidence: [`bvh`] (CPU SAH BVH), [`reference`](mod@reference) (ray-traced ground truth
//! and CPU mirrors of the GPU passes), [`metrics`] (MSE, MAE, PSNR, SSIM, halo metric) and
//! [`report`] (the `compare` report: JSON, Markdown, HTML with heat maps).
//!
//! Conventions: right-handed view space looking down −Z, linear depth = −z in world units,
//! AO = 1 unoccluded / 0 fully occluded, exponent applied last. The defaults assume metres; for a
//! scene in other units, [`AoSettings::scaled`] converts every setting in world units, after
//! which every technique gives the same image as in metres (tests/it/scale_invariance.rs).

#![warn(missing_docs)]

pub mod bindings;
pub mod bvh;
// Not on the web: its executors run shards on threads (one per GPU) and write files.
#[cfg(not(target_arch = "wasm32"))]
pub mod dataset;
pub mod engine_geometry;
pub mod engine_input;
pub mod error;
pub mod estimators;
pub mod filter;
pub mod frame;
pub mod gpu;
pub mod hash;
pub mod knob;
pub mod metrics;
pub mod output;
pub mod pipeline;
pub mod raster;
pub mod reference;
pub mod report;
pub mod scene;
pub mod schedules;
pub mod settings;
pub(crate) mod shaders;
pub mod sources;
pub mod technique;
pub mod view;

pub use engine_geometry::{AlphaMask, EngineGeometry, EngineMesh, IndexData, VertexAttribute};
pub use engine_input::{EngineFrame, EngineInput, EngineNormals, NormalEncoding};
pub use error::{Error, SettingsError};
pub use filter::ray_budget::{RayBudgetReport, TimeBudget};
pub use gpu::{Gpu, GpuError, GpuOptions, PassProfiler};
pub use pipeline::{renderer::Renderer, AmbientOcclusion, FrameTextures};
pub use settings::{AoSettings, BlurSettings, Normalization, Preset, Technique, VaoSettings};
pub use sources::SceneResources;
pub use view::{default_guard_band, guard_banded_fov_y, near_plane, FrameView, ScreenGeometry};
