//! References the GPU is held to. [`cpu_vao`] mirrors the VAO kernel on the CPU (same G-buffer,
//! same arithmetic) so tests can check the GPU pass pixel by pixel; it re-exports the mirror that
//! lives with its estimator, as every estimator's does (`estimators::<name>::cpu_<name>`).

pub mod cache;
pub mod cpu_blur;
pub mod cpu_vao;
pub mod gpu;
pub mod ground_truth;

use crate::gpu::Gpu;
use crate::raster::GBufferImage;
use crate::settings::BlurSettings;
use crate::view::FrameView;
use ground_truth::ReferenceModel;

/// The reference as reports compare it: the vao models keep the kernel's per-pixel rotation
/// noise, so they go through the techniques' bilateral blur (`blur`, on the same G-buffer) so
/// that only hidden geometry differs; the hemisphere model as traced. The CLI's `compare` and the
/// Python package's `compare` both use it.
pub fn as_compared(
    image: Vec<f32>,
    model: ReferenceModel,
    blur: &BlurSettings,
    gbuffer: &GBufferImage,
    view: &FrameView,
) -> Vec<f32> {
    if model != ReferenceModel::Hemisphere && blur.enabled {
        cpu_blur::cpu_blur(&image, gbuffer, &view.screen(), blur)
    } else {
        image
    }
}

/// Whether the reference is traced on the CPU rather than on `gpu` by default: on a software
/// (CPU) adapter such as lavapipe, where the CPU tracer is several times faster (measured in
/// issue 14: lavapipe traced Sponza in 52.7 s, the CPU tracer in 6.1 s on the same two cores,
/// same image).
pub fn cpu_tracer_by_default(gpu: &Gpu) -> bool {
    gpu.summary.device_type == "Cpu"
}
