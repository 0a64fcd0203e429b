//! The VAO kernel of `shaders/estimators/vao.wgsl` written again, plainly, on the CPU: a test oracle
//! for the GPU pass on a read-back G-buffer (seed 000 §3.1–3.5). The mirror lives with its
//! estimator (`estimators::vao`); this path keeps the names the reference and the tests have used.

pub use crate::estimators::vao::{cpu_vao, cpu_vao_turned, cpu_vao_with, CpuVao};
// The read-back G-buffer the CPU mirrors take lives in `raster` (re-exported at its old path).
pub use crate::raster::GBufferImage;
