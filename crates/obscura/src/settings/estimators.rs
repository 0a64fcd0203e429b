//! The depth pyramid's parameters (the source `sao` and `pyramid-hbao` read) and the bilateral
//! blur's. Each estimator's own settings live in its module (`src/estimators/`).

use super::*;
use crate::knob::{Kind, Knob, Widget};

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

/// The edge-avoiding à-trous denoiser made for AO (src/filter/atrous.rs): in the blur's place
/// when enabled (off by default).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct DenoiseSettings {
    /// Whether it runs (then the bilateral blur does not).
    pub enabled: bool,
    /// À-trous iterations at most, taps 1, 2, 4, … pixels apart (2 reach 6 px on each side); a
    /// pixel stops earlier where its reach is enough (`samples`, the AO radius on screen).
    pub iterations: u32,
    /// How many of a pixel's local standard deviations of AO a neighbour may differ by and still
    /// count (SVGF's σ_l).
    pub sigma: f32,
    /// Hemisphere rows: the samples of visibility (rays × frames of history) a pixel's filtered
    /// value should rest on; a pixel stops widening once its footprint holds about this many.
    pub samples: f32,
}

impl Default for DenoiseSettings {
    fn default() -> Self {
        Self {
            enabled: false,
            // Five iterations, as Schied et al. 2017 (§4.4), as a cap: each pixel stops widening
            // once its footprint holds `samples` rays or reaches R/4 on screen (atrous.wgsl,
            // `within_reach`), so how far it reaches follows its history, the resolution and
            // the AO radius rather than a fixed count. σ = 8: at one ray a pixel the spatial
            // variance is too coarse a guide for SVGF's σ = 4. 256 rays: noise of at most
            // 0.5/√256 ≈ 0.03 in a pixel's AO. Measured on lavapipe after 16 frames of one ray,
            // Sponza at 960×540: 256 rays 0.0161 MAE, 512 and 1024 0.0143; but at 512 a pixel
            // with 256 rays of its own is still filtered, which added error where the image is
            // small (tests/it/hemisphere.rs, 32 frames of 8 rays at 96×64: stairs 0.0066 →
            // 0.0086), and at 256 it is left alone.
            iterations: 5,
            sigma: 8.0,
            samples: 256.0,
        }
    }
}

impl DenoiseSettings {
    /// Every field's knob: range, unit, flag, help, widget (crate::knob).
    pub const KNOBS: &'static [Knob] = &[
        Knob::new(
            "denoise.enabled",
            "--denoise",
            "Denoise with the edge-avoiding à-trous filter made for AO instead of the bilateral \
             blur (for the noisy hemisphere rows, with or without --temporal).",
            Kind::Switch { flag_sets: true },
        )
        .doc(
            "the edge-avoiding à-trous denoiser in the blur's place: depth-, normal- and \
             variance-stopped, so it weakens where the AO is already smooth (a long history)",
        )
        .widget(Widget::Checkbox),
        Knob::new(
            "denoise.iterations",
            "--denoise-iterations",
            "Denoiser iterations (taps 1, 2, 4, ... px apart).",
            Kind::int(1, 5),
        )
        .doc(
            "à-trous iterations at most, taps 1, 2, 4, … pixels apart (2 reach 6 px on each \
             side); each pixel stops where its footprint holds `denoise.samples` rays or reaches \
             a quarter of the AO radius on screen",
        )
        .widget(Widget::Range),
        Knob::new(
            "denoise.sigma",
            "--denoise-sigma",
            "Denoiser: local standard deviations of AO a neighbour may differ by.",
            Kind::POSITIVE,
        )
        .doc("how many local standard deviations of AO a neighbour may differ by (SVGF uses 4)"),
        Knob::new(
            "denoise.samples",
            "--denoise-samples",
            "Denoiser, hemisphere rows: the rays (over a pixel's frames of history) its filtered \
             value should rest on; it widens no further once its footprint holds this many.",
            Kind::POSITIVE,
        )
        .doc(
            "hemisphere rows: the rays × frames a pixel's filtered value should rest on; each \
             iteration widens the footprint about 4×, none once the pixel's own history holds \
             this many",
        ),
    ];
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

// The estimators' own names for their choices, parsed where settings errors live (the
// estimators know nothing of settings errors).
impl FromStr for Normalization {
    type Err = SettingsError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim().to_ascii_lowercase().as_str() {
            "hemisphere" | "paper" => Ok(Normalization::Hemisphere),
            "clipped" => Ok(Normalization::Clipped),
            _ => Err(SettingsError::Invalid {
                field: "vao.normalization",
                value: s.to_string(),
                rule: "must be 'clipped' (default) or 'hemisphere' (the paper's 2/N)".into(),
            }),
        }
    }
}

impl FromStr for SectorActivation {
    type Err = SettingsError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim().to_ascii_lowercase().as_str() {
            "ceil" => Ok(SectorActivation::Ceil),
            "round" => Ok(SectorActivation::Round),
            "floor" => Ok(SectorActivation::Floor),
            _ => Err(SettingsError::Invalid {
                field: "gtao_vb.activation",
                value: s.to_string(),
                rule: "must be 'ceil' (default), 'round' or 'floor'".into(),
            }),
        }
    }
}
