//! Rasterisation passes: the scene on the GPU and the G-buffer.

pub mod gbuffer;
pub mod gpu_scene;
