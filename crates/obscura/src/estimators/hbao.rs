//! The classic HBAO estimator (`shaders/estimators/hbao.wgsl`): horizon-based AO as seed 001 §3.2
//! Algorithm 2 and seed 004 §2.2.1 state it. Its direction table and per-pixel pattern are here so
//! that its CPU mirror, [`cpu_hbao`] (the kernel in plain Rust for the tests), uses the same
//! numbers.

use super::mirror::{per_shaded_pixel, surface_at, MirrorGBuffer, MirrorScreen};
use crate::knob::{Kind, Knob, Widget};
use glam::Vec2;
use serde::{Deserialize, Serialize};
use std::f32::consts::{FRAC_PI_2, TAU};

/// The most `hbao.directions` (the parameter block's direction table; seed 004's largest grid is
/// 64 × 80).
pub const HBAO_MAX_DIRECTIONS: u32 = 64;

/// Classic HBAO parameters (seed 001 §3.2 Algorithm 2, seed 004 §2.2.1): D directions × S steps,
/// defaults 8 × 4 as seed 001 Tab. 1; seed 004's grid 8 × 10 … 64 × 80 is within range.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct HbaoSettings {
    /// Radius R in world units: samples up to R on screen, attenuation W(r) = 1 − r/R.
    pub radius: f32,
    /// Angle added to the tangent's elevation to start each direction's horizon, in radians
    /// (absorbs tessellation creases; the papers give no value, ours is 0.1 ≈ 5.7°).
    pub angle_bias: f32,
    /// Power applied to the final AO.
    pub exponent: f32,
    /// Directions per pixel, 1 to 64.
    pub directions: u32,
    /// Steps per direction, 1 to 128.
    pub steps: u32,
}

impl Default for HbaoSettings {
    fn default() -> Self {
        Self {
            radius: 0.5,
            angle_bias: 0.1,
            exponent: 1.0,
            directions: 8,
            steps: 4,
        }
    }
}

impl HbaoSettings {
    // Classic HBAO's flags are `--horizon-*`: `--hbao-*` named HBAO+'s first and stays its alias.
    /// Every field's knob: range, unit, flag, help, widget (crate::knob).
    pub const KNOBS: &'static [Knob] = &[
        Knob::new(
            "hbao.radius",
            "--horizon-radius",
            "HBAO (hbao, hbao-dual) radius R in world units; attenuation 1 − r/R.",
            Kind::POSITIVE,
        )
        .length()
        .doc("HBAO radius R (samples up to R on screen, attenuation W(r) = 1 − r/R)")
        .widget(Widget::RADIUS),
        Knob::new(
            "hbao.angle_bias",
            "--horizon-bias",
            "HBAO angle bias in radians, added to the tangent elevation each direction starts from.",
            Kind::number(0.0, std::f64::consts::FRAC_PI_2, false, true),
        )
        .units("radians")
        .doc("added to the tangent's elevation where each direction's horizon starts"),
        Knob::new("hbao.exponent", "--horizon-exponent", "HBAO power applied to the final AO.", Kind::POSITIVE),
        Knob::new(
            "hbao.directions",
            "--horizon-directions",
            "HBAO directions per pixel, D.",
            Kind::int(1, HBAO_MAX_DIRECTIONS),
        )
        .widget(Widget::Range),
        Knob::new(
            "hbao.steps",
            "--horizon-steps",
            "HBAO steps per direction, r'/(S + 1) pixels apart.",
            Kind::int(1, 128),
        )
        .widget(Widget::Range),
    ];
}

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
    direction_table: [[f32; 4]; HBAO_MAX_DIRECTIONS as usize],
}

/// The estimator as the technique table runs it (`EstimatorCaps::module`).
pub const MODULE: super::EstimatorModule = super::EstimatorModule {
    wgsl: WGSL,
    constants: CONSTANTS,
    knobs: HbaoSettings::KNOBS,
    params: |section, inputs| params(&super::section(section), inputs),
    table: None,
};

/// The parameter block (group 1) and the values of [`CONSTANTS`] for `settings`.
pub(crate) fn params(s: &HbaoSettings, _: &super::SourceInputs) -> (Vec<u8>, Vec<f64>) {
    let mut direction_table = [[0.0; 4]; HBAO_MAX_DIRECTIONS as usize];
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

/// The CPU mirror: HBAO as `hbao.wgsl` states it, as plain Rust per pixel of `g` drawn with
/// `screen`; `interleaved`: the interleaved schedule's samples, which read the nearest pixel of
/// their own residue class mod 4. Returns the AO of every visible pixel, row-major, and whether
/// one of its samples lay within 1e-3 px of where the pixel it reads flips, where float rounding
/// may snap the GPU and the CPU to different neighbours (the tests allow a difference only there).
pub fn cpu_hbao(
    g: &dyn MirrorGBuffer,
    screen: &dyn MirrorScreen,
    s: &HbaoSettings,
    interleaved: bool,
) -> (Vec<f32>, Vec<bool>) {
    per_shaded_pixel(g, screen, s.radius, |x, y, p| {
        let step = p.radius_px / (s.steps + 1) as f32;
        let (c, sn, jitter) = pixel_pattern(x, y, s.directions);
        let start = jitter * step + 1.0;
        let (mut occlusion, mut edge) = (0.0f32, false);
        for d in 0..s.directions {
            let (bx, by) = direction(d, s.directions);
            let dir = Vec2::new(bx * c - by * sn, bx * sn + by * c);
            let d3 = dir.extend(0.0);
            let slice = (d3 - p.v * d3.dot(p.v)).normalize();
            let (n_v, n_d) = (p.n.dot(p.v), p.n.dot(slice));
            let sin_t = -n_d / (n_v * n_v + n_d * n_d).max(1e-12).sqrt();
            let t = sin_t.clamp(-1.0, 1.0).asin();
            let mut sin_h = (t + s.angle_bias).min(FRAC_PI_2).sin();
            for k in 0..s.steps {
                let px = p.centre + Vec2::new(dir.x, -dir.y) * (start + k as f32 * step);
                let (surface, e) = surface_at(g, screen, p, px, interleaved);
                edge |= e;
                let Some(q) = surface else { continue };
                let v = q - p.pos;
                let dist = v.length();
                let sin_phi = v.dot(p.v) / dist.max(1e-20);
                if v.dot(p.n) <= 1e-3 * dist {
                    continue;
                }
                let w = (1.0 - dist / s.radius).max(0.0);
                if w > 0.0 && sin_phi > sin_h {
                    occlusion += w * (sin_phi - sin_h);
                    sin_h = sin_phi;
                }
            }
        }
        let ao = (1.0 - occlusion / s.directions as f32)
            .clamp(0.0, 1.0)
            .powf(s.exponent);
        (ao, edge)
    })
}
