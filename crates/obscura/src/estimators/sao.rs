//! The Scalable Ambient Obscurance estimator (`shaders/estimators/sao.wgsl`; McGuire, Mara,
//! Luebke 2012, seed 004 §2.2.2): spiral taps over the depth pyramid, the level chosen by the
//! tap's distance.

use crate::settings::{PyramidSettings, SaoSettings};
use std::f32::consts::TAU;

/// The estimator's WGSL (the estimator contract, docs/ARCHITECTURE.md), after the shared
/// screen-space pixel set-up.
pub(crate) const WGSL: &str = concat!(
    include_str!("../../shaders/estimators/screen_space.wgsl"),
    include_str!("../../shaders/estimators/spiral.wgsl"),
    include_str!("../../shaders/estimators/sao.wgsl"),
    include_str!("../../shaders/estimators/no_bent_sample.wgsl"),
    include_str!("../../shaders/estimators/no_depth_interval.wgsl"),
    include_str!("../../shaders/estimators/no_bent_normal.wgsl"),
);
/// Its `override` constants: the taps and the pyramid's levels.
pub(crate) const CONSTANTS: &[&str] = &["SAMPLE_COUNT", "LEVELS"];

/// Taps within this many texels of the pixel read its level (SAO's LOG_MAX_OFFSET 3: 2³).
pub const LEVEL_OFFSET_PX: f32 = 8.0;

/// ε = (0.2 R)²: SAO's code adds ε = 0.01 to v·v against division by zero, a squared length in
/// the metres it was written for; held at its value for our default R = 0.5 but made
/// proportional to R², so that a scene in other units gives the same image (with
/// `AoSettings::scaled`; tests/it/scale_invariance.rs).
pub const EPSILON_PER_RADIUS: f32 = 0.2;

/// GPU mirror of `SaoParams` in the WGSL.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct SaoParams {
    radius: f32,
    radius2: f32,
    scale: f32,
    bias: f32,
    spiral_turns: f32,
    inv_log_factor: f32,
    log_q: f32,
    epsilon: f32,
    pattern: [[f32; 4]; 16],
}

/// The parameter block (group 1) and the values of [`CONSTANTS`] for `settings` over `pyramid`.
pub(crate) fn params(s: &SaoSettings, pyramid: &PyramidSettings) -> (Vec<u8>, Vec<f64>) {
    let pattern = super::bayer_table(TAU).map(|[c, sn, _, _]| [sn.atan2(c), 0.0, 0.0, 0.0]);
    let params = SaoParams {
        radius: s.radius,
        radius2: s.radius * s.radius,
        scale: s.intensity / s.radius.powi(6) * 5.0 / s.samples as f32,
        bias: s.bias,
        spiral_turns: s.spiral_turns,
        inv_log_factor: 1.0 / (pyramid.factor as f32).ln(),
        log_q: LEVEL_OFFSET_PX.ln(),
        epsilon: (EPSILON_PER_RADIUS * s.radius).powi(2),
        pattern,
    };
    (
        bytemuck::bytes_of(&params).to_vec(),
        vec![f64::from(s.samples), f64::from(pyramid.levels)],
    )
}
