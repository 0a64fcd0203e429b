//! The Pyramid HBAO estimator (`shaders/estimators/pyramid_hbao.wgsl`, seed 004 §3): directions
//! walked over the levels of the depth pyramid, each direction's largest weighted contribution.
//! Its per-pixel offsets are here so the tests use the same numbers.

use crate::settings::{PyramidHbaoSettings, PyramidSettings};
use std::f32::consts::TAU;

/// The estimator's WGSL (the estimator contract, docs/ARCHITECTURE.md), after the shared
/// screen-space pixel set-up.
pub(crate) const WGSL: &str = concat!(
    include_str!("../../shaders/estimators/screen_space.wgsl"),
    include_str!("../../shaders/estimators/pyramid_hbao.wgsl")
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

/// Direction `d` of `directions` for pixel (x, y): its screen unit vector (framebuffer y down) at
/// angle 2π(d + u)/D, u = fract(u₀ + 0.618…·d), and its start offset o = fract(o₀ + 0.754…·d),
/// (u₀, o₀) the pixel's [`pixel_offsets`] (the golden-ratio sequences of the WGSL's top comment).
pub fn direction(x: u32, y: u32, d: u32, directions: u32) -> (f32, f32, f32) {
    let (u0, o0) = pixel_offsets(x, y);
    let df = d as f32;
    let u = (u0 + 0.618_034 * df).fract();
    let o = (o0 + 0.754_877_7 * df).fract();
    let angle = TAU * (df + u) / directions as f32;
    (angle.cos(), -angle.sin(), o)
}

/// Level `l`'s step in pixels, K^l, and where it starts, S·(K^l − 1)/(K − 1) pixels out.
pub fn level_step_and_start(level: u32, factor: u32, steps: u32) -> (f32, f32) {
    let k = factor as f32;
    let size = k.powi(level as i32);
    (size, steps as f32 * (size - 1.0) / (k - 1.0))
}

/// GPU mirror of `PyramidHbaoParams` in the WGSL.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct PyramidHbaoParams {
    radius: f32,
    inv_radius: f32,
    exponent: f32,
    _pad0: f32,
    directions: u32,
    _pad: [u32; 3],
    direction_table: [[f32; 4]; 512],
    level_table: [[f32; 4]; 8],
}

/// The parameter block (group 1) and the values of [`CONSTANTS`] for `settings` over `pyramid`.
pub(crate) fn params(s: &PyramidHbaoSettings, pyramid: &PyramidSettings) -> (Vec<u8>, Vec<f64>) {
    let mut direction_table = [[0.0; 4]; 512];
    for pattern in 0..16u32 {
        for d in 0..s.directions {
            let (x, y, o) = direction(pattern % 4, pattern / 4, d, s.directions);
            direction_table[(32 * pattern + d) as usize] = [x, y, o, 0.0];
        }
    }
    let mut level_table = [[0.0; 4]; 8];
    for (l, row) in level_table
        .iter_mut()
        .enumerate()
        .take(pyramid.levels as usize)
    {
        let (step, start) = level_step_and_start(l as u32, pyramid.factor, s.steps);
        *row = [step, start, 0.0, 0.0];
    }
    let params = PyramidHbaoParams {
        radius: s.radius,
        inv_radius: 1.0 / s.radius,
        exponent: s.exponent,
        _pad0: 0.0,
        directions: s.directions,
        _pad: [0; 3],
        direction_table,
        level_table,
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
