//! The GTAO estimator (`shaders/estimators/gtao.wgsl`): ground-truth-based AO (Jimenez et al.
//! 2016), the baseline of seed 003, with XeGTAO's falloff and step distribution. Its slice table
//! and per-pixel pattern are here so the CPU mirror in the tests uses the same numbers.

use crate::knob::{Kind, Knob, Widget};
use serde::{Deserialize, Serialize};
use std::f32::consts::PI;

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
