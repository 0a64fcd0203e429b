//! The GTAO visibility-bitmask estimator (`shaders/estimators/gtao_vb.wgsl`, seed 003). Its sample
//! table and per-pixel pattern are here so that its CPU mirror, [`cpu_gtao_vb`] (the kernel in
//! plain Rust for the tests), uses the same numbers.

use super::mirror::{
    open_slice_visibility, per_visible_pixel, pixel_setup, span_visibility, surface_at,
    MirrorGBuffer, MirrorScreen,
};
use crate::knob::{Kind, Knob, Widget};
use glam::{Vec2, Vec3};
use serde::{Deserialize, Serialize};
use std::f32::consts::{FRAC_PI_2, PI};

/// How a sample's angular span turns into sectors of the visibility bitmask (seed 003).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SectorActivation {
    /// A sector the span touches (seed 003's listing). Any span, however thin, occludes a whole
    /// sector: a sample a hair above a near-flat surface's tangent plane (tessellated curves,
    /// depth rounding) greys open surfaces (issue 62: 0.03–0.04 below the truth on Sponza and
    /// Sibenik).
    Ceil,
    /// A sector the span covers at least half of: the default, chosen by measurement against the
    /// hemisphere ground truth on Sponza, Sibenik, stairs and colonnade at R = 0.5 and 1 (the
    /// lowest mean MAE of the three, half ceil's error on open surfaces;
    /// docs/lab/2026-12-06-rows-against-truth.md).
    #[default]
    Round,
    /// A sector the span covers whole.
    Floor,
}

/// GTAO with visibility bitmasks (seed 003): slices × steps per side, 32 sectors per slice,
/// constant thickness, no falloff.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct GtaoVbSettings {
    /// Screen-space search radius R in world units.
    pub radius: f32,
    /// Constant thickness of every surface behind its depth sample, world units (the default
    /// is VAO's default thickness τ·R = 0.25: the same physical assumption).
    pub thickness: f32,
    /// Power applied to the final AO.
    pub exponent: f32,
    /// Slices (1 to 3: one 32-bit mask each in the estimator's three-word state).
    pub slices: u32,
    /// Steps on each side of a slice; slices × 2 × steps ≤ 32.
    pub steps: u32,
    /// Which sectors a sample's angular span sets (default [`SectorActivation::Round`]).
    pub activation: SectorActivation,
    /// Weigh each free sector by its cosine-weighted share of the slice, GTAO's integral (our
    /// extension: the ground truth's cosine-weighted AO); default `false`, seed 003's uniform
    /// count of free sectors.
    pub cosine_weighted: bool,
}

impl Default for GtaoVbSettings {
    fn default() -> Self {
        Self {
            radius: 0.5,
            thickness: 0.25,
            exponent: 1.0,
            slices: 2,
            steps: 2,
            activation: SectorActivation::Round,
            cosine_weighted: false,
        }
    }
}

impl GtaoVbSettings {
    /// Every field's knob: range, unit, flag, help, widget (crate::knob).
    pub const KNOBS: &'static [Knob] = &[
        Knob::new("gtao_vb.radius", "--gtao-vb-radius", "GTAO-VB search radius R in world units.", Kind::POSITIVE)
            .aliases(&["--vb-radius"])
            .length()
            .widget(Widget::RADIUS),
        Knob::new(
            "gtao_vb.thickness",
            "--gtao-vb-thickness",
            "GTAO-VB constant thickness behind every depth sample, world units.",
            Kind::NON_NEGATIVE,
        )
        .aliases(&["--vb-thickness"])
        .length()
        .doc("constant thickness behind every depth sample (light passes behind it)")
        .widget(Widget::Slider {
            min: 0.0,
            max: 1.0,
            log: false,
        }),
        Knob::new("gtao_vb.exponent", "--gtao-vb-exponent", "GTAO-VB power applied to the final AO.", Kind::POSITIVE)
            .aliases(&["--vb-exponent"]),
        Knob::new("gtao_vb.slices", "--gtao-vb-slices", "GTAO-VB slices per pixel.", Kind::int(1, 3))
            .aliases(&["--vb-slices"])
            .note("one 32-bit mask each")
            .widget(Widget::Range),
        Knob::new("gtao_vb.steps", "--gtao-vb-steps", "GTAO-VB steps on each side of a slice.", Kind::int(1, 16))
            .aliases(&["--vb-steps"])
            .note("slices × 2 × steps ≤ 32: one bit per sample")
            .widget(Widget::Range),
        Knob::new(
            "gtao_vb.activation",
            "--gtao-vb-activation",
            "GTAO-VB sector activation: ceil (touched), round (half covered) or floor (covered).",
            Kind::Choice(&["ceil", "round", "floor"]),
        )
        .aliases(&["--vb-activation"])
        .doc("a sector is occluded when a sample's span touches it, covers half of it, or covers it whole (seed 003)"),
        Knob::new(
            "gtao_vb.cosine_weighted",
            "--gtao-vb-cosine",
            "GTAO-VB: weigh free sectors by the cosine to the normal, GTAO's integral (our \
             extension; seed 003 counts sectors alike).",
            Kind::Switch { flag_sets: true },
        )
        .aliases(&["--vb-cosine"]),
    ];
}

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
/// no deeper surface can mark a free sector ([`super::SourceInputs::exact_query`]); and the steps per slice side.
pub(crate) const CONSTANTS: &[&str] = &["SAMPLE_COUNT", "COSINE_WEIGHTED", "EXACT_QUERY", "STEPS"];

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

/// The table gtao_vb.wgsl's uniformly weighted bent normal reads (bindings::ESTIMATOR_TABLE):
/// entry b, for the sectors j of a byte b's set bits, is 2 sin(π/64) Σ_j (cos φ_j, sin φ_j),
/// φ_j = (j + ½) π/32 the centre of sector j of the byte's first eight. 2 sin(π/64) (cos φ, −sin φ)
/// negated is the ∫ω over one sector, so a mask's marked sectors sum from its four bytes, each
/// turned by its offset (π/4 a byte), with no loop over the mask's runs. Made in f64.
pub fn sector_direction_table() -> Vec<[f32; 2]> {
    let sector = std::f64::consts::PI / 32.0;
    let scale = 2.0 * (sector / 2.0).sin();
    (0..256u32)
        .map(|byte| {
            let (mut c, mut s) = (0.0f64, 0.0f64);
            for j in (0..8).filter(|j| byte >> j & 1 == 1) {
                let phi = (f64::from(j) + 0.5) * sector;
                c += phi.cos();
                s += phi.sin();
            }
            [(scale * c) as f32, (scale * s) as f32]
        })
        .collect()
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

/// The estimator as the technique table runs it (`EstimatorCaps::module`).
pub const MODULE: super::EstimatorModule = super::EstimatorModule {
    wgsl: WGSL,
    constants: CONSTANTS,
    knobs: GtaoVbSettings::KNOBS,
    params: |section, inputs| params(&super::section(section), inputs),
    table: Some(sector_direction_table),
};

/// The parameter block (group 1) and the values of [`CONSTANTS`] for `settings`.
pub(crate) fn params(s: &GtaoVbSettings, inputs: &super::SourceInputs) -> (Vec<u8>, Vec<f64>) {
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
            f64::from(u8::from(inputs.exact_query())),
            f64::from(s.steps),
        ],
    )
}

/// The sectors between hemisphere positions `a` and `b` (0 to 1 across the slice's hemisphere),
/// as gtao_vb.wgsl's `sector_bits` marks them under `activation`.
pub fn sector_bits(a: f32, b: f32, activation: SectorActivation) -> u32 {
    let lo = a.min(b);
    let width = (a.max(b) - lo) * 32.0;
    let count = match activation {
        SectorActivation::Ceil => width.ceil(),
        SectorActivation::Round => width.round(),
        SectorActivation::Floor => width.floor(),
    };
    let start = ((lo * 32.0) as u32).min(32);
    let n = (count.max(0.0) as u32).min(32 - start);
    if n == 0 {
        0
    } else {
        (u32::MAX >> (32 - n)) << start
    }
}

/// The CPU mirror: GTAO-VB as `gtao_vb.wgsl` states it, as plain Rust per pixel of `g` drawn with
/// `screen` (single-pass schedule; uniform or cosine-weighted sectors as `s` says). Returns the AO
/// of every visible pixel, row-major, and whether one of its samples lay within 1e-3 px of a pixel
/// edge, where float rounding may snap the GPU and the CPU to different neighbours.
pub fn cpu_gtao_vb(
    g: &dyn MirrorGBuffer,
    screen: &dyn MirrorScreen,
    s: &GtaoVbSettings,
) -> (Vec<f32>, Vec<bool>) {
    per_visible_pixel(screen, |x, y| {
        let Some(p) = pixel_setup(g, screen, x, y, s.radius) else {
            return (1.0, false);
        };
        let step_px = if p.radius_px >= 1.0 {
            p.radius_px / s.steps as f32
        } else {
            0.0
        };
        let (c, sn, jitter) = pixel_pattern(x, y, s.slices);
        let mut masks = [0u32; 3];
        // Per slice: the projected normal's angle γ and length (cosine-weighted sectors).
        let mut slice_normals = [(0.0f32, 0.0f32); 3];
        let mut edge = false;
        for i in 0..s.slices * 2 * s.steps {
            if step_px == 0.0 {
                break;
            }
            let (bx, by, side, step) = sample(i, s.slices, s.steps);
            let dir = Vec2::new(bx * c - by * sn, bx * sn + by * c);
            let slice = (i / (2 * s.steps)) as usize;
            let px = p.centre
                + side * Vec2::new(dir.x, -dir.y) * ((jitter + 1.0 + step as f32) * step_px);
            let (surface, e) = surface_at(g, screen, &p, px, false);
            edge |= e;
            let d = dir.extend(0.0);
            let tangent = (d - p.v * d.dot(p.v)).normalize();
            let slice_normal = tangent.cross(p.v);
            let projected = p.n - slice_normal * p.n.dot(slice_normal);
            let normal_angle = projected.dot(tangent).atan2(projected.dot(p.v));
            slice_normals[slice] = (normal_angle, projected.length());
            let Some(q) = surface else { continue };
            let front = q - p.pos;
            if front.dot(p.n) <= 1e-3 * front.length() {
                continue;
            }
            let back = front - p.v * s.thickness;
            let position = |w: Vec3| {
                let angle = w.dot(tangent).atan2(w.dot(p.v));
                ((angle - normal_angle + FRAC_PI_2) / PI).clamp(0.0, 1.0)
            };
            masks[slice] |= sector_bits(position(front), position(back), s.activation);
        }
        let (mut visible, mut open) = (0.0f32, 0.0f32);
        for (&mask, &(gamma, length)) in masks.iter().zip(&slice_normals).take(s.slices as usize) {
            if !s.cosine_weighted {
                visible += 1.0 - mask.count_ones() as f32 / 32.0;
                open += 1.0;
                continue;
            }
            // Every free sector k spans θ from γ + π(k/32 − ½) to γ + π((k + 1)/32 − ½).
            let angle = |k: u32| gamma + PI * (k as f32 / 32.0 - 0.5);
            for k in (0..32).filter(|k| mask & (1 << k) == 0) {
                visible += length * span_visibility(angle(k), angle(k + 1), gamma);
            }
            open += length * open_slice_visibility(gamma);
        }
        ((visible / open).clamp(0.0, 1.0).powf(s.exponent), edge)
    })
}

#[cfg(test)]
mod tests {
    use super::sector_direction_table;

    /// The free sectors' ∫ω in the slice's local frame as the shader summed it before the table:
    /// a loop over the runs of free sectors, each the difference of its boundaries' pairs.
    fn free_runs(mask: u32) -> [f64; 2] {
        let step = std::f64::consts::PI / 32.0;
        let pair = |k: u32| (f64::from(k) * step).sin_cos();
        let (mut x, mut y) = (0.0, 0.0);
        let mut free = !mask;
        while free != 0 {
            let start = free.trailing_zeros();
            let end = start + (!(free >> start)).trailing_zeros();
            let ((s0, c0), (s1, c1)) = (pair(start), pair(end));
            x += s0 - s1;
            y += c0 - c1;
            free &= if end >= 32 { 0 } else { u32::MAX << end };
        }
        [x, y]
    }

    /// gtao_vb.wgsl's marked_sector_sum and its use, in f32 as the shader runs it.
    fn from_table(mask: u32) -> [f32; 2] {
        let table = sector_direction_table();
        let t = |b: u32| table[(mask >> (8 * b) & 255) as usize];
        let h = std::f32::consts::FRAC_1_SQRT_2;
        let (t0, t1, t2, t3) = (t(0), t(1), t(2), t(3));
        let m = [
            t0[0] + h * (t1[0] - t1[1]) - t2[1] + h * (-t3[0] - t3[1]),
            t0[1] + h * (t1[0] + t1[1]) + t2[0] + h * (t3[0] - t3[1]),
        ];
        [m[0], 2.0 - m[1]]
    }

    #[test]
    fn the_byte_table_sums_the_free_sectors_as_the_loop_over_their_runs() {
        let mut masks = vec![
            0,
            u32::MAX,
            1,
            1 << 31,
            0x0000_ff00,
            0x8000_0001,
            0x0f0f_0f0f,
        ];
        // A fixed xorshift sequence for the rest: every byte value many times over.
        let mut x = 0x9e37_79b9u32;
        masks.extend((0..20_000).map(|_| {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            x
        }));
        for mask in masks {
            let (loop_sum, table_sum) = (free_runs(mask), from_table(mask));
            for c in 0..2 {
                let error = (f64::from(table_sum[c]) - loop_sum[c]).abs();
                assert!(
                    error < 2e-6,
                    "mask {mask:#010x}: {table_sum:?} against {loop_sum:?}"
                );
            }
        }
        // Nothing marked: exactly the open hemisphere's (0, 2), so an unoccluded plane's bent
        // normal is its normal.
        assert_eq!(from_table(0), [0.0, 2.0]);
    }
}
