//! The SSAO estimator of seed 001 §3.2 (`shaders/estimators/ssao.wgsl`): Alchemy AO (McGuire et
//! al. 2011), N samples on a spiral within the world radius.

use crate::settings::{SdQuery, SsaoSettings};
use std::f32::consts::TAU;

/// The estimator's WGSL (the estimator contract, docs/ARCHITECTURE.md), after the shared
/// screen-space pixel set-up.
pub(crate) const WGSL: &str = concat!(
    include_str!("../../shaders/estimators/screen_space.wgsl"),
    include_str!("../../shaders/estimators/spiral.wgsl"),
    include_str!("../../shaders/estimators/ssao.wgsl"),
    include_str!("../../shaders/estimators/no_bent_sample.wgsl"),
    include_str!("../../shaders/estimators/no_depth_interval.wgsl"),
    include_str!("../../shaders/estimators/no_bent_normal.wgsl"),
);
/// Its `override` constants: the sample count, and whether the map is read where the first
/// surface does not occlude even if no deeper surface can (`stochastic_depth.query =
/// "first-layer"`).
pub(crate) const CONSTANTS: &[&str] = &["SAMPLE_COUNT", "SSAO_LITERAL_QUERY"];

/// The spiral's turns (SAO's, McGuire et al. 2012).
pub const SPIRAL_TURNS: f32 = 7.0;

/// u = 0.1·R, the length of Alchemy's falloff u·t/max(u, t)², whose u is what turns the term
/// (v·n)/(v·v), an inverse length, into a dimensionless obscurance.
pub const FALLOFF_U: f32 = 0.1;

/// ε = (0.02 R)²: Alchemy AO's ε = 10⁻⁴ against division by zero is a squared length in the
/// paper's metres; held at that value for our default R = 0.5 but made proportional to R², so
/// that a scene in other units gives the same image (with `AoSettings::scaled`;
/// tests/it/scale_invariance.rs).
pub const EPSILON_PER_RADIUS: f32 = 0.02;

/// GPU mirror of `SsaoParams` in the WGSL.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct SsaoParams {
    radius: f32,
    radius2: f32,
    scale: f32,
    bias: f32,
    contrast: f32,
    epsilon: f32,
    spiral_turns: f32,
    _pad: f32,
    pattern: [[f32; 4]; 16],
}

/// The parameter block (group 1) and the values of [`CONSTANTS`] for `settings`.
pub(crate) fn params(s: &SsaoSettings, query: SdQuery) -> (Vec<u8>, Vec<f64>) {
    let pattern = super::bayer_table(TAU).map(|[c, sn, _, _]| [sn.atan2(c), 0.0, 0.0, 0.0]);
    let params = SsaoParams {
        radius: s.radius,
        radius2: s.radius * s.radius,
        scale: 2.0 * s.intensity * FALLOFF_U * s.radius / s.samples as f32,
        bias: s.bias,
        contrast: s.contrast,
        epsilon: (EPSILON_PER_RADIUS * s.radius).powi(2),
        spiral_turns: SPIRAL_TURNS,
        _pad: 0.0,
        pattern,
    };
    (
        bytemuck::bytes_of(&params).to_vec(),
        vec![
            f64::from(s.samples),
            f64::from(u8::from(query == SdQuery::FirstLayer)),
        ],
    )
}
