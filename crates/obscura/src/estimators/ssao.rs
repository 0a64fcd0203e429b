//! The SSAO estimator of seed 001 §3.2 (`shaders/estimators/ssao.wgsl`): Alchemy AO (McGuire et
//! al. 2011), N samples on a spiral within the world radius. Its CPU mirror, [`cpu_ssao`], is the
//! same kernel in plain Rust for the tests.

use super::mirror::{per_shaded_pixel, surface_at, MirrorGBuffer, MirrorScreen};
use crate::knob::{Kind, Knob, Widget};
use glam::Vec2;
use serde::{Deserialize, Serialize};
use std::f32::consts::TAU;

/// SSAO parameters (seed 001 §3.2: Alchemy AO, McGuire et al. 2011; 32 samples as seed 001
/// Tab. 1).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SsaoSettings {
    /// Radius R in world units: samples within R count.
    pub radius: f32,
    /// N, samples per pixel, 1 to 32 (one bit each in the two-phase mask).
    pub samples: u32,
    /// σ, the intensity: A = max(0, 1 − 2σ·u/N · Σ)^k with u = 0.1 R (ours: the paper folds u
    /// into σ; written out, σ does not depend on the scene's units).
    pub intensity: f32,
    /// β, the bias per world unit of depth (the paper's 10⁻⁴).
    pub bias: f32,
    /// k, the contrast: the power applied to the final AO.
    pub contrast: f32,
}

impl Default for SsaoSettings {
    fn default() -> Self {
        Self {
            radius: 0.5,
            samples: 32,
            intensity: 1.0,
            bias: 1e-4,
            contrast: 1.0,
        }
    }
}

impl SsaoSettings {
    /// Every field's knob: range, unit, flag, help, widget (crate::knob).
    pub const KNOBS: &'static [Knob] = &[
        Knob::new(
            "ssao.radius",
            "--ssao-radius",
            "SSAO (Alchemy) radius R in world units.",
            Kind::POSITIVE,
        )
        .length()
        .doc("SSAO (Alchemy AO, seed 001's SSAO) radius R: samples within R count")
        .widget(Widget::RADIUS),
        Knob::new(
            "ssao.samples",
            "--ssao-samples",
            "SSAO samples per pixel, N (seed 001 Tab. 1: 32).",
            Kind::int(1, 32),
        )
        .note("one bit per sample")
        .widget(Widget::Range),
        Knob::new(
            "ssao.intensity",
            "--ssao-intensity",
            "SSAO intensity σ.",
            Kind::POSITIVE,
        )
        .doc("σ: A = max(0, 1 − 2σ·u/N · Σ)^k, u = 0.1 R (ours: the paper folds u into σ)"),
        Knob::new(
            "ssao.bias",
            "--ssao-bias",
            "SSAO bias β per world unit of depth.",
            Kind::NON_NEGATIVE,
        )
        .doc("β, bias per world unit of depth (McGuire et al. 2011: 10⁻⁴)"),
        Knob::new(
            "ssao.contrast",
            "--ssao-contrast",
            "SSAO contrast k (power of the final AO).",
            Kind::POSITIVE,
        ),
    ];
}

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

/// Alchemy AO's ε for radius R, (0.02 R)² ([`EPSILON_PER_RADIUS`]).
pub fn epsilon(radius: f32) -> f32 {
    (EPSILON_PER_RADIUS * radius).powi(2)
}

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

/// The estimator as the technique table runs it (`EstimatorCaps::module`).
pub const MODULE: super::EstimatorModule = super::EstimatorModule {
    wgsl: WGSL,
    constants: CONSTANTS,
    knobs: SsaoSettings::KNOBS,
    params: |section, inputs| params(&super::section(section), inputs),
    table: None,
};

/// The parameter block (group 1) and the values of [`CONSTANTS`] for `settings`.
pub(crate) fn params(s: &SsaoSettings, inputs: &super::SourceInputs) -> (Vec<u8>, Vec<f64>) {
    let pattern = super::bayer_table(TAU).map(|[c, sn, _, _]| [sn.atan2(c), 0.0, 0.0, 0.0]);
    let params = SsaoParams {
        radius: s.radius,
        radius2: s.radius * s.radius,
        scale: 2.0 * s.intensity * FALLOFF_U * s.radius / s.samples as f32,
        bias: s.bias,
        contrast: s.contrast,
        epsilon: epsilon(s.radius),
        spiral_turns: SPIRAL_TURNS,
        _pad: 0.0,
        pattern,
    };
    (
        bytemuck::bytes_of(&params).to_vec(),
        vec![
            f64::from(s.samples),
            f64::from(u8::from(inputs.literal_query)),
        ],
    )
}

/// The CPU mirror: SSAO as `ssao.wgsl` states it, as plain Rust per pixel of `g` drawn with
/// `screen` (single-pass schedule). Returns the AO of every visible pixel, row-major, and whether
/// one of its samples lay within 1e-3 px of a pixel edge, where float rounding may snap the GPU
/// and the CPU to different neighbours (the tests allow a difference only there).
pub fn cpu_ssao(
    g: &dyn MirrorGBuffer,
    screen: &dyn MirrorScreen,
    s: &SsaoSettings,
) -> (Vec<f32>, Vec<bool>) {
    let n_samples = s.samples as f32;
    per_shaded_pixel(g, screen, s.radius, |x, y, p| {
        let (c, sn, _) = super::bayer_pattern(x, y, TAU);
        let rotation = sn.atan2(c);
        let (mut sum, mut edge) = (0.0f32, false);
        for i in 0..s.samples {
            let alpha = (i as f32 + 0.5) / n_samples;
            let angle = alpha * TAU * SPIRAL_TURNS + rotation;
            let px = p.centre + Vec2::new(angle.cos(), -angle.sin()) * (alpha * p.radius_px);
            let (surface, e) = surface_at(g, screen, p, px, false);
            edge |= e;
            let Some(q) = surface else { continue };
            let v = q - p.pos;
            let vv = v.dot(v);
            if vv < s.radius * s.radius {
                sum += (v.dot(p.n) + p.pos.z * s.bias).max(0.0) / (vv + epsilon(s.radius));
            }
        }
        let ao = (1.0 - 2.0 * s.intensity * FALLOFF_U * s.radius / n_samples * sum)
            .max(0.0)
            .powf(s.contrast);
        (ao, edge)
    })
}
