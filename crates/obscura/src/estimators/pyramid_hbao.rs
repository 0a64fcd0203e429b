//! The Pyramid HBAO estimator (`shaders/estimators/pyramid_hbao.wgsl`, seed 004 §3): directions
//! walked over the levels of the depth pyramid, each direction's largest weighted contribution.
//! Its per-pixel offsets are here so the tests use the same numbers.

use crate::settings::{PyramidHbaoSettings, PyramidSettings};

/// The estimator's WGSL (the estimator contract, docs/ARCHITECTURE.md), after the shared
/// screen-space pixel set-up.
pub(crate) const WGSL: &str = concat!(
    include_str!("../../shaders/estimators/screen_space.wgsl"),
    include_str!("../../shaders/estimators/pyramid_hbao.wgsl"),
    include_str!("../../shaders/estimators/no_bent_sample.wgsl"),
    include_str!("../../shaders/estimators/no_depth_interval.wgsl"),
    include_str!("../../shaders/estimators/no_bent_normal.wgsl"),
);
/// Its `override` constants: the sample count (directions × levels × steps), levels, steps.
pub(crate) const CONSTANTS: &[&str] = &["SAMPLE_COUNT", "LEVELS", "STEPS"];

/// Pixel (x, y) of the visible image: its direction offset u and start offset o in [0, 1), the
/// 4×4 Bayer value and its transpose ([`super::bayer_pattern`] with period 1).
pub fn pixel_offsets(x: u32, y: u32) -> (f32, f32) {
    let (i, j) = ((x % 4) as usize, (y % 4) as usize);
    (
        super::vao::BAYER_4X4[i + 4 * j] as f32 / 16.0,
        (super::vao::BAYER_4X4[j + 4 * i] as f32 + 0.5) / 16.0,
    )
}

/// GPU mirror of `PyramidHbaoParams` in the WGSL.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct PyramidHbaoParams {
    radius: f32,
    inv_radius: f32,
    exponent: f32,
    factor: f32,
    directions: u32,
    _pad: [u32; 3],
    pattern: [[f32; 4]; 16],
}

/// The parameter block (group 1) and the values of [`CONSTANTS`] for `settings` over `pyramid`.
pub(crate) fn params(s: &PyramidHbaoSettings, pyramid: &PyramidSettings) -> (Vec<u8>, Vec<f64>) {
    let pattern = std::array::from_fn(|i| {
        let (u, o) = pixel_offsets(i as u32 % 4, i as u32 / 4);
        [u, o, 0.0, 0.0]
    });
    let params = PyramidHbaoParams {
        radius: s.radius,
        inv_radius: 1.0 / s.radius,
        exponent: s.exponent,
        factor: pyramid.factor as f32,
        directions: s.directions,
        _pad: [0; 3],
        pattern,
    };
    (
        bytemuck::bytes_of(&params).to_vec(),
        vec![
            f64::from(s.directions * pyramid.levels * s.steps),
            f64::from(pyramid.levels),
            f64::from(s.steps),
        ],
    )
}
