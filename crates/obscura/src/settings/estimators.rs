//! The estimators' parameters (VAO, HBAO, GTAO, the depth pyramid, Pyramid HBAO, SAO, SSAO,
//! HBAO+, GTAO-VB) and the bilateral blur's.

use super::*;

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
