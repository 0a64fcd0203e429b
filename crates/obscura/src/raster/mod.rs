//! Rasterisation passes: the scene on the GPU, the G-buffer and the stochastic depth map.

pub mod gbuffer;
pub mod gpu_scene;
mod sd_reset;
mod sd_unpack;
pub mod stochastic_depth;
