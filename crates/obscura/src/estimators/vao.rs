//! The Volumetric Ambient Occlusion estimator (seed 000 §3.1–3.5): the sample kernel, the per-pixel
//! rotation pattern and the parameters of `shaders/estimators/vao.wgsl`. The same tables feed the
//! CPU mirror in [`crate::reference::cpu_vao`].

use crate::knob::{Kind, Knob, Widget};
use glam::{Vec2, Vec3};
use serde::{Deserialize, Serialize};
use std::f32::consts::TAU;
use std::fmt;

/// Volumetric AO parameters (seed 000; defaults from the authors' 2022 code, docs/AUTHORS_CODE.md
/// §1.2).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct VaoSettings {
    /// Sphere radius R in world units.
    pub radius: f32,
    /// Thickness τ of the constant (fully occluding) area above the sample column, in units of R.
    pub thickness: f32,
    /// Power applied to the final AO.
    pub exponent: f32,
    /// Line samples per pixel: 8, 16 or 32.
    pub samples: u32,
    /// How the free column lengths become AO (default [`Normalization::Clipped`]).
    pub normalization: Normalization,
}

/// How VAO turns the free column lengths into AO (see `shaders/estimators/vao.wgsl`). In files:
/// `"clipped"` or `"hemisphere"`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Normalization {
    /// Seed 000 Eq. 7 with the hemisphere factor 2: `2/N Σ free/2h`. Exactly 1 on an unoccluded
    /// plane only on average over the 4×4 rotation pattern.
    #[serde(alias = "paper")]
    Hemisphere,
    /// `Σ free/2h / Σ clipped/2h`: the same limit, exactly 1 on every unoccluded plane.
    #[default]
    Clipped,
}

impl Default for VaoSettings {
    fn default() -> Self {
        Self {
            radius: 0.5,
            thickness: 0.5,
            exponent: 1.3,
            samples: 8,
            normalization: Normalization::Clipped,
        }
    }
}

impl fmt::Display for Normalization {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Normalization::Hemisphere => "hemisphere",
            Normalization::Clipped => "clipped",
        })
    }
}

impl VaoSettings {
    /// Every field's knob: range, unit, flag, help, widget (crate::knob).
    pub const KNOBS: &'static [Knob] = &[
        Knob::new(
            "vao.radius",
            "--vao-radius",
            "VAO sphere radius R in world units.",
            Kind::POSITIVE,
        )
        .aliases(&["--radius"])
        .length()
        .doc("VAO sphere radius R")
        .widget(Widget::RADIUS),
        Knob::new(
            "vao.thickness",
            "--vao-thickness",
            "VAO thickness τ (constant occluded area above the column, in units of R).",
            Kind::NON_NEGATIVE,
        )
        .aliases(&["--thickness"])
        .units("units of R")
        .doc("thickness τ of the fully occluding area above the sample column")
        .widget(Widget::Slider {
            min: 0.0,
            max: 2.0,
            log: false,
        }),
        Knob::new(
            "vao.exponent",
            "--vao-exponent",
            "VAO power applied to the final AO.",
            Kind::POSITIVE,
        )
        .aliases(&["--exponent"]),
        Knob::new(
            "vao.samples",
            "--vao-samples",
            "VAO line samples per pixel.",
            Kind::OneOf(&[8, 16, 32]),
        )
        .aliases(&["--samples"])
        .widget(Widget::Buttons),
        Knob::new(
            "vao.normalization",
            "--vao-normalization",
            "VAO normalisation: clipped (exact 1 on planes) or hemisphere (the paper's 2/N).",
            Kind::Choice(&["clipped", "hemisphere"]),
        )
        .aliases(&["--normalization"])
        .doc("clipped: exactly 1 on every unoccluded plane; hemisphere: the paper's 2/N"),
    ];
}

/// Base-2 van der Corput radical inverse of `i`.
pub fn van_der_corput(i: u32) -> f32 {
    (f64::from(i.reverse_bits()) / 4_294_967_296.0) as f32
}

/// Sample `i` of `n` before the per-pixel rotation: unit direction at angle 2πi/n and radius
/// `sqrt(1 - ψ^(2/3))` with ψ = van der Corput(n + i) (seed 000 Eq. 4–5, §7.1; offset n "skips 0"
/// as in the authors' code, giving 1/16, 9/16, 5/16, … for n = 8).
pub fn kernel_sample(i: u32, n: u32) -> (Vec2, f32) {
    let angle = TAU * i as f32 / n as f32;
    let psi = van_der_corput(n + i);
    let radius = (1.0 - psi.powf(2.0 / 3.0)).sqrt();
    (Vec2::new(angle.cos(), angle.sin()), radius)
}

/// 4×4 ordered-dither (Bayer) matrix, row-major; pixel (x, y) rotates its samples by
/// 2π·BAYER[x%4 + 4(y%4)]/16 (the 4×4 pattern of seed 000 §3.1; the values of the authors' 2024
/// code, docs/AUTHORS_CODE.md §2.2).
pub const BAYER_4X4: [u32; 16] = [0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5];

/// (cos, sin) of the rotation of pixel (x, y) of the visible image.
pub fn pixel_rotation(x: u32, y: u32) -> Vec2 {
    let a = TAU * BAYER_4X4[((x % 4) + 4 * (y % 4)) as usize] as f32 / 16.0;
    Vec2::new(a.cos(), a.sin())
}

/// Samples whose hemisphere-clipped column is shorter than this fraction of R are skipped
/// (seed 000 §3.2 "a_i = 0"; the authors' 2022 code used an absolute 0.01 world units, which
/// does not scale with the scene, so we make it relative to R).
pub const MIN_COLUMN_FRACTION: f32 = 0.01;

/// Orthonormal basis (t, b) perpendicular to unit `n`; Duff et al. 2017 (JCGT 6(1)), Listing 3.
/// Mirrors `orthonormal_basis` in `shaders/common/basis.wgsl`.
pub fn orthonormal_basis(n: Vec3) -> (Vec3, Vec3) {
    let s = if n.z >= 0.0 { 1.0 } else { -1.0 };
    let a = -1.0 / (s + n.z);
    let b = n.x * n.y * a;
    (
        Vec3::new(1.0 + s * n.x * n.x * a, s * b, -s * n.x),
        Vec3::new(b, s + n.y * n.y * a, -n.y),
    )
}

/// GPU mirror of `VaoParams` in `shaders/estimators/vao.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
pub struct VaoParams {
    radius: f32,
    thickness: f32,
    exponent: f32,
    _pad0: u32,
    min_column_fraction: f32,
    normalization: u32,
    _pad: [u32; 2],
    kernel: [[f32; 4]; 32],
    rotations: [[f32; 4]; 16],
}

impl VaoParams {
    /// The uniform for `s`: its radius, thickness, exponent and normalisation, the kernel of
    /// `s.samples` line samples and the 4×4 per-pixel rotation pattern.
    pub fn new(s: &VaoSettings) -> Self {
        let mut kernel = [[0.0; 4]; 32];
        for (i, k) in kernel.iter_mut().enumerate().take(s.samples as usize) {
            let (dir, r) = kernel_sample(i as u32, s.samples);
            // What the shader makes of the sample for every pixel, made here once: its offset on
            // the unit disc, its column's half height over R, sqrt(1 − r²) (r < 1), and the
            // reciprocal of that (so the weight 1/2h the AO sums take needs no division per
            // sample, vao.wgsl).
            let half_height = (1.0 - r * r).sqrt();
            *k = [dir.x * r, dir.y * r, half_height, 1.0 / half_height];
        }
        let mut rotations = [[0.0; 4]; 16];
        for (i, rot) in rotations.iter_mut().enumerate() {
            let c = pixel_rotation(i as u32 % 4, i as u32 / 4);
            *rot = [c.x, c.y, 0.0, 0.0];
        }
        Self {
            radius: s.radius,
            thickness: s.thickness,
            exponent: s.exponent,
            _pad0: 0,
            min_column_fraction: MIN_COLUMN_FRACTION,
            normalization: match s.normalization {
                Normalization::Hemisphere => 0,
                Normalization::Clipped => 1,
            },
            _pad: [0; 2],
            kernel,
            rotations,
        }
    }
}

/// The estimator's WGSL (the estimator contract, docs/ARCHITECTURE.md).
pub(crate) const WGSL: &str = include_str!("../../shaders/estimators/vao.wgsl");
/// Its `override` constants: the sample count (the loop unrolls).
pub(crate) const CONSTANTS: &[&str] = &["SAMPLE_COUNT"];

/// The estimator as the technique table runs it (`EstimatorCaps::module`).
pub const MODULE: super::EstimatorModule = super::EstimatorModule {
    wgsl: WGSL,
    constants: CONSTANTS,
    knobs: VaoSettings::KNOBS,
    params: |section, inputs| params(&super::section(section), inputs),
    table: None,
};

/// The parameter block (group 1) and the values of [`CONSTANTS`] for `settings`.
pub(crate) fn params(settings: &VaoSettings, _: &super::SourceInputs) -> (Vec<u8>, Vec<f64>) {
    (
        bytemuck::bytes_of(&VaoParams::new(settings)).to_vec(),
        vec![f64::from(settings.samples)],
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn radii_match_the_authors_table() {
        // docs/AUTHORS_CODE.md §1.3: sampleRadius[8] of the 2022 SVAO shader.
        let table = [
            0.917883, 0.564429, 0.734504, 0.359545, 0.820004, 0.470149, 0.650919, 0.205215,
        ];
        for (i, expected) in table.iter().enumerate() {
            let (_, r) = kernel_sample(i as u32, 8);
            assert!((r - expected).abs() < 1e-5, "sample {i}: {r} vs {expected}");
        }
        // 16 and 32 samples start at 0.949098… and 0.968246… (docs/AUTHORS_CODE.md §2.2).
        assert!((kernel_sample(0, 16).1 - 0.949098).abs() < 1e-5);
        assert!((kernel_sample(0, 32).1 - 0.968246).abs() < 1e-5);
    }

    #[test]
    fn basis_is_orthonormal() {
        for n in [
            Vec3::Z,
            -Vec3::Z,
            Vec3::X,
            Vec3::new(0.3, -0.5, 0.8).normalize(),
        ] {
            let (t, b) = orthonormal_basis(n);
            assert!((t.length() - 1.0).abs() < 1e-5 && (b.length() - 1.0).abs() < 1e-5);
            assert!(t.dot(b).abs() < 1e-5 && t.dot(n).abs() < 1e-5 && b.dot(n).abs() < 1e-5);
        }
    }
}
