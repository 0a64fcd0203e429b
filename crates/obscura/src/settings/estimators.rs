//! The estimators' parameters (VAO, HBAO, GTAO, the depth pyramid, Pyramid HBAO, SAO, SSAO,
//! HBAO+, GTAO-VB) and the bilateral blur's.

use super::*;
use crate::knob::{Kind, Knob, Widget};

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

impl FromStr for Normalization {
    type Err = SettingsError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim().to_ascii_lowercase().as_str() {
            "hemisphere" | "paper" => Ok(Normalization::Hemisphere),
            "clipped" => Ok(Normalization::Clipped),
            _ => Err(invalid(
                "vao.normalization",
                s,
                "must be 'clipped' (default) or 'hemisphere' (the paper's 2/N)",
            )),
        }
    }
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

/// The most `hbao.directions` (the parameter block's direction table; seed 004's largest grid is
/// 64 × 80).
pub const HBAO_MAX_DIRECTIONS: u32 = 64;

/// The most `gtao.slices` (the parameter block's slice table).
pub const GTAO_MAX_SLICES: u32 = 16;

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

/// The depth pyramid (seed 004 §3.3) that `sao` and `pyramid-hbao` read: levels of linear depth,
/// each texel the mean of K × K texels of the level below.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct PyramidSettings {
    /// L, the levels, the depth buffer (level 0) included: 1 to 8 (seed 004: 1 … 5, default 5).
    /// More levels reach farther: `pyramid-hbao` walks every level.
    pub levels: u32,
    /// K, texels of a level per texel of the next along each axis: 2 to 4 (seed 004: 3).
    pub factor: u32,
}

impl Default for PyramidSettings {
    fn default() -> Self {
        Self {
            levels: 5,
            factor: 3,
        }
    }
}

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

/// Scalable Ambient Obscurance parameters (McGuire et al. 2012; defaults of its published code:
/// 11 taps on 7 spiral turns, bias 0.01, intensity 1).
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
    /// Scale of the summed obscurance, in world units: under SAO's shipped normalisation
    /// intensity/R⁶ · 5/N the sum has the dimension of an inverse length, which the intensity
    /// cancels ([`crate::AoSettings::scaled`] scales it with the radii).
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

/// How a sample's angular span turns into sectors of the visibility bitmask (seed 003).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SectorActivation {
    /// A sector the span touches.
    #[default]
    Ceil,
    /// A sector the span covers at least half of.
    Round,
    /// A sector the span covers whole.
    Floor,
}

impl FromStr for SectorActivation {
    type Err = SettingsError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim().to_ascii_lowercase().as_str() {
            "ceil" => Ok(SectorActivation::Ceil),
            "round" => Ok(SectorActivation::Round),
            "floor" => Ok(SectorActivation::Floor),
            _ => Err(invalid(
                "gtao_vb.activation",
                s,
                "must be 'ceil' (default), 'round' or 'floor'",
            )),
        }
    }
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
    /// Which sectors a sample's angular span sets (default [`SectorActivation::Ceil`]).
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
            activation: SectorActivation::Ceil,
            cosine_weighted: false,
        }
    }
}

/// Depth-aware separable blur (seed 000 §3.4, HBAO+ weights).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct BlurSettings {
    /// Whether the blur runs at all; `false` outputs the estimator's unfiltered AO.
    pub enabled: bool,
    /// Taps on each side.
    pub radius: u32,
    /// Depth weight sharpness per world unit of depth difference (0: a plain Gaussian).
    pub sharpness: f32,
    /// σ in pixels of a natural Gaussian spatial weight, exp(−d²/2σ²); left out (the default),
    /// HBAO+'s weight exp2(−d²/2σ'²) with σ' = (radius + 1)/2 (docs/AUTHORS_CODE.md §1.8). Seed
    /// 004's filter for Pyramid HBAO is `radius = 2, sharpness = 0, sigma = 1.5`.
    pub sigma: Option<f32>,
}

impl Default for BlurSettings {
    fn default() -> Self {
        Self {
            enabled: true,
            radius: 4,
            sharpness: 16.0,
            sigma: None,
        }
    }
}

impl BlurSettings {
    /// The spatial weight's exponent per squared pixel of distance, in exp2 units: the weight of
    /// a tap d pixels away is exp2(−d²·falloff).
    pub fn falloff(&self) -> f32 {
        match self.sigma {
            Some(sigma) => 1.0 / (2.0 * sigma * sigma * std::f32::consts::LN_2),
            None => {
                let sigma = (self.radius as f32 + 1.0) * 0.5;
                1.0 / (2.0 * sigma * sigma)
            }
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

/// The viewer's radius slider: 1/1000 of the scene's size to all of it, logarithmic.
const RADIUS_SLIDER: Widget = Widget::Slider {
    min: 1e-3,
    max: 1.0,
    log: true,
};

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
        .widget(RADIUS_SLIDER),
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
        .widget(RADIUS_SLIDER),
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

impl GtaoSettings {
    /// Every field's knob: range, unit, flag, help, widget (crate::knob).
    pub const KNOBS: &'static [Knob] = &[
        Knob::new("gtao.radius", "--gtao-radius", "GTAO radius R in world units.", Kind::POSITIVE)
            .length()
            .doc(
                "GTAO radius R (as XeGTAO: samples reach 1.457·R, full weight up to 0.56·R, none \
                 beyond 1.457·R)",
            )
            .widget(RADIUS_SLIDER),
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

impl PyramidSettings {
    /// Every field's knob: range, unit, flag, help, widget (crate::knob).
    pub const KNOBS: &'static [Knob] = &[
        Knob::new(
            "pyramid.levels",
            "--pyramid-levels",
            "Depth pyramid levels L, the depth buffer included: sao, pyramid-hbao.",
            Kind::int(1, 8),
        )
        .doc(
            "L, levels of the depth pyramid, the depth buffer (level 0) included (seed 004: 1 … 5); \
             `pyramid-hbao` walks every level, so more levels reach farther",
        ),
        Knob::new(
            "pyramid.factor",
            "--pyramid-factor",
            "Depth pyramid factor K: each texel the mean of K × K below.",
            Kind::int(2, 4),
        )
        .doc("K: each texel of a level the mean of K × K texels below (seed 004: 3)"),
    ];
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
        .widget(RADIUS_SLIDER),
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

impl SaoSettings {
    /// Every field's knob: range, unit, flag, help, widget (crate::knob).
    pub const KNOBS: &'static [Knob] = &[
        Knob::new("sao.radius", "--sao-radius", "SAO radius R in world units.", Kind::POSITIVE)
            .length()
            .doc("SAO radius R (taps up to R on screen, falloff (R² − d²)³)")
            .widget(RADIUS_SLIDER),
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
            "SAO intensity (scale of the obscurance), in world units as SAO's normalisation has it.",
            Kind::POSITIVE,
        )
        .length()
        .doc(
            "scale of the summed obscurance (A = 1 − intensity/R⁶ · 5/N · Σ, SAO's shipped \
             normalisation, whose sum has the dimension of an inverse length: the intensity is a \
             length, scaled with the radii)",
        ),
    ];
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
        .widget(RADIUS_SLIDER),
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
        .widget(RADIUS_SLIDER),
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

impl GtaoVbSettings {
    /// Every field's knob: range, unit, flag, help, widget (crate::knob).
    pub const KNOBS: &'static [Knob] = &[
        Knob::new("gtao_vb.radius", "--gtao-vb-radius", "GTAO-VB search radius R in world units.", Kind::POSITIVE)
            .aliases(&["--vb-radius"])
            .length()
            .widget(RADIUS_SLIDER),
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

impl BlurSettings {
    /// Every field's knob: range, unit, flag, help, widget (crate::knob).
    pub const KNOBS: &'static [Knob] = &[
        Knob::new(
            "blur.enabled",
            "--no-blur",
            "Skip the bilateral blur (blurred by default).",
            Kind::Switch { flag_sets: false },
        )
        .doc("the depth-aware bilateral blur")
        .widget(Widget::Checkbox),
        Knob::new("blur.radius", "--blur-radius", "Bilateral blur taps on each side.", Kind::int(1, 16))
            .widget(Widget::Range),
        Knob::new(
            "blur.sharpness",
            "--blur-sharpness",
            "Bilateral blur depth sharpness (per world unit of depth difference).",
            Kind::NON_NEGATIVE,
        )
        .per_length()
        .doc("blur depth-weight sharpness"),
        Knob::new(
            "blur.sigma",
            "--blur-sigma",
            "σ in pixels of a natural Gaussian spatial weight; seed 004's filter is --blur-radius 2 \
             --blur-sharpness 0 --blur-sigma 1.5.",
            Kind::POSITIVE,
        )
        .units("pixels")
        .auto("HBAO+'s weights")
        .doc(
            "σ of a natural Gaussian spatial weight; left out (the default), HBAO+'s weights with \
             σ' = (radius + 1)/2 in exp2 units. Seed 004's Gaussian for Pyramid HBAO: \
             `--blur-radius 2 --blur-sharpness 0 --blur-sigma 1.5`",
        ),
    ];
}
