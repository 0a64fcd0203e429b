//! Rasterisation passes: the scene on the GPU and the G-buffer (with depth peeling). The stochastic
//! depth map, also rasterised, is a hidden-depth source: [`crate::sources::stochastic_depth`].

pub mod chunks;
pub mod gbuffer;
pub mod gpu_scene;
pub(crate) mod occlusion_pyramid;
pub(crate) mod triangle_cull;
