//! The Pyramid HBAO estimator (`shaders/estimators/pyramid_hbao.wgsl`, seed 004 §3): directions
//! walked over the levels of the depth pyramid, each direction's largest weighted contribution.
//! Its per-pixel offsets are here so that its CPU mirror, [`cpu_pyramid_hbao`] (the kernel in plain
//! Rust for the tests), and the tests use the same numbers.

use super::mirror::{per_visible_pixel, pixel_setup, Levels};
use crate::knob::{Kind, Knob, Widget};
use glam::Vec2;
use serde::{Deserialize, Serialize};
use std::f32::consts::TAU;

/// Pyramid HBAO parameters (seed 004 §3.4–3.5).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct PyramidHbaoSettings {
    /// Radius R in world units: attenuation W(r) = 1 − r/R (Eq. 7).
    pub radius: f32,
    /// Power applied to the final AO.
    pub exponent: f32,
    /// D, directions per pixel (seed 004: 8), 1 to 32.
    pub directions: u32,
    /// Steps on every pyramid level along each direction, 1 to 16 (the paper fixes a number
    /// without giving it; ours is 4).
    pub steps: u32,
}

impl Default for PyramidHbaoSettings {
    fn default() -> Self {
        Self {
            radius: 0.5,
            exponent: 1.0,
            directions: 8,
            steps: 4,
        }
    }
}

impl PyramidHbaoSettings {
    /// Every field's knob: range, unit, flag, help, widget (crate::knob).
    pub const KNOBS: &'static [Knob] = &[
        Knob::new(
            "pyramid_hbao.radius",
            "--pyramid-hbao-radius",
            "Pyramid HBAO radius R in world units; attenuation 1 − r/R.",
            Kind::POSITIVE,
        )
        .aliases(&["--phbao-radius"])
        .length()
        .doc("Pyramid HBAO radius R (attenuation W(r) = 1 − r/R, seed 004 Eq. 7)")
        .widget(Widget::RADIUS),
        Knob::new(
            "pyramid_hbao.exponent",
            "--pyramid-hbao-exponent",
            "Pyramid HBAO power applied to the final AO.",
            Kind::POSITIVE,
        )
        .aliases(&["--phbao-exponent"]),
        Knob::new(
            "pyramid_hbao.directions",
            "--pyramid-hbao-directions",
            "Pyramid HBAO directions per pixel, D (seed 004: 8).",
            Kind::int(1, 32),
        )
        .aliases(&["--phbao-directions"])
        .widget(Widget::Range),
        Knob::new(
            "pyramid_hbao.steps",
            "--pyramid-hbao-steps",
            "Pyramid HBAO steps on every pyramid level along each direction (K^l px apart on level l).",
            Kind::int(1, 16),
        )
        .aliases(&["--phbao-steps"])
        .widget(Widget::Range),
    ];
}

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

/// The estimator as the technique table runs it (`EstimatorCaps::module`).
pub const MODULE: super::EstimatorModule = super::EstimatorModule {
    wgsl: WGSL,
    constants: CONSTANTS,
    knobs: PyramidHbaoSettings::KNOBS,
    params: |section, inputs| params(&super::section(section), inputs),
    table: None,
};

/// The parameter block (group 1) and the values of [`CONSTANTS`] for `settings` over `pyramid`.
pub(crate) fn params(s: &PyramidHbaoSettings, inputs: &super::SourceInputs) -> (Vec<u8>, Vec<f64>) {
    let pattern = std::array::from_fn(|i| {
        let (u, o) = pixel_offsets(i as u32 % 4, i as u32 / 4);
        [u, o, 0.0, 0.0]
    });
    let params = PyramidHbaoParams {
        radius: s.radius,
        inv_radius: 1.0 / s.radius,
        exponent: s.exponent,
        factor: inputs.pyramid_factor as f32,
        directions: s.directions,
        _pad: [0; 3],
        pattern,
    };
    (
        bytemuck::bytes_of(&params).to_vec(),
        vec![
            f64::from(s.directions * inputs.pyramid_levels * s.steps),
            f64::from(inputs.pyramid_levels),
            f64::from(s.steps),
        ],
    )
}

/// The CPU mirror: Pyramid HBAO as `pyramid_hbao.wgsl` states it, as plain Rust per pixel, over
/// `l` (the G-buffer and the pyramid's `levels` levels as read back). Returns the AO of every
/// visible pixel, row-major, and whether one of its samples lay within 1e-3 texel of a texel edge,
/// where float rounding may snap the GPU and the CPU to different texels.
pub fn cpu_pyramid_hbao(
    l: &Levels,
    s: &PyramidHbaoSettings,
    levels: u32,
) -> (Vec<f32>, Vec<bool>) {
    let k = l.factor as f32;
    per_visible_pixel(l.screen, |x, y| {
        let Some(p) = pixel_setup(l.g, l.screen, x, y, s.radius) else {
            return (1.0, false);
        };
        let (u0, o0) = pixel_offsets(x, y);
        let (mut sum, mut edge) = (0.0f32, false);
        for d in 0..s.directions {
            let df = d as f32;
            let u = (u0 + 0.618_034 * df).fract();
            let o = (o0 + 0.754_877_7 * df).fract();
            let angle = TAU * (df + u) / s.directions as f32;
            let mut best = 0.0f32;
            for level in 0..levels {
                let size = k.powi(level as i32);
                let start = s.steps as f32 * (size - 1.0) / (k - 1.0);
                for step in 0..s.steps {
                    let distance = (start + (step as f32 + o) * size).max(1.0);
                    let px = p.centre + Vec2::new(angle.cos(), -angle.sin()) * distance;
                    let (surface, e) = l.surface(p.pixel, px, level);
                    edge |= e;
                    if let Some(q) = surface {
                        let v = q - p.pos;
                        let dist = v.length();
                        let sin_alpha = v.dot(p.n) / dist.max(1e-20);
                        if sin_alpha > 1e-3 {
                            best = best.max((1.0 - dist / s.radius).max(0.0) * sin_alpha);
                        }
                    }
                }
            }
            sum += best;
        }
        let ao = (1.0 - sum / s.directions as f32)
            .clamp(0.0, 1.0)
            .powf(s.exponent);
        (ao, edge)
    })
}
