//! The GTAO estimator (`shaders/estimators/gtao.wgsl`): ground-truth-based AO (Jimenez et al.
//! 2016), the baseline of seed 003, with XeGTAO's falloff and step distribution. Its slice table
//! and per-pixel pattern are here so that its CPU mirror, [`cpu_gtao`] (the kernel in plain Rust
//! for the tests), uses the same numbers.

use super::mirror::{
    open_slice_visibility, per_shaded_pixel, side_visibility, surface_at, MirrorGBuffer,
    MirrorScreen,
};
use crate::knob::{Kind, Knob, Widget};
use glam::Vec2;
use serde::{Deserialize, Serialize};
use std::f32::consts::{FRAC_PI_2, PI};

/// The most `gtao.slices` (the parameter block's slice table).
pub const GTAO_MAX_SLICES: u32 = 16;

/// GTAO parameters (Jimenez et al. 2016, the baseline of seed 003; falloff and step distribution
/// as XeGTAO).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct GtaoSettings {
    /// Radius R in world units. As XeGTAO, samples reach 1.457·R, their weight falling from 1 at
    /// 0.56·R to 0 at 1.457·R, which finds as much occlusion as R unattenuated on average.
    pub radius: f32,
    /// Thickness heuristic β in [0, 1]: a sample below the current horizon pulls it down by β
    /// (0, the default: the plain maximum horizon).
    pub thickness_blend: f32,
    /// Power applied to the final AO.
    pub exponent: f32,
    /// Slices per pixel, 1 to 16.
    pub slices: u32,
    /// Steps on each side of a slice, 1 to 32.
    pub steps: u32,
}

impl Default for GtaoSettings {
    fn default() -> Self {
        Self {
            radius: 0.5,
            thickness_blend: 0.0,
            exponent: 1.0,
            slices: 2,
            steps: 2,
        }
    }
}

impl GtaoSettings {
    /// Every field's knob: range, unit, flag, help, widget (crate::knob).
    pub const KNOBS: &'static [Knob] = &[
        Knob::new("gtao.radius", "--gtao-radius", "GTAO radius R in world units.", Kind::POSITIVE)
            .length()
            .doc(
                "GTAO radius R (as XeGTAO: samples reach 1.457·R, full weight up to 0.56·R, none \
                 beyond 1.457·R)",
            )
            .widget(Widget::RADIUS),
        Knob::new(
            "gtao.thickness_blend",
            "--gtao-thickness-blend",
            "GTAO thickness heuristic β: how far a lower sample pulls the horizon down.",
            Kind::number(0.0, 1.0, false, false),
        )
        .doc("thickness heuristic β: a sample below the horizon pulls it down by β (0: the maximum horizon)"),
        Knob::new("gtao.exponent", "--gtao-exponent", "GTAO power applied to the final AO.", Kind::POSITIVE),
        Knob::new("gtao.slices", "--gtao-slices", "GTAO slices per pixel.", Kind::int(1, GTAO_MAX_SLICES))
            .widget(Widget::Range),
        Knob::new("gtao.steps", "--gtao-steps", "GTAO steps on each side of a slice.", Kind::int(1, 32))
            .widget(Widget::Range),
    ];
}

/// The estimator's WGSL (the estimator contract, docs/ARCHITECTURE.md), after the shared
/// screen-space pixel set-up.
pub(crate) const WGSL: &str = concat!(
    include_str!("../../shaders/estimators/screen_space.wgsl"),
    include_str!("../../shaders/estimators/slice_visibility.wgsl"),
    include_str!("../../shaders/estimators/gtao.wgsl"),
    include_str!("../../shaders/estimators/no_bent_sample.wgsl"),
    include_str!("../../shaders/estimators/no_depth_interval.wgsl"),
);
/// Its `override` constants: the sample count, slices × 2 × steps, and the steps per side.
pub(crate) const CONSTANTS: &[&str] = &["SAMPLE_COUNT", "STEPS"];

/// XeGTAO's radius multiplier: samples reach 1.457·R, so that with the falloff below the
/// occlusion found matches an unattenuated radius R on average (XeGTAO's default).
pub const RADIUS_MULTIPLIER: f32 = 1.457;

/// XeGTAO's falloff range as a fraction of the reach: a sample's weight falls linearly from 1 at
/// (1 − 0.615)·1.457·R ≈ 0.56·R to 0 at 1.457·R.
pub const FALLOFF_RANGE: f32 = 0.615;

/// Pixel (x, y) of the visible image: (cos, sin) of its slice rotation, π·B/16/slices with B the
/// Bayer value of (x % 4, y % 4), and its step jitter in [0, 1) ([`super::bayer_pattern`]).
pub fn pixel_pattern(x: u32, y: u32, slices: u32) -> (f32, f32, f32) {
    super::bayer_pattern(x, y, PI / slices as f32)
}

/// Slice `j` of `slices`, unrotated: the unit direction at angle π·j/slices (view-space x right,
/// y up).
pub fn slice_direction(j: u32, slices: u32) -> (f32, f32) {
    let angle = PI * j as f32 / slices as f32;
    (angle.cos(), angle.sin())
}

/// How far samples reach for `radius`: [`RADIUS_MULTIPLIER`]·R.
pub fn reach(radius: f32) -> f32 {
    RADIUS_MULTIPLIER * radius
}

/// The falloff weight of a sample `distance` world units from the shading point.
pub fn falloff(distance: f32, radius: f32) -> f32 {
    let reach = reach(radius);
    ((reach - distance) / (FALLOFF_RANGE * reach)).clamp(0.0, 1.0)
}

/// GPU mirror of `GtaoParams` in the WGSL.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct GtaoParams {
    radius: f32,
    falloff_mul: f32,
    falloff_add: f32,
    thickness_blend: f32,
    exponent: f32,
    slices: u32,
    steps: u32,
    _pad: u32,
    pattern: [[f32; 4]; 16],
    slice_table: [[f32; 4]; GTAO_MAX_SLICES as usize],
}

/// The estimator as the technique table runs it (`EstimatorCaps::module`).
pub const MODULE: super::EstimatorModule = super::EstimatorModule {
    wgsl: WGSL,
    constants: CONSTANTS,
    knobs: GtaoSettings::KNOBS,
    params: |section, inputs| params(&super::section(section), inputs),
    table: None,
};

/// The parameter block (group 1) and the values of [`CONSTANTS`] for `settings`.
pub(crate) fn params(s: &GtaoSettings, _: &super::SourceInputs) -> (Vec<u8>, Vec<f64>) {
    let mut slice_table = [[0.0; 4]; GTAO_MAX_SLICES as usize];
    for (j, k) in slice_table.iter_mut().enumerate().take(s.slices as usize) {
        let (c, sn) = slice_direction(j as u32, s.slices);
        *k = [c, sn, 0.0, 0.0];
    }
    let reach = reach(s.radius);
    let range = FALLOFF_RANGE * reach;
    let params = GtaoParams {
        radius: reach,
        // (reach − d)/range = d·(−1/range) + reach/range.
        falloff_mul: -1.0 / range,
        falloff_add: reach / range,
        thickness_blend: s.thickness_blend,
        exponent: s.exponent,
        slices: s.slices,
        steps: s.steps,
        _pad: 0,
        pattern: super::bayer_table(PI / s.slices as f32),
        slice_table,
    };
    (
        bytemuck::bytes_of(&params).to_vec(),
        vec![f64::from(s.slices * 2 * s.steps), f64::from(s.steps)],
    )
}

/// The CPU mirror: GTAO as `gtao.wgsl` states it, as plain Rust per pixel of `g` drawn with
/// `screen` (single-pass schedule). Returns the AO of every visible pixel, row-major, and whether
/// one of its samples lay within 1e-3 px of a pixel edge, where float rounding may snap the GPU
/// and the CPU to different neighbours (the tests allow a difference only there).
pub fn cpu_gtao(
    g: &dyn MirrorGBuffer,
    screen: &dyn MirrorScreen,
    s: &GtaoSettings,
) -> (Vec<f32>, Vec<bool>) {
    let reach = reach(s.radius);
    per_shaded_pixel(g, screen, reach, |x, y, p| {
        let (c, sn, jitter) = pixel_pattern(x, y, s.slices);
        let min_fraction = 1.3 / p.radius_px;
        let (mut visible, mut open, mut edge) = (0.0f32, 0.0f32, false);
        for j in 0..s.slices {
            let (bx, by) = slice_direction(j, s.slices);
            let dir = Vec2::new(bx * c - by * sn, bx * sn + by * c);
            let d3 = dir.extend(0.0);
            let tangent = (d3 - p.v * d3.dot(p.v)).normalize();
            let axis = tangent.cross(p.v);
            let projected = p.n - axis * p.n.dot(axis);
            let length = projected.length();
            let gamma = projected.dot(tangent).atan2(projected.dot(p.v));
            let lowest = [-gamma.sin(), gamma.sin()];
            let mut horizon = lowest;
            for (side, sign) in [(0, 1.0), (1, -1.0)] {
                for k in 0..s.steps {
                    let f = (k as f32 + jitter) / s.steps as f32;
                    let distance = (f * f + min_fraction) * p.radius_px;
                    let px = p.centre + sign * Vec2::new(dir.x, -dir.y) * distance;
                    let (surface, e) = surface_at(g, screen, p, px, false);
                    edge |= e;
                    let (cos_s, w) = match surface {
                        Some(q) => {
                            let delta = q - p.pos;
                            let dist = delta.length();
                            let above = delta.dot(p.n) > 1e-3 * dist;
                            let w = if above { falloff(dist, s.radius) } else { 0.0 };
                            (delta.dot(p.v) / dist.max(1e-20), w)
                        }
                        None => (-1.0, 0.0),
                    };
                    let sample = lowest[side] + (cos_s - lowest[side]) * w;
                    let h = horizon[side];
                    horizon[side] = sample.max(h + (sample - h) * s.thickness_blend);
                }
            }
            let h1 = gamma + (horizon[0].clamp(-1.0, 1.0).acos() - gamma).min(FRAC_PI_2);
            let h0 = gamma + (-horizon[1].clamp(-1.0, 1.0).acos() - gamma).max(-FRAC_PI_2);
            visible += length * (side_visibility(h0, gamma) + side_visibility(h1, gamma));
            open += length * open_slice_visibility(gamma);
        }
        let ao = if open > 0.0 {
            (visible / open).clamp(0.0, 1.0).powf(s.exponent)
        } else {
            1.0
        };
        (ao, edge)
    })
}
