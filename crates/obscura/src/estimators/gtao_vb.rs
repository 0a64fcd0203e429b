//! The GTAO visibility-bitmask estimator (`shaders/estimators/gtao_vb.wgsl`, seed 003). Its sample
//! table and per-pixel pattern are here so the CPU mirror in the tests uses the same numbers.

use crate::settings::{GtaoVbSettings, SdQuery, SectorActivation, StochasticDepthSettings};
use std::f32::consts::PI;

/// The estimator's WGSL (the estimator contract, docs/ARCHITECTURE.md), after the shared
/// screen-space pixel set-up.
pub(crate) const WGSL: &str = concat!(
    include_str!("../../shaders/estimators/screen_space.wgsl"),
    include_str!("../../shaders/estimators/slice_visibility.wgsl"),
    include_str!("../../shaders/estimators/gtao_vb.wgsl"),
    include_str!("../../shaders/estimators/no_bent_sample.wgsl"),
    include_str!("../../shaders/estimators/no_depth_interval.wgsl"),
);
/// Its `override` constants: the sample count, slices × 2 × steps; whether sectors are
/// cosine-weighted (1) or counted alike (0, seed 003); whether hidden depth is skipped where
/// no deeper surface can mark a free sector ([`exact_query`]); and the steps per slice side.
pub(crate) const CONSTANTS: &[&str] = &["SAMPLE_COUNT", "COSINE_WEIGHTED", "EXACT_QUERY", "STEPS"];

/// Whether a sample skips the hidden depth where every sector a deeper surface could mark is
/// marked already (gtao_vb.wgsl): with the default query, and only without compensation, which
/// widens a stochastic sample's run beyond the sectors the test counts on.
pub fn exact_query(sd: &StochasticDepthSettings) -> bool {
    sd.query != SdQuery::FirstLayer && sd.compensation == 1.0
}

/// Pixel (x, y) of the visible image: (cos, sin) of its slice rotation, π·B/16/slices with B the
/// Bayer value of (x % 4, y % 4), and its step jitter in [0, 1) ([`super::bayer_pattern`]).
pub fn pixel_pattern(x: u32, y: u32, slices: u32) -> (f32, f32, f32) {
    super::bayer_pattern(x, y, PI / slices as f32)
}

/// Sample `i`: the unrotated slice direction (angle π·slice/slices), the side (±1) and the step.
pub fn sample(i: u32, slices: u32, steps: u32) -> (f32, f32, f32, u32) {
    let slice = i / (2 * steps);
    let side = if (i / steps).is_multiple_of(2) {
        1.0
    } else {
        -1.0
    };
    let angle = PI * slice as f32 / slices as f32;
    (angle.cos(), angle.sin(), side, i % steps)
}

/// GPU mirror of `GtaoVbParams` in the WGSL.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct GtaoVbParams {
    radius: f32,
    thickness: f32,
    exponent: f32,
    activation: u32,
    slices: u32,
    steps: u32,
    _pad: [u32; 2],
    pattern: [[f32; 4]; 16],
    samples: [[f32; 4]; 32],
}

/// The parameter block (group 1) and the values of [`CONSTANTS`] for `settings`.
pub(crate) fn params(s: &GtaoVbSettings, sd: &StochasticDepthSettings) -> (Vec<u8>, Vec<f64>) {
    let pattern = super::bayer_table(PI / s.slices as f32);
    let count = s.slices * 2 * s.steps;
    let mut samples = [[0.0; 4]; 32];
    for (i, k) in samples.iter_mut().enumerate().take(count as usize) {
        let (c, sn, side, step) = sample(i as u32, s.slices, s.steps);
        *k = [c, sn, side, step as f32];
    }
    let params = GtaoVbParams {
        radius: s.radius,
        thickness: s.thickness,
        exponent: s.exponent,
        activation: match s.activation {
            SectorActivation::Ceil => 0,
            SectorActivation::Round => 1,
            SectorActivation::Floor => 2,
        },
        slices: s.slices,
        steps: s.steps,
        _pad: [0; 2],
        pattern,
        samples,
    };
    (
        bytemuck::bytes_of(&params).to_vec(),
        vec![
            f64::from(count),
            f64::from(u8::from(s.cosine_weighted)),
            f64::from(u8::from(exact_query(sd))),
            f64::from(s.steps),
        ],
    )
}
