//! What a user chooses: the technique and its parameters. Defaults are the papers' / authors'.

pub use crate::technique::{Technique, UnknownTechnique};
use std::fmt;
use std::str::FromStr;

#[derive(Debug, thiserror::Error, PartialEq)]
pub enum SettingsError {
    #[error(transparent)]
    UnknownTechnique(#[from] UnknownTechnique),
    #[error("invalid {name} {value}: {rule}")]
    Invalid {
        name: &'static str,
        value: String,
        rule: &'static str,
    },
}

/// Volumetric AO parameters (seed 000; defaults from the authors' 2022 code, seed-code-notes §1.2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VaoSettings {
    /// Sphere radius R in world units.
    pub radius: f32,
    /// Thickness τ of the constant (fully occluding) area above the sample column, in units of R.
    pub thickness: f32,
    /// Power applied to the final AO.
    pub exponent: f32,
    /// Line samples per pixel: 8, 16 or 32.
    pub samples: u32,
    pub normalization: Normalization,
}

/// How VAO turns the free column lengths into AO (see `shaders/vao.wgsl`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Normalization {
    /// Seed 000 Eq. 7 with the hemisphere factor 2: `2/N Σ free/2h`. Exactly 1 on an unoccluded
    /// plane only on average over the 4×4 rotation pattern.
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
                "normalization",
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

/// Depth-aware separable blur (seed 000 §3.4, HBAO+ weights).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BlurSettings {
    pub enabled: bool,
    /// Taps on each side.
    pub radius: u32,
    /// Depth weight sharpness per world unit of depth difference.
    pub sharpness: f32,
}

impl Default for BlurSettings {
    fn default() -> Self {
        Self {
            enabled: true,
            radius: 4,
            sharpness: 16.0,
        }
    }
}

/// The stratified stochastic depth map (seed 001 §3.1, Alg. 1).
///
/// Defaults are the authors' 2022 values (S = 4, α = 0.2: seed 000 §4.1 and its scripts,
/// seed-code-notes §1.5). Their 2024 code used α = 1.5/S instead (0.375 for S = 4,
/// seed-code-notes §2.2); pass `--sd-alpha 0.375` for that.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StochasticDepthSettings {
    /// Depth samples per pixel, S: 1, 2, 4, 8 or 16. Counts the adapter cannot rasterise in one
    /// multisampled target are made of several maps stacked (each with its own seed).
    pub samples: u32,
    /// Global transparency α in (0, 1]: a hidden fragment is stored in ⌊αS + ξ⌋ samples.
    pub alpha: f32,
    /// Seed of the per-fragment hash (ξ and the choice of samples).
    pub seed: u32,
    /// `sd-svao`: how the map is limited to the pixels phase 1 requested.
    pub mask: SdMask,
}

/// How `sd-svao` rasterises its stochastic depth map only where phase 1 asked for it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SdMask {
    /// The paper's way (seed 000 §3.9): a full-screen pass copies the request mask into the
    /// map's stencil, then the scene is drawn with the stencil test.
    #[default]
    Stencil,
    /// No stencil: the map's fragment shader reads the request mask and discards where it is
    /// not set (saves the full-screen copy pass; the fragments are still rasterised).
    Discard,
}

impl FromStr for SdMask {
    type Err = SettingsError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim().to_ascii_lowercase().as_str() {
            "stencil" => Ok(SdMask::Stencil),
            "discard" => Ok(SdMask::Discard),
            _ => Err(invalid(
                "sd mask",
                s,
                "must be 'stencil' (default, the paper's) or 'discard'",
            )),
        }
    }
}

impl fmt::Display for SdMask {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            SdMask::Stencil => "stencil",
            SdMask::Discard => "discard",
        })
    }
}

impl Default for StochasticDepthSettings {
    fn default() -> Self {
        Self {
            samples: 4,
            alpha: 0.2,
            seed: 0,
            mask: SdMask::Stencil,
        }
    }
}

/// Depth samples per pixel the stochastic depth map accepts (before the adapter's own limits).
pub const SD_SAMPLE_COUNTS: [u32; 5] = [1, 2, 4, 8, 16];

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AoSettings {
    pub technique: Technique,
    pub vao: VaoSettings,
    pub blur: BlurSettings,
    /// `vao-dual`: the second layer is the nearest surface more than this many world units behind
    /// the first (the authors' `minSeparationDistance`, seed-code-notes §2.1).
    /// Also the minimum distance behind the first layer for a fragment to enter the stochastic
    /// depth map (`sd-vao`, `sd-svao`).
    pub peel_separation: f32,
    pub stochastic_depth: StochasticDepthSettings,
}

impl Default for AoSettings {
    fn default() -> Self {
        Self {
            technique: Technique::default(),
            vao: VaoSettings::default(),
            blur: BlurSettings::default(),
            peel_separation: 0.01,
            stochastic_depth: StochasticDepthSettings::default(),
        }
    }
}

fn invalid(name: &'static str, value: impl fmt::Display, rule: &'static str) -> SettingsError {
    SettingsError::Invalid {
        name,
        value: value.to_string(),
        rule,
    }
}

impl AoSettings {
    /// Reject values no kernel can use; every message names the setting and the valid range.
    pub fn validate(&self) -> Result<(), SettingsError> {
        let v = &self.vao;
        if !(v.radius.is_finite() && v.radius > 0.0) {
            return Err(invalid(
                "radius",
                v.radius,
                "must be a positive number of world units (e.g. --radius 0.5)",
            ));
        }
        if !(v.thickness.is_finite() && v.thickness >= 0.0) {
            return Err(invalid(
                "thickness",
                v.thickness,
                "must be zero or positive (e.g. --thickness 0.5)",
            ));
        }
        if !(v.exponent.is_finite() && v.exponent > 0.0) {
            return Err(invalid(
                "exponent",
                v.exponent,
                "must be positive (e.g. --exponent 1.3)",
            ));
        }
        if ![8, 16, 32].contains(&v.samples) {
            return Err(invalid("sample count", v.samples, "must be 8, 16 or 32"));
        }
        if !(self.peel_separation.is_finite() && self.peel_separation >= 0.0) {
            return Err(invalid(
                "peel separation",
                self.peel_separation,
                "must be zero or positive (e.g. --peel-separation 0.01)",
            ));
        }
        let sd = &self.stochastic_depth;
        if !SD_SAMPLE_COUNTS.contains(&sd.samples) {
            return Err(invalid(
                "stochastic depth sample count",
                sd.samples,
                "must be 1, 2, 4, 8 or 16 (e.g. --sd-samples 4)",
            ));
        }
        if !(sd.alpha > 0.0 && sd.alpha <= 1.0) {
            return Err(invalid(
                "stochastic depth alpha",
                sd.alpha,
                "must be in (0, 1] (e.g. --sd-alpha 0.2)",
            ));
        }
        let b = &self.blur;
        if b.radius == 0 || b.radius > 16 {
            return Err(invalid("blur radius", b.radius, "must be between 1 and 16"));
        }
        if !(b.sharpness.is_finite() && b.sharpness >= 0.0) {
            return Err(invalid(
                "blur sharpness",
                b.sharpness,
                "must be zero or positive",
            ));
        }
        Ok(())
    }
}
