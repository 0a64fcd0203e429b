//! The classic HBAO estimator (`shaders/estimators/hbao.wgsl`): horizon-based AO as seed 001 §3.2
//! Algorithm 2 and seed 004 §2.2.1 state it. Its direction table and per-pixel pattern are here so
//! the CPU mirror in the tests uses the same numbers.

use crate::settings::{HbaoSettings, HBAO_MAX_DIRECTIONS as MAX_DIRECTIONS};
use std::f32::consts::TAU;

/// The estimator's WGSL (the estimator contract, docs/ARCHITECTURE.md), after the shared
/// screen-space pixel set-up.
pub(crate) const WGSL: &str = concat!(
    include_str!("../../shaders/estimators/screen_space.wgsl"),
    include_str!("../../shaders/estimators/hbao.wgsl"),
    include_str!("../../shaders/estimators/no_bent_sample.wgsl"),
    include_str!("../../shaders/estimators/no_depth_interval.wgsl"),
    include_str!("../../shaders/estimators/no_bent_normal.wgsl"),
);
/// Its `override` constants: the sample count, directions × steps, and the steps.
pub(crate) const CONSTANTS: &[&str] = &["SAMPLE_COUNT", "STEPS"];

/// Pixel (x, y) of the visible image: (cos, sin) of its direction rotation, 2π·B/16/D with B the
/// Bayer value of (x % 4, y % 4), and its start jitter in [0, 1) ([`super::bayer_pattern`]).
pub fn pixel_pattern(x: u32, y: u32, directions: u32) -> (f32, f32, f32) {
    super::bayer_pattern(x, y, TAU / directions as f32)
}

/// Direction `d` of `directions`, unrotated: the unit vector at angle 2π·d/directions (view-space
/// x right, y up).
pub fn direction(d: u32, directions: u32) -> (f32, f32) {
    let angle = TAU * d as f32 / directions as f32;
    (angle.cos(), angle.sin())
}

/// GPU mirror of `HbaoParams` in the WGSL.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct HbaoParams {
    radius: f32,
    inv_radius: f32,
    cos_bias: f32,
    sin_bias: f32,
    exponent: f32,
    directions: u32,
    steps: u32,
    _pad: u32,
    pattern: [[f32; 4]; 16],
    direction_table: [[f32; 4]; MAX_DIRECTIONS as usize],
}

/// The parameter block (group 1) and the values of [`CONSTANTS`] for `settings`.
pub(crate) fn params(s: &HbaoSettings) -> (Vec<u8>, Vec<f64>) {
    let mut direction_table = [[0.0; 4]; MAX_DIRECTIONS as usize];
    for (d, k) in direction_table
        .iter_mut()
        .enumerate()
        .take(s.directions as usize)
    {
        let (c, sn) = direction(d as u32, s.directions);
        *k = [c, sn, 0.0, 0.0];
    }
    let params = HbaoParams {
        radius: s.radius,
        inv_radius: 1.0 / s.radius,
        cos_bias: s.angle_bias.cos(),
        sin_bias: s.angle_bias.sin(),
        exponent: s.exponent,
        directions: s.directions,
        steps: s.steps,
        _pad: 0,
        pattern: super::bayer_table(TAU / s.directions as f32),
        direction_table,
    };
    (
        bytemuck::bytes_of(&params).to_vec(),
        vec![f64::from(s.directions * s.steps), f64::from(s.steps)],
    )
}
