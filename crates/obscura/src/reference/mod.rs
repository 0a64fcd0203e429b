//! References the GPU is held to. [`cpu_vao`] mirrors the VAO kernel on the CPU (same G-buffer,
//! same arithmetic) so tests can check the GPU pass pixel by pixel; it re-exports the mirror that
//! lives with its estimator, as every estimator's does (`estimators::<name>::cpu_<name>`).

pub mod cache;
pub mod cpu_blur;
pub mod cpu_vao;
pub mod gpu;
pub mod ground_truth;
