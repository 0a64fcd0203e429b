//! The HBAO+ estimator (`shaders/estimators/hbao_plus.wgsl`): NVIDIA-style per-sample horizon AO
//! as the seed authors' baseline (seed 000 §2.1, docs/AUTHORS_CODE.md §1.7). Its per-pixel pattern
//! is here so that its CPU mirror, [`cpu_hbao_plus`] (the kernel in plain Rust for the tests),
//! uses the same numbers.

use super::mirror::{per_shaded_pixel, surface_at, MirrorGBuffer, MirrorScreen};
use crate::knob::{Kind, Knob, Widget};
use glam::Vec2;
use serde::{Deserialize, Serialize};
use std::f32::consts::TAU;

/// HBAO+ parameters: NVIDIA-style per-sample horizon AO as the seed authors ran it as their baseline
/// (docs/AUTHORS_CODE.md §1.7: 8 directions × 4 steps, R 1.0, NdotV bias 0.1, exponent 2).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct HbaoPlusSettings {
    /// Radius R in world units: samples up to R on screen, falloff 1 − d²/R².
    pub radius: f32,
    /// Angle bias: a sample occludes by `saturate(N·V/|V| − bias)`.
    pub bias: f32,
    /// Power applied to the final AO.
    pub exponent: f32,
    /// Directions per pixel.
    pub directions: u32,
    /// Steps per direction; directions × steps ≤ 32 (one bit each in the two-phase mask).
    pub steps: u32,
}

impl Default for HbaoPlusSettings {
    fn default() -> Self {
        Self {
            radius: 1.0,
            bias: 0.1,
            exponent: 2.0,
            directions: 8,
            steps: 4,
        }
    }
}

impl HbaoPlusSettings {
    /// Every field's knob: range, unit, flag, help, widget (crate::knob).
    pub const KNOBS: &'static [Knob] = &[
        Knob::new(
            "hbao_plus.radius",
            "--hbao-plus-radius",
            "HBAO+ radius R in world units.",
            Kind::POSITIVE,
        )
        .aliases(&["--hbao-radius"])
        .length()
        .doc("HBAO+ radius R (samples up to R on screen, falloff 1 − d²/R²)")
        .widget(Widget::RADIUS),
        Knob::new(
            "hbao_plus.bias",
            "--hbao-plus-bias",
            "HBAO+ angle bias: a sample occludes by saturate(N·V/|V| − bias).",
            Kind::number(0.0, 1.0, false, true),
        )
        .aliases(&["--hbao-bias"]),
        Knob::new(
            "hbao_plus.exponent",
            "--hbao-plus-exponent",
            "HBAO+ power applied to the final AO.",
            Kind::POSITIVE,
        )
        .aliases(&["--hbao-exponent"]),
        Knob::new(
            "hbao_plus.directions",
            "--hbao-plus-directions",
            "HBAO+ directions per pixel (directions × steps ≤ 32).",
            Kind::int(1, 32),
        )
        .aliases(&["--hbao-directions"])
        .widget(Widget::Range),
        Knob::new(
            "hbao_plus.steps",
            "--hbao-plus-steps",
            "HBAO+ steps per direction.",
            Kind::int(1, 32),
        )
        .aliases(&["--hbao-steps"])
        .note("directions × steps ≤ 32: one bit per sample")
        .widget(Widget::Range),
    ];
}

/// The estimator's WGSL (the estimator contract, docs/ARCHITECTURE.md), after the shared
/// screen-space pixel set-up.
pub(crate) const WGSL: &str = concat!(
    include_str!("../../shaders/estimators/screen_space.wgsl"),
    include_str!("../../shaders/estimators/hbao_plus.wgsl"),
    include_str!("../../shaders/estimators/no_depth_interval.wgsl"),
);
/// Its `override` constants: the sample count, directions × steps, and the steps per direction.
pub(crate) const CONSTANTS: &[&str] = &["SAMPLE_COUNT", "STEPS"];

/// Pixel (x, y) of the visible image: (cos, sin) of its direction rotation, 2π·B/16/D with B the
/// Bayer value of (x % 4, y % 4), and its start jitter in [0, 1) ([`super::bayer_pattern`]).
pub fn pixel_pattern(x: u32, y: u32, directions: u32) -> (f32, f32, f32) {
    super::bayer_pattern(x, y, TAU / directions as f32)
}

/// Sample `i` of `directions` × `steps`: the unrotated unit direction 2π·(i / steps)/directions
/// and the step `i % steps`.
pub fn sample(i: u32, directions: u32, steps: u32) -> (f32, f32, u32) {
    let angle = TAU * (i / steps) as f32 / directions as f32;
    (angle.cos(), angle.sin(), i % steps)
}

/// GPU mirror of `HbaoPlusParams` in the WGSL.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct HbaoPlusParams {
    radius: f32,
    neg_inv_r2: f32,
    bias: f32,
    exponent: f32,
    directions: u32,
    steps: u32,
    _pad: [u32; 2],
    pattern: [[f32; 4]; 16],
    samples: [[f32; 4]; 32],
}

/// The estimator as the technique table runs it (`EstimatorCaps::module`).
pub const MODULE: super::EstimatorModule = super::EstimatorModule {
    wgsl: WGSL,
    constants: CONSTANTS,
    knobs: HbaoPlusSettings::KNOBS,
    params: |section, inputs| params(&super::section(section), inputs),
    table: None,
};

/// The parameter block (group 1) and the values of [`CONSTANTS`] for `settings`.
pub(crate) fn params(s: &HbaoPlusSettings, _: &super::SourceInputs) -> (Vec<u8>, Vec<f64>) {
    let pattern = super::bayer_table(TAU / s.directions as f32);
    let mut samples = [[0.0; 4]; 32];
    for (i, k) in samples
        .iter_mut()
        .enumerate()
        .take((s.directions * s.steps) as usize)
    {
        let (c, sn, step) = sample(i as u32, s.directions, s.steps);
        *k = [c, sn, step as f32, 0.0];
    }
    let params = HbaoPlusParams {
        radius: s.radius,
        neg_inv_r2: -1.0 / (s.radius * s.radius),
        bias: s.bias,
        exponent: s.exponent,
        directions: s.directions,
        steps: s.steps,
        _pad: [0; 2],
        pattern,
        samples,
    };
    (
        bytemuck::bytes_of(&params).to_vec(),
        vec![f64::from(s.directions * s.steps), f64::from(s.steps)],
    )
}

/// The CPU mirror: HBAO+ as `hbao_plus.wgsl` states it, as plain Rust per pixel of `g` drawn with
/// `screen`; `interleaved`: the interleaved schedule's samples, which read the nearest pixel of
/// their own residue class mod 4. Returns the AO of every visible pixel, row-major, and whether
/// one of its samples lay within 1e-3 px of where the pixel it reads flips, where float rounding
/// may snap the GPU and the CPU to different neighbours (the tests allow a difference only there).
pub fn cpu_hbao_plus(
    g: &dyn MirrorGBuffer,
    screen: &dyn MirrorScreen,
    s: &HbaoPlusSettings,
    interleaved: bool,
) -> (Vec<f32>, Vec<bool>) {
    let neg_inv_r2 = -1.0 / (s.radius * s.radius);
    per_shaded_pixel(g, screen, s.radius, |x, y, p| {
        let step = p.radius_px / (s.steps + 1) as f32;
        let (c, sn, jitter) = pixel_pattern(x, y, s.directions);
        let start = jitter * step + 1.0;
        let (mut occlusion, mut count, mut edge) = (0.0f32, 0.0f32, false);
        for i in 0..s.directions * s.steps {
            let (bx, by, k) = sample(i, s.directions, s.steps);
            let dir = Vec2::new(bx * c - by * sn, bx * sn + by * c);
            let px = p.centre + dir * (start + k as f32 * step);
            count += 1.0;
            let (surface, e) = surface_at(g, screen, p, px, interleaved);
            edge |= e;
            let Some(q) = surface else { continue };
            let v = q - p.pos;
            let v_dot_v = v.dot(v).max(1e-20);
            let angle_term = (p.n.dot(v) / v_dot_v.sqrt() - s.bias).clamp(0.0, 1.0);
            let distance_term = (v_dot_v * neg_inv_r2 + 1.0).clamp(0.0, 1.0);
            occlusion += angle_term * distance_term;
        }
        let ao = (1.0 - 2.0 * occlusion / count)
            .clamp(0.0, 1.0)
            .powf(s.exponent);
        (ao, edge)
    })
}
