//! The Volumetric Ambient Occlusion estimator (seed 000 §3.1–3.5): the sample kernel, the per-pixel
//! rotation pattern and the parameters of `shaders/estimators/vao.wgsl`. The same tables feed its
//! CPU mirror below: the sample geometry on the CPU ([`PixelFrame`], [`Column`], [`Accumulator`]),
//! which the ray-traced `vao` reference shares, and the kernel as plain Rust per pixel
//! ([`cpu_vao`], re-exported by `reference::cpu_vao` under its old path).

use super::mirror::{per_visible_pixel, MirrorGBuffer, MirrorScreen};
use crate::knob::{Kind, Knob, Widget};
use glam::{UVec2, Vec2, Vec3};
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

// ------------------------------------------------------------------------------ CPU mirror
// The sample geometry of seed 000 §3.1–3.3 on the CPU, shared by the kernel's mirror below
// (occluders from a depth buffer) and the ray-traced `vao` reference (`reference::ground_truth`,
// occluders from every ray hit).

/// Free length of the column `[end, start]` for an occluder at height `z` (Fig. 4 / Eq. 8).
pub fn column_visibility(s: &VaoSettings, z: f32, start: f32, end: f32) -> f32 {
    let length = start - end;
    let sphere_vis = (start - end.max(z)).max(0.0);
    let halo_start = (1.0 + s.thickness) * s.radius;
    let halo_vis = ((z - halo_start) / length).clamp(0.0, 1.0) * length;
    sphere_vis + halo_vis
}

/// One line sample: its hemisphere-clipped column and where it falls on screen.
pub struct Column {
    /// Lateral offset in the sample disc (tangent, bitangent), world units.
    pub d: Vec2,
    /// Half height of the full column.
    pub h: f32,
    /// Top of the clipped column: height along the view axis from the pixel's surface point,
    /// world units.
    pub start: f32,
    /// Bottom of the clipped column (where the tangent plane cuts it, or −`h`); `start − end` is
    /// its length.
    pub end: f32,
    /// Unclamped framebuffer pixel coordinates of the sample point.
    pub px: Vec2,
}

/// A visible pixel's sample frame: position, view axis, disc basis, normal in that frame.
pub struct PixelFrame {
    /// The pixel's surface point, view space.
    pub pos: Vec3,
    /// Unit view axis from the point towards the camera: the columns' direction.
    pub axis: Vec3,
    /// First axis of the sample disc, perpendicular to `axis`.
    pub tangent: Vec3,
    /// Second axis of the sample disc, perpendicular to `axis` and `tangent`.
    pub bitangent: Vec3,
    n_local: Vec3,
    inv_n_z: f32,
    rotation: Vec2,
}

impl PixelFrame {
    /// `pos`: view-space surface point; `n`: its view-space normal facing the camera;
    /// `x`, `y`: the visible pixel (selects the 4×4 rotation).
    pub fn new(pos: Vec3, n: Vec3, x: u32, y: u32) -> Self {
        let n = n.normalize();
        let axis = -pos.normalize();
        let (tangent, bitangent) = orthonormal_basis(axis);
        let n_local = Vec3::new(n.dot(tangent), n.dot(bitangent), n.dot(axis));
        let n_z = if n_local.z >= 0.0 {
            n_local.z.max(1e-4)
        } else {
            n_local.z.min(-1e-4)
        };
        Self {
            pos,
            axis,
            tangent,
            bitangent,
            n_local,
            inv_n_z: 1.0 / n_z,
            rotation: pixel_rotation(x, y),
        }
    }

    /// Sample `k` (unit direction before rotation, radius fraction) of the kernel, or `None` when
    /// its clipped column is too short to count (seed 000 §3.2: a_i = 0).
    pub fn column(
        &self,
        k: (Vec2, f32),
        s: &VaoSettings,
        screen: &dyn MirrorScreen,
    ) -> Option<Column> {
        let (dir, kr) = k;
        let rot = self.rotation;
        let dir = Vec2::new(dir.x * rot.x - dir.y * rot.y, dir.x * rot.y + dir.y * rot.x);
        let r = s.radius;
        let d = dir * (kr * r);
        let h = (r * r - d.dot(d)).max(0.0).sqrt();
        let z_i = (-d.dot(self.n_local.truncate()) * self.inv_n_z).clamp(-h, h);
        let (start, end) = if self.n_local.z >= 0.0 {
            (h, z_i)
        } else {
            (z_i, -h)
        };
        if start - end < MIN_COLUMN_FRACTION * r {
            return None;
        }
        let sample_pos = self.pos + self.tangent * d.x + self.bitangent * d.y;
        Some(Column {
            d,
            h,
            start,
            end,
            px: screen.view_to_pixel(sample_pos),
        })
    }

    /// Height of view-space point `p` in `column`'s frame: its height along the view axis,
    /// corrected along the tangent plane for its lateral offset from the column (vao.wgsl).
    pub fn height(&self, column: &Column, p: Vec3) -> f32 {
        let offset = p - self.pos;
        let lateral = Vec2::new(offset.dot(self.tangent), offset.dot(self.bitangent)) - column.d;
        offset.dot(self.axis) + lateral.dot(self.n_local.truncate()) * self.inv_n_z
    }

    /// How fast [`Self::height`] grows along view-space direction `d` (its linear part; vao.wgsl
    /// `column_height_slope`). Not the difference of two heights: that loses the slope to
    /// rounding where the heights are large next to it (a scene far from its camera in world
    /// units; tests/it/scale_invariance.rs).
    pub fn height_slope(&self, d: Vec3) -> f32 {
        let lateral = Vec2::new(d.dot(self.tangent), d.dot(self.bitangent));
        d.dot(self.axis) + lateral.dot(self.n_local.truncate()) * self.inv_n_z
    }
}

/// The per-pixel sums of free and clipped column fractions.
#[derive(Default)]
pub struct Accumulator {
    sum: f32,
    clipped_sum: f32,
}

impl Accumulator {
    /// Add one column: its free length `free` and its clipped length, each over its full length 2h.
    pub fn add(&mut self, column: &Column, free: f32) {
        let inv_2h = 0.5 / column.h;
        self.sum += free * inv_2h;
        self.clipped_sum += (column.start - column.end) * inv_2h;
    }

    /// Final AO with the normalisation and exponent of `s`.
    pub fn finish(&self, s: &VaoSettings) -> f32 {
        let raw = match s.normalization {
            Normalization::Hemisphere => 2.0 * self.sum / s.samples as f32,
            Normalization::Clipped if self.clipped_sum > 0.0 => self.sum / self.clipped_sum,
            Normalization::Clipped => 1.0,
        };
        raw.clamp(0.0, 1.0).powf(s.exponent)
    }
}

/// The kernel's samples for `s` (before rotation).
pub fn kernel(s: &VaoSettings) -> Vec<(Vec2, f32)> {
    (0..s.samples)
        .map(|i| kernel_sample(i, s.samples))
        .collect()
}

/// The framebuffer pixel a sample reads, and whether its projection lies within 1e-3 px of a
/// pixel edge (there float rounding may snap two implementations to different pixels).
pub fn snap(px: Vec2, screen: &dyn MirrorScreen) -> (UVec2, bool) {
    let full = screen.full_size().as_vec2();
    let px = px.clamp(Vec2::ZERO, full - 0.5);
    let frac = px - px.floor();
    let ambiguous = frac.min_element() < 1e-3 || frac.max_element() > 1.0 - 1e-3;
    (px.as_uvec2(), ambiguous)
}

/// What [`cpu_vao`] returns for every visible pixel (before blur).
pub struct CpuVao {
    /// AO per visible pixel, row-major, exponent applied (1 = unoccluded; background 1).
    pub ao: Vec<f32>,
    /// Pixels where some sample projects within `1e-3` px of a pixel edge: there float rounding
    /// may snap the GPU and the CPU to different neighbours, so the two may legitimately differ.
    pub ambiguous: Vec<bool>,
}

/// The CPU mirror: VAO as `vao.wgsl` computes it from the first depth layer (no blur), as plain
/// Rust per pixel of `g` drawn with `screen`, settings `s`: the oracle the GPU `vao` pass is
/// tested against. Returns the AO of every visible pixel and where a sample lay on a pixel edge
/// ([`CpuVao`]).
pub fn cpu_vao(g: &dyn MirrorGBuffer, screen: &dyn MirrorScreen, s: &VaoSettings) -> CpuVao {
    cpu_vao_turned(g, screen, s, 0)
}

/// [`cpu_vao`] with the 4×4 rotation pattern turned by `pattern_offset` entries, as the GPU
/// turns it per frame under temporal accumulation (`pattern_index` in common/pattern.wgsl).
pub fn cpu_vao_turned(
    g: &dyn MirrorGBuffer,
    screen: &dyn MirrorScreen,
    s: &VaoSettings,
    pattern_offset: u32,
) -> CpuVao {
    cpu_vao_with(g, screen, s, pattern_offset, 0.0)
}

/// [`cpu_vao_turned`] with the radius capped at `max_radius_px` pixels on screen (0: no cap;
/// `AoSettings::max_radius_px`): each pixel runs the kernel with its own R,
/// [`MirrorScreen::capped_radius`], as `vao.wgsl` does.
pub fn cpu_vao_with(
    g: &dyn MirrorGBuffer,
    screen: &dyn MirrorScreen,
    s: &VaoSettings,
    pattern_offset: u32,
    max_radius_px: f32,
) -> CpuVao {
    let kernel = kernel(s);
    let (ao, ambiguous) = per_visible_pixel(screen, |x, y| {
        let pixel = UVec2::new(x, y) + screen.guard_band();
        let z = g.depth_at(pixel);
        if z <= 0.0 {
            return (1.0, false);
        }
        let pos = screen.pixel_to_view(pixel.as_vec2() + 0.5, z);
        let s = &VaoSettings {
            radius: screen.capped_radius(s.radius, -pos.z, max_radius_px),
            ..*s
        };
        // The pattern entry this pixel uses, as the (x % 4, y % 4) that names it.
        let entry = (x % 4 + 4 * (y % 4) + pattern_offset) % 16;
        let frame = PixelFrame::new(pos, g.normal_at(pixel), entry % 4, entry / 4);
        let (mut acc, mut ambiguous) = (Accumulator::default(), false);
        for &k in &kernel {
            let Some(column) = frame.column(k, s, screen) else {
                continue;
            };
            let (sample_pixel, edge) = snap(column.px, screen);
            ambiguous |= edge;
            let mut free = column.start - column.end;
            if sample_pixel != pixel {
                let sz = g.depth_at(sample_pixel);
                if sz > 0.0 {
                    let occluder = screen.pixel_to_view(sample_pixel.as_vec2() + 0.5, sz);
                    free = column_visibility(
                        s,
                        frame.height(&column, occluder),
                        column.start,
                        column.end,
                    );
                }
            }
            acc.add(&column, free);
        }
        (acc.finish(s), ambiguous)
    });
    CpuVao { ao, ambiguous }
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
