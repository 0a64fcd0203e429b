//! The Scalable Ambient Obscurance estimator (`shaders/estimators/sao.wgsl`; McGuire, Mara,
//! Luebke 2012, seed 004 §2.2.2): spiral taps over the depth pyramid, the level chosen by the
//! tap's distance. Its CPU mirror, [`cpu_sao`], is the same kernel in plain Rust for the tests.

use super::mirror::{per_shaded_pixel, Levels};
use crate::knob::{Kind, Knob, Widget};
use glam::Vec2;
use serde::{Deserialize, Serialize};
use std::f32::consts::TAU;

/// Scalable Ambient Obscurance parameters (McGuire et al. 2012; defaults of its published code:
/// 11 taps on 7 spiral turns, bias 0.01, intensity 1 at its example radius of 1 m).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SaoSettings {
    /// Radius R in world units: taps up to R on screen, falloff (R² − d²)³.
    pub radius: f32,
    /// N, taps per pixel, 1 to 64.
    pub samples: u32,
    /// τ, turns of the tap spiral.
    pub spiral_turns: f32,
    /// β, world units a tap must rise above the tangent plane before it occludes.
    pub bias: f32,
    /// σ, the dimensionless intensity: A = max(0, 1 − σR/R⁶ · 5/N · Σ). SAO's shipped
    /// normalisation is intensity/R⁶ · 5/N, whose sum has the dimension of an inverse length:
    /// its `intensity` is a length, σR here, so that the obscurance follows the radius (and
    /// its on-screen cap) instead of growing as 1/R (issue 62). At SAO's example radius, 1 m,
    /// σ = 1 is its shipped intensity 1.
    pub intensity: f32,
}

impl Default for SaoSettings {
    fn default() -> Self {
        Self {
            radius: 0.5,
            samples: 11,
            spiral_turns: 7.0,
            bias: 0.01,
            intensity: 1.0,
        }
    }
}

impl SaoSettings {
    /// Every field's knob: range, unit, flag, help, widget (crate::knob).
    pub const KNOBS: &'static [Knob] = &[
        Knob::new("sao.radius", "--sao-radius", "SAO radius R in world units.", Kind::POSITIVE)
            .length()
            .doc("SAO radius R (taps up to R on screen, falloff (R² − d²)³)")
            .widget(Widget::RADIUS),
        Knob::new("sao.samples", "--sao-samples", "SAO spiral taps per pixel, N (SAO's code: 11).", Kind::int(1, 64))
            .widget(Widget::Range),
        Knob::new(
            "sao.spiral_turns",
            "--sao-spiral-turns",
            "SAO turns of the tap spiral, τ (SAO's code: 7).",
            Kind::POSITIVE,
        )
        .aliases(&["--sao-turns"]),
        Knob::new(
            "sao.bias",
            "--sao-bias",
            "SAO bias β: how far a tap must rise above the tangent plane to occlude.",
            Kind::NON_NEGATIVE,
        )
        .length(),
        Knob::new(
            "sao.intensity",
            "--sao-intensity",
            "SAO intensity σ (scale of the obscurance, dimensionless: SAO's intensity over R).",
            Kind::POSITIVE,
        )
        .doc(
            "σ, scale of the summed obscurance: A = 1 − σR/R⁶ · 5/N · Σ (SAO's shipped \
             normalisation intensity/R⁶ · 5/N with its intensity, a length, written σR so that \
             the obscurance follows the radius and its cap; σ = 1 is SAO's intensity 1 at its \
             example radius 1 m)",
        ),
    ];
}

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

/// ε = (0.2 R)²: SAO's code adds ε = 0.01 to v·v against division by zero ("large epsilon to
/// avoid overdarkening within cracks"), a squared length in metres; held at that value for our
/// default R = 0.5 but made proportional to R², so that a scene in other units gives the same
/// image (tests/it/scale_invariance.rs) and a radius capped on screen scales it with the rest.
/// (Measured, issue 62: anchoring it at SAO's example radius instead, (0.1 R)², darkened every
/// view at R = 1: Sponza's bias −0.076 → −0.132; docs/lab/2026-12-06-rows-against-truth.md.)
pub const EPSILON_PER_RADIUS: f32 = 0.2;

/// SAO's ε for radius R, (0.2 R)² ([`EPSILON_PER_RADIUS`]).
pub fn epsilon(radius: f32) -> f32 {
    (EPSILON_PER_RADIUS * radius).powi(2)
}

/// The factor of the summed terms for radius R: σR/R⁶ · 5/N = σ · 5/(N R⁵) (SAO's
/// intensity/R⁶ · 5/N with its intensity σR), so that A = max(0, 1 − factor · Σ).
pub fn obscurance_scale(s: &SaoSettings, radius: f32) -> f32 {
    s.intensity * 5.0 / (s.samples as f32 * radius.powi(5))
}

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

/// The estimator as the technique table runs it (`EstimatorCaps::module`).
pub const MODULE: super::EstimatorModule = super::EstimatorModule {
    wgsl: WGSL,
    constants: CONSTANTS,
    knobs: SaoSettings::KNOBS,
    params: |section, inputs| params(&super::section(section), inputs),
    table: None,
};

/// The parameter block (group 1) and the values of [`CONSTANTS`] for `settings` over `pyramid`.
pub(crate) fn params(s: &SaoSettings, inputs: &super::SourceInputs) -> (Vec<u8>, Vec<f64>) {
    let pattern = super::bayer_table(TAU).map(|[c, sn, _, _]| [sn.atan2(c), 0.0, 0.0, 0.0]);
    let params = SaoParams {
        radius: s.radius,
        radius2: s.radius * s.radius,
        scale: obscurance_scale(s, s.radius),
        bias: s.bias,
        spiral_turns: s.spiral_turns,
        inv_log_factor: 1.0 / (inputs.pyramid_factor as f32).ln(),
        log_q: LEVEL_OFFSET_PX.ln(),
        epsilon: epsilon(s.radius),
        pattern,
    };
    (
        bytemuck::bytes_of(&params).to_vec(),
        vec![f64::from(s.samples), f64::from(inputs.pyramid_levels)],
    )
}

/// The CPU mirror: SAO as `sao.wgsl` states it, as plain Rust per pixel, over `l` (the G-buffer
/// and the pyramid's `levels` levels as read back). Returns the AO of every visible pixel,
/// row-major, and whether one of its taps lay within 1e-3 texel of a texel edge or on the boundary
/// between two levels, where float rounding may make the GPU and the CPU read different texels.
pub fn cpu_sao(l: &Levels, s: &SaoSettings, levels: u32) -> (Vec<f32>, Vec<bool>) {
    let n = s.samples as f32;
    per_shaded_pixel(l.g, l.screen, s.radius, |x, y, p| {
        let (c, sn, _) = super::bayer_pattern(x, y, TAU);
        let phi = sn.atan2(c);
        let (mut sum, mut edge) = (0.0f32, false);
        for i in 0..s.samples {
            let alpha = (i as f32 + 0.5) / n;
            let angle = alpha * TAU * s.spiral_turns + phi;
            let distance = alpha * p.radius_px;
            let exact = (distance.max(1.0).ln() - LEVEL_OFFSET_PX.ln()) / (l.factor as f32).ln();
            edge |= exact > -0.5 && (exact - exact.round()).abs() < 1e-4;
            let level = exact.floor().clamp(0.0, (levels - 1) as f32) as u32;
            let px = p.centre + Vec2::new(angle.cos(), -angle.sin()) * distance;
            let (surface, e) = l.surface(p.pixel, px, level);
            edge |= e;
            if let Some(q) = surface {
                let v = q - p.pos;
                let vv = v.dot(v);
                let f = (s.radius * s.radius - vv).max(0.0);
                sum += f * f * f * ((v.dot(p.n) - s.bias) / (epsilon(s.radius) + vv)).max(0.0);
            }
        }
        let ao = (1.0 - sum * obscurance_scale(s, s.radius)).max(0.0);
        (ao, edge)
    })
}
