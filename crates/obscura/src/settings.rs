//! What a user chooses: the technique and its parameters, as data. Defaults are the papers' /
//! authors'; [`Preset`]s are per technique; settings files are JSON or TOML
//! ([`AoSettings::from_file`]); `docs/SETTINGS.md` documents every field.

use crate::technique::{Estimator, Source};
pub use crate::technique::{Technique, UnknownTechnique};
use serde::{Deserialize, Serialize};
use std::fmt;
use std::path::{Path, PathBuf};
use std::str::FromStr;

/// What can be wrong with settings. Messages name settings *fields* by their path in a settings
/// file (`vao.radius`, `stochastic_depth.alpha`), never a command-line flag: the CLI maps fields
/// to its flags itself.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum SettingsError {
    /// A `technique` name that is not a row of the technique table.
    #[error(transparent)]
    UnknownTechnique(#[from] UnknownTechnique),
    /// A value no kernel can use.
    #[error("invalid {field} {value}: {rule}")]
    Invalid {
        /// The field's path, as in a settings file: `vao.radius`, `blur.radius`,
        /// `stochastic_depth.alpha`, `peel_separation`, … (one of [`AoSettings::field_paths`]).
        field: &'static str,
        /// The rejected value, as given.
        value: String,
        /// What a valid value is, with an example; no command-line flags.
        rule: &'static str,
    },
    /// A valid value the adapter cannot do (e.g. a stochastic depth sample count it cannot
    /// rasterise), with what it can do.
    #[error("{field} {value} is not supported on adapter '{adapter}': {reason}")]
    Unsupported {
        /// The field's path, as for [`SettingsError::Invalid`].
        field: &'static str,
        /// The value asked for, as given.
        value: String,
        /// The adapter's name.
        adapter: String,
        /// Why, and the values that work here.
        reason: String,
    },
    /// A preset name that is not one of [`Preset::ALL`].
    #[error("unknown preset '{0}': use low, medium, high or ultra")]
    UnknownPreset(String),
    /// A settings file whose extension says neither JSON nor TOML.
    #[error(
        "settings file '{}' is neither .json nor .toml: name it *.toml or *.json (the format is \
         chosen by the extension)",
        path.display()
    )]
    UnknownFormat {
        /// The settings file.
        path: PathBuf,
    },
    /// A settings file that cannot be read.
    #[error("cannot read settings file '{}': {message}: check the path", path.display())]
    Read {
        /// The settings file.
        path: PathBuf,
        /// The operating system's error.
        message: String,
    },
    /// A settings file that is not valid JSON/TOML, has a value of the wrong type or names a
    /// field that does not exist (`line`/`column` where the parser says, 1-based).
    #[error(
        "settings file '{}'{}: {message} (fix the file; its fields are listed in docs/SETTINGS.md)",
        path.display(),
        at(*line, *column)
    )]
    Parse {
        /// The settings file.
        path: PathBuf,
        /// The line the parser points at, 1-based; `None` where it cannot tell.
        line: Option<usize>,
        /// The column on that line, 1-based; `None` where the parser cannot tell.
        column: Option<usize>,
        /// The parser's message, without the position (`line`, `column` give it).
        message: String,
    },
    /// A settings file that parses but whose values do not validate.
    #[error("settings file '{}': {source}", path.display())]
    InFile {
        /// The settings file.
        path: PathBuf,
        /// What [`AoSettings::validate`] rejected in the file's values.
        source: Box<SettingsError>,
    },
}

fn at(line: Option<usize>, column: Option<usize>) -> String {
    match (line, column) {
        (Some(l), Some(c)) => format!(", line {l}, column {c}"),
        (Some(l), None) => format!(", line {l}"),
        _ => String::new(),
    }
}

/// Volumetric AO parameters (seed 000; defaults from the authors' 2022 code, seed-code-notes §1.2).
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
    /// Scale of the summed obscurance.
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
/// (seed-code-notes §1.7: 8 directions × 4 steps, R 1.0, NdotV bias 0.1, exponent 2).
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
    /// HBAO+'s weight exp2(−d²/2σ'²) with σ' = (radius + 1)/2 (seed-code-notes §1.8). Seed 004's
    /// filter for Pyramid HBAO is `radius = 2, sharpness = 0, sigma = 1.5`.
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

/// The stratified stochastic depth map (seed 001 §3.1, Alg. 1).
///
/// Defaults: S = 4 and α = 1.5/S (0.375 at S = 4), the authors' 2024 rule (seed-code-notes
/// §2.2; DESIGN.md). Held against an outside renderer's ground truth, α = 1.5/S gave a lower MSE
/// than the authors' 2022 α = 0.2 on every view tried (1.04× to 7.6×), and 0.2 lost to depth
/// peeling on one; 0.2 stays reachable (`alpha = 0.2`, `--sd-alpha 0.2`) to reproduce the 2022
/// tables.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct StochasticDepthSettings {
    /// Depth samples per pixel, S: 1, 2, 4, 8 or 16 (on every adapter: the map is a storage
    /// buffer).
    pub samples: u32,
    /// Global transparency α in (0, 1]: a hidden fragment is stored in ⌊αS + ξ⌋ samples. `None`
    /// (the default; a file that leaves it out, JSON `null`, `--sd-alpha auto`): 1.5/S, at most
    /// 1 ([`StochasticDepthSettings::alpha`]).
    pub alpha: Option<f32>,
    /// Seed of the per-fragment hash (ξ and the choice of samples).
    pub seed: u32,
    /// `sd-svao`: how the map is limited to the pixels phase 1 requested.
    pub mask: SdMask,
    /// When a sample reads the map: only where the first layer cannot decide (the default, seed
    /// 001 §3.3's query heuristic), or for every sample that finds a surface (to measure what the
    /// heuristic saves and costs).
    pub query: SdQuery,
    /// Missing-occlusion compensation (seed 001 §4, Figs. 7–8): the occlusion each stochastic
    /// sample contributes is multiplied by this factor, in [1, 8]; 1 (the default) is off, the
    /// paper used 2 for its Figs. 7–8. Makes up for occluders the few samples miss behind many
    /// layers, and overshoots where the samples missed nothing.
    pub compensation: f32,
    /// Which hidden fragments each pixel of the raster map keeps: a stochastic subset (the
    /// default, seed 001 Alg. 1) or the S nearest (ours). The ray-traced map has its reservoir.
    pub selection: SdSelection,
    /// The raster map's own guard band in pixels (ours; seed 002 §3.5 gives the ray-traced map
    /// one): the map is rasterised this far beyond the framebuffer on every side, every layer
    /// there, so samples that fall off the framebuffer read it instead of the framebuffer's edge.
    /// 0 (the default) is off; at most 2048. It widens the map's raster pass by that much.
    pub guard_band: u32,
    /// What rasterises the map: compute passes (ours) where the GPU allows them (the default),
    /// or the GPU's rasteriser.
    pub rasterizer: SdRasterizer,
}

/// When a stochastic-depth technique reads the map for a sample (seed 001 §3.3). In files:
/// `"needed"`, `"first-layer"` or `"always"`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SdQuery {
    /// Only where the estimator says the first surface may hide more ("needs hidden depth?");
    /// for SSAO also only where a deeper surface on the sample's camera ray could occlude at all,
    /// for GTAO-VB only where one could mark a sector still free (exact tests: the same image as
    /// `FirstLayer`, fewer reads).
    #[default]
    Needed,
    /// Seed 001 §3.3 as worded: wherever the first surface does not decide (for SSAO: does not
    /// occlude), without the exact tests of SSAO and GTAO-VB (to measure what they save). The
    /// same as `Needed` for the other estimators.
    FirstLayer,
    /// For every sample whose pixel shows a surface.
    Always,
}

impl FromStr for SdQuery {
    type Err = SettingsError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim().to_ascii_lowercase().as_str() {
            "needed" => Ok(SdQuery::Needed),
            "first-layer" => Ok(SdQuery::FirstLayer),
            "always" => Ok(SdQuery::Always),
            _ => Err(invalid(
                "stochastic_depth.query",
                s,
                "must be 'needed' (default, seed 001 §3.3), 'first-layer' or 'always'",
            )),
        }
    }
}

/// Which hidden fragments a pixel of the raster stochastic depth map keeps in its S depths. In
/// files: `"stochastic"` or `"nearest"`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SdSelection {
    /// Seed 001 Alg. 1: each fragment behind the first layer is stored in ⌊αS + ξ⌋ of the S
    /// samples, chosen by a hash, and each sample keeps the nearest fragment that chose it: every
    /// hidden layer has a chance, whatever lies in front of it, at the price of noise.
    #[default]
    Stochastic,
    /// Ours: the S nearest distinct depths behind the first layer, with no hash and no α (a
    /// k-buffer kept by chains of `atomicMax`, whose result does not depend on the order the
    /// fragments arrive in). Exact wherever a pixel hides at most S layers, so it neither
    /// flickers nor loses a layer there; where more lie behind the first, the deepest are lost
    /// every time (the stochastic map would keep each with some chance).
    Nearest,
}

impl FromStr for SdSelection {
    type Err = SettingsError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim().to_ascii_lowercase().as_str() {
            "stochastic" => Ok(SdSelection::Stochastic),
            "nearest" => Ok(SdSelection::Nearest),
            _ => Err(invalid(
                "stochastic_depth.selection",
                s,
                "must be 'stochastic' (default, seed 001 Alg. 1) or 'nearest' (the S nearest hidden layers)",
            )),
        }
    }
}

impl fmt::Display for SdSelection {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            SdSelection::Stochastic => "stochastic",
            SdSelection::Nearest => "nearest",
        })
    }
}

/// What rasterises the stochastic depth map. In files: `"auto"`, `"hardware"` or `"compute"`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SdRasterizer {
    /// `Compute` where the device binds the storage buffers it needs and is not a CPU
    /// (software) adapter, else `Hardware`. Why: on an H200 the compute map took a quarter of
    /// the hardware map's time on every view measured; on lavapipe (the CPU) a Sponza frame took
    /// 3.5× longer with it (BENCHMARKS.md, 2026-12-05). A renderer reports the one it chose
    /// ([`crate::Renderer::settings`]).
    #[default]
    Auto,
    /// The GPU's rasteriser, every fragment shaded by `map.wgsl` after early depth (and
    /// stencil) tests.
    Hardware,
    /// Ours: compute passes clip, bin and rasterise the triangles (pixel centres, corners
    /// snapped to 1/256 pixel, the top-left rule), handing each fragment to the same Alg. 1
    /// code; the hardware draws only triangles that do not fit the passes' buffers. The map
    /// holds the same fragments up to rounding (`compute_raster.rs`' tests bound the
    /// difference); for GPUs whose raster units are slow next to their compute.
    Compute,
}

impl FromStr for SdRasterizer {
    type Err = SettingsError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim().to_ascii_lowercase().as_str() {
            "auto" => Ok(SdRasterizer::Auto),
            "hardware" => Ok(SdRasterizer::Hardware),
            "compute" => Ok(SdRasterizer::Compute),
            _ => Err(invalid(
                "stochastic_depth.rasterizer",
                s,
                "must be 'auto' (default: compute passes where the GPU allows them), 'hardware' \
                 (the GPU's rasteriser) or 'compute' (compute passes)",
            )),
        }
    }
}

impl fmt::Display for SdRasterizer {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            SdRasterizer::Auto => "auto",
            SdRasterizer::Hardware => "hardware",
            SdRasterizer::Compute => "compute",
        })
    }
}

/// How `sd-svao` rasterises its stochastic depth map only where phase 1 asked for it. In files:
/// `"stencil"`, `"depth"` or `"discard"`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SdMask {
    /// The paper's way (seed 000 §3.9): a full-screen pass copies the request mask into the
    /// map's stencil, then the scene is drawn with the stencil test, before shading where the
    /// device has early tests.
    Stencil,
    /// The request mask folded into the depth the map is early-tested against: the reset
    /// writes the far plane at the pixels nobody requested, which no fragment lies behind, so
    /// the depth test alone rejects them before shading, as the stencil does. The reset needs no
    /// `discard` and the target no stencil aspect (any adapter; the same image). The default:
    /// faster than the stencil on every scene measured (BENCHMARKS.md, issue 16).
    #[default]
    Depth,
    /// No stencil: the map's fragment shader reads the request mask and returns where it is
    /// not set (the fragments are still shaded; the same image).
    Discard,
}

impl FromStr for SdMask {
    type Err = SettingsError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim().to_ascii_lowercase().as_str() {
            "stencil" => Ok(SdMask::Stencil),
            "depth" => Ok(SdMask::Depth),
            "discard" => Ok(SdMask::Discard),
            _ => Err(invalid(
                "stochastic_depth.mask",
                s,
                "must be 'depth' (default), 'stencil' (the paper's) or 'discard'",
            )),
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

impl fmt::Display for SdMask {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            SdMask::Stencil => "stencil",
            SdMask::Depth => "depth",
            SdMask::Discard => "discard",
        })
    }
}

impl StochasticDepthSettings {
    /// The α in use: the one given, else 1.5/S capped at 1.
    pub fn alpha(&self) -> f32 {
        self.alpha.unwrap_or_else(|| sd_alpha_2024(self.samples))
    }
}

impl AoSettings {
    /// These settings with every rule-derived value written out (α = 1.5/S as a number), for
    /// records that must say what ran (bench and compare JSON).
    pub fn resolved(&self) -> AoSettings {
        let mut s = *self;
        s.stochastic_depth.alpha = Some(s.stochastic_depth.alpha());
        s
    }
}

impl Default for StochasticDepthSettings {
    fn default() -> Self {
        Self {
            samples: 4,
            alpha: None,
            seed: 0,
            mask: SdMask::Depth,
            query: SdQuery::Needed,
            compensation: 1.0,
            selection: SdSelection::Stochastic,
            guard_band: 0,
            rasterizer: SdRasterizer::Auto,
        }
    }
}

/// Depth samples per pixel the stochastic depth map accepts (before the adapter's own limits).
pub const SD_SAMPLE_COUNTS: [u32; 5] = [1, 2, 4, 8, 16];

/// The ray-traced stochastic depth map (`ray-sd-vao`; seed 002 §3.1): one camera ray per pixel
/// through the BVH keeps `reservoir` of the depths behind the first layer by reservoir sampling.
/// A hit must lie `peel_separation` behind the first layer, as for the raster map. Defaults: the
/// paper's N = 4, MAX_COUNT = 8, z-culling on.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RaySdSettings {
    /// Depth slots per pixel, N, in [1, 8].
    pub reservoir: u32,
    /// Hits a ray handles before it stops (MAX_COUNT), in [N, 64].
    pub max_count: u32,
    /// A slot is overwritten only by a nearer depth (the paper's z-culling; it favours near
    /// layers). Off: plain reservoir sampling, every hit kept with probability N/count.
    pub z_cull: bool,
    /// Seed of the reservoir's hash (per map; `stochastic_depth.seed` is the raster map's).
    pub seed: u32,
    /// The map's resolution divisor: 1 (a ray per pixel), 2 or 4 (a ray per 2×2 or 4×4 pixels,
    /// through a jittered point of its block; seed 002 §3.3).
    pub resolution: u32,
    /// Radius cutoff in pixels (seed 002 §3.4; the paper's t = 6): a sample nearer than this to
    /// its shading pixel keeps the first layer's answer and never requests the map. 0: off (the
    /// default, so the map is read wherever the raster map's rows read theirs).
    pub radius_cutoff: f32,
    /// Ray intervals (seed 002 §3.2, the authors' default): on a two-phase schedule a ray is
    /// traced only over the depths phase 1's samples need there. Off: from the first layer to the
    /// scene's end.
    pub intervals: bool,
    /// The map's own guard band in pixels (seed 002 §3.5): the map reaches this far beyond the
    /// framebuffer (its guard band included), in ⌈g / resolution⌉ texels, so a sample that falls
    /// off the framebuffer reads the map there instead of the framebuffer's edge; those texels
    /// hold every layer (no first layer is known there) and are traced only where requested on
    /// a two-phase schedule (a one-pass row traces all of them). 0: no band. `None` (the
    /// default; a file that leaves it out, JSON `null`, `--sd-guard-band auto`): the authors'
    /// 512 px at 1080p, scaled with the visible height, on two-phase rows, and none on one-pass
    /// rows ([`RaySdSettings::guard_band_for`]).
    pub guard_band: Option<u32>,
}

impl Default for RaySdSettings {
    fn default() -> Self {
        Self {
            reservoir: 4,
            max_count: 8,
            z_cull: true,
            seed: 0,
            resolution: 1,
            radius_cutoff: 0.0,
            intervals: true,
            guard_band: None,
        }
    }
}

impl RaySdSettings {
    /// Checks the ranges above.
    pub fn validate(&self) -> Result<(), SettingsError> {
        if !(1..=8).contains(&self.reservoir) {
            return Err(invalid(
                "ray_sd.reservoir",
                self.reservoir,
                "must be in [1, 8] depth slots per pixel, e.g. 4",
            ));
        }
        if !(self.reservoir..=64).contains(&self.max_count) {
            return Err(invalid(
                "ray_sd.max_count",
                self.max_count,
                "must be at least ray_sd.reservoir and at most 64, e.g. 8",
            ));
        }
        if ![1, 2, 4].contains(&self.resolution) {
            return Err(invalid(
                "ray_sd.resolution",
                self.resolution,
                "must be 1, 2 or 4 (the map's resolution divisor)",
            ));
        }
        if !(self.radius_cutoff.is_finite() && self.radius_cutoff >= 0.0) {
            return Err(invalid(
                "ray_sd.radius_cutoff",
                self.radius_cutoff,
                "must be zero (off) or a positive number of pixels, e.g. 6",
            ));
        }
        if let Some(band) = self.guard_band.filter(|&b| b > MAX_SD_GUARD_BAND) {
            return Err(invalid(
                "ray_sd.guard_band",
                band,
                "must be at most 2048 pixels beyond the framebuffer, e.g. 512 (seed 002 §3.5) or 0 (off)",
            ));
        }
        Ok(())
    }

    /// The map's guard band in pixels for a `visible_height` image, on a two-phase schedule or
    /// not: `guard_band`, or where that is `None`, 512 px at 1080p scaled with the height and
    /// rounded up to a multiple of 4 (whole texels at 1/4 resolution) on two-phase schedules,
    /// where only requested band texels are traced, and 0 on one-pass schedules, which would
    /// trace every band texel each frame (at 1080p + 64 px, 2.8× the rays of the framebuffer).
    pub fn guard_band_for(&self, visible_height: u32, two_phase: bool) -> u32 {
        self.guard_band.unwrap_or_else(|| {
            if two_phase {
                let scaled = 512.0 * f64::from(visible_height) / 1080.0;
                (scaled / 4.0).ceil() as u32 * 4
            } else {
                0
            }
        })
    }
}

/// The widest map guard band `ray_sd.guard_band` accepts (four times the authors' 512).
const MAX_SD_GUARD_BAND: u32 = 2048;

/// Everything a technique's kernels read, as data: every field has a default (the papers' /
/// authors' values), and settings files (JSON or TOML, [`AoSettings::from_file`]) name the same
/// fields, nested as here (`vao.radius`, `stochastic_depth.alpha`, …). A file may give any subset;
/// an unknown field is an error. `docs/SETTINGS.md` lists every field.
///
/// ```
/// use obscura::settings::{AoSettings, Preset};
/// use obscura::Technique;
///
/// let mut s = AoSettings::preset("gtao-vb".parse::<Technique>()?, Preset::High);
/// s.gtao_vb.radius = 0.75;
/// s.validate()?;
/// // α = 1.5/S unless given: 0.375 at the default S = 4.
/// assert_eq!(s.stochastic_depth.alpha(), 0.375);
///
/// s.vao.radius = -1.0;
/// let err = s.validate().unwrap_err().to_string();
/// assert!(err.contains("vao.radius"), "{err}"); // errors name the field
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct AoSettings {
    /// Which row of the technique table runs (estimator × hidden-depth source × schedule); default
    /// `vao`.
    pub technique: Technique,
    /// The VAO estimator (`vao`, `vao-dual`, `rt-vao`, `rt-svao`, `rt-svao-dense`, `sd-vao`,
    /// `sd-svao`).
    pub vao: VaoSettings,
    /// The bilateral blur that filters every technique's raw AO.
    pub blur: BlurSettings,
    /// `vao-dual`: the second layer is the nearest surface more than this many world units behind
    /// the first (the authors' `minSeparationDistance`, seed-code-notes §2.1).
    /// Also the minimum distance behind the first layer for a fragment to enter the stochastic
    /// depth map (`sd-vao`, `sd-svao`).
    pub peel_separation: f32,
    /// The stochastic depth map (`sd-vao`, `sd-svao`).
    pub stochastic_depth: StochasticDepthSettings,
    /// The ray-traced stochastic depth map (`ray-sd-vao`).
    pub ray_sd: RaySdSettings,
    /// The classic HBAO estimator (`hbao`, `hbao-dual`).
    pub hbao: HbaoSettings,
    /// The HBAO+ estimator (`hbao+`, `hbao+-dual`).
    pub hbao_plus: HbaoPlusSettings,
    /// The GTAO estimator (`gtao`).
    pub gtao: GtaoSettings,
    /// The depth pyramid (`sao`, `pyramid-hbao`).
    pub pyramid: PyramidSettings,
    /// The Pyramid HBAO estimator (`pyramid-hbao`).
    pub pyramid_hbao: PyramidHbaoSettings,
    /// The Scalable Ambient Obscurance estimator (`sao`).
    pub sao: SaoSettings,
    /// The SSAO (Alchemy AO) estimator (`ssao`).
    pub ssao: SsaoSettings,
    /// The visibility-bitmask estimator (`gtao-vb`, `gtao-vb-dual`).
    pub gtao_vb: GtaoVbSettings,
    /// Where the technique runs: at the inputs' resolution, or at half of it in each axis and
    /// brought back by a depth-aware upsample (seed 001 Tab. 1–2; every technique can).
    pub resolution: Resolution,
    /// The AO radius's cap on screen, in pixels of the output image (seed 002 §3.5; the
    /// authors' `ssMaxRadius`): where a shading point's radius R would cover more
    /// pixels (a surface close to the camera), R is shrunk for that pixel to cover exactly this
    /// many, so the kernel keeps its shape. Every estimator honours it; the ground truths never
    /// do. 0 (the default): no cap. The authors pair 512 px with their map's 512 px guard band
    /// at 1080p, so that samples never fall beyond the map; it costs accuracy near the camera
    /// (measured: docs/SETTINGS.md), so it is off unless asked for.
    pub max_radius_px: f32,
    /// Also write the bent normal, the mean unoccluded direction, next to the AO (seed 001 §4,
    /// Fig. 9): view space, unit length, for the techniques whose estimator reports one (GTAO,
    /// GTAO-VB, VAO, HBAO+ and their dual and stochastic-depth rows), on the single-pass schedule
    /// at full resolution.
    pub bent_normals: bool,
    /// The multi-view schedule's second view (`sd-hbao+-multiview`).
    pub multiview: MultiviewSettings,
    /// Temporal accumulation of the AO over frames (off by default).
    pub temporal: TemporalSettings,
}

/// Temporal accumulation (issue 13; src/filter/temporal.rs): before the blur, each pixel's AO is
/// averaged with its history from the previous frames, reprojected by depth and camera motion,
/// and the estimators turn their 4×4 sample pattern by one entry per frame, so a still camera
/// converges to the mean over all 16 rotations. History is rejected where the surface differs
/// (disocclusion): its depth or normal is out of tolerance.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct TemporalSettings {
    /// Whether the pass runs (and the pattern turns per frame).
    pub enabled: bool,
    /// The most frames averaged: a running mean up to this many, then an exponential blend with
    /// weight 1/frames. 16 covers the pattern's 16 rotations once.
    pub frames: u32,
    /// Relative depth difference within which the history holds the same surface.
    pub depth_tolerance: f32,
    /// Degrees between normals within which the history holds the same surface.
    pub normal_tolerance_deg: f32,
    /// Clip the history to mean ± σ of this frame's AO at the pixel and its four neighbours (as
    /// engines' TAA does): screen-space AO changes with the view (halos move with parallax), and
    /// without the clamp that change lags `frames` frames behind.
    pub clamp: bool,
}

impl Default for TemporalSettings {
    fn default() -> Self {
        Self {
            enabled: false,
            frames: 16,
            depth_tolerance: 0.03,
            normal_tolerance_deg: 30.0,
            clamp: true,
        }
    }
}

/// The second view of the multi-view schedule (seed 001 §3.4: "at a set distance to the side of
/// the original camera, and angled such that the original camera frustum is fully covered"; the
/// paper gives no numbers, so the rule is ours): the camera swung by `angle` about its up axis
/// around the focus point `focus` ahead of it, looking at that point, its field of view widened by
/// twice the angle (at most 150°) so the camera's frustum stays in view.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct MultiviewSettings {
    /// Degrees between the two views' axes, in (0, 60].
    pub angle: f32,
    /// Distance (world units) from the camera to the point both views look at; `None` (the
    /// default): the distance along the view axis to the scene's bounding-box centre.
    pub focus: Option<f32>,
    /// The second view's map and pass: at the camera's resolution or at half of it.
    pub resolution: Resolution,
}

impl Default for MultiviewSettings {
    fn default() -> Self {
        Self {
            angle: 30.0,
            focus: None,
            resolution: Resolution::Full,
        }
    }
}

/// The resolution a technique's passes run at (`resolution`; in files `"full"` or `"half"`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Resolution {
    /// The inputs' resolution.
    #[default]
    Full,
    /// Half the width and height (a quarter of the pixels): the depth and normals are reduced
    /// 2×2 → 1, the source, schedule and blur run there, and a depth-aware upsample writes the
    /// full-size output (src/filter/half_resolution.rs). Needs an even visible size and guard band.
    Half,
}

impl FromStr for Resolution {
    type Err = SettingsError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim().to_ascii_lowercase().as_str() {
            "full" => Ok(Resolution::Full),
            "half" => Ok(Resolution::Half),
            _ => Err(invalid(
                "resolution",
                s,
                "must be 'full' (default) or 'half'",
            )),
        }
    }
}

impl fmt::Display for Resolution {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Resolution::Full => "full",
            Resolution::Half => "half",
        })
    }
}

impl Default for AoSettings {
    fn default() -> Self {
        Self {
            technique: Technique::default(),
            hbao: HbaoSettings::default(),
            hbao_plus: HbaoPlusSettings::default(),
            gtao: GtaoSettings::default(),
            pyramid: PyramidSettings::default(),
            pyramid_hbao: PyramidHbaoSettings::default(),
            sao: SaoSettings::default(),
            ssao: SsaoSettings::default(),
            gtao_vb: GtaoVbSettings::default(),
            vao: VaoSettings::default(),
            blur: BlurSettings::default(),
            peel_separation: 0.01,
            stochastic_depth: StochasticDepthSettings::default(),
            ray_sd: RaySdSettings::default(),
            resolution: Resolution::Full,
            max_radius_px: 0.0,
            bent_normals: false,
            multiview: MultiviewSettings::default(),
            temporal: TemporalSettings::default(),
        }
    }
}

fn invalid(field: &'static str, value: impl fmt::Display, rule: &'static str) -> SettingsError {
    SettingsError::Invalid {
        field,
        value: value.to_string(),
        rule,
    }
}

impl AoSettings {
    /// Reject values no kernel can use; every message names the field (`vao.radius`) and the
    /// valid range. Every rule is about one field alone.
    pub fn validate(&self) -> Result<(), SettingsError> {
        let v = &self.vao;
        if !(v.radius.is_finite() && v.radius > 0.0) {
            return Err(invalid(
                "vao.radius",
                v.radius,
                "must be a positive number of world units, e.g. 0.5",
            ));
        }
        if !(v.thickness.is_finite() && v.thickness >= 0.0) {
            return Err(invalid(
                "vao.thickness",
                v.thickness,
                "must be zero or positive, e.g. 0.5",
            ));
        }
        if !(v.exponent.is_finite() && v.exponent > 0.0) {
            return Err(invalid(
                "vao.exponent",
                v.exponent,
                "must be positive, e.g. 1.3",
            ));
        }
        if ![8, 16, 32].contains(&v.samples) {
            return Err(invalid("vao.samples", v.samples, "must be 8, 16 or 32"));
        }
        let cap = self.max_radius_px;
        if !(cap == 0.0 || (1.0..=1e6).contains(&cap)) {
            return Err(invalid(
                "max_radius_px",
                cap,
                "must be 0 (no cap) or from 1 to 1e6 pixels, e.g. 512 (seed 002 §3.5)",
            ));
        }
        if !(self.peel_separation.is_finite() && self.peel_separation >= 0.0) {
            return Err(invalid(
                "peel_separation",
                self.peel_separation,
                "must be zero or positive (world units), e.g. 0.01",
            ));
        }
        let sd = &self.stochastic_depth;
        if !SD_SAMPLE_COUNTS.contains(&sd.samples) {
            return Err(invalid(
                "stochastic_depth.samples",
                sd.samples,
                "must be 1, 2, 4, 8 or 16, e.g. 4",
            ));
        }
        if let Some(alpha) = sd.alpha.filter(|a| !(*a > 0.0 && *a <= 1.0)) {
            return Err(invalid(
                "stochastic_depth.alpha",
                alpha,
                "must be in (0, 1], e.g. 0.375, or left out for 1.5/S",
            ));
        }
        self.ray_sd.validate()?;
        let mv = &self.multiview;
        if !(mv.angle.is_finite() && mv.angle > 0.0 && mv.angle <= 60.0) {
            return Err(invalid(
                "multiview.angle",
                mv.angle,
                "must be in (0, 60] degrees, e.g. 30",
            ));
        }
        if let Some(focus) = mv.focus.filter(|f| !(f.is_finite() && *f > 0.0)) {
            return Err(invalid(
                "multiview.focus",
                focus,
                "must be a positive distance in world units, or left out for the scene's centre",
            ));
        }
        if !(sd.compensation.is_finite() && (1.0..=8.0).contains(&sd.compensation)) {
            return Err(invalid(
                "stochastic_depth.compensation",
                sd.compensation,
                "must be in [1, 8]: 1 is off, the paper used 2",
            ));
        }
        if sd.guard_band > MAX_SD_GUARD_BAND {
            return Err(invalid(
                "stochastic_depth.guard_band",
                sd.guard_band,
                "must be at most 2048 pixels (0 is off)",
            ));
        }
        let h = &self.hbao;
        if !(h.radius.is_finite() && h.radius > 0.0) {
            return Err(invalid(
                "hbao.radius",
                h.radius,
                "must be a positive number of world units, e.g. 0.5",
            ));
        }
        if !(h.angle_bias.is_finite() && (0.0..std::f32::consts::FRAC_PI_2).contains(&h.angle_bias))
        {
            return Err(invalid(
                "hbao.angle_bias",
                h.angle_bias,
                "must be in [0, π/2) radians, e.g. 0.1",
            ));
        }
        if !(h.exponent.is_finite() && h.exponent > 0.0) {
            return Err(invalid(
                "hbao.exponent",
                h.exponent,
                "must be positive, e.g. 1",
            ));
        }
        if !(1..=HBAO_MAX_DIRECTIONS).contains(&h.directions) {
            return Err(invalid(
                "hbao.directions",
                h.directions,
                "must be 1 to 64, e.g. 8",
            ));
        }
        if !(1..=128).contains(&h.steps) {
            return Err(invalid("hbao.steps", h.steps, "must be 1 to 128, e.g. 4"));
        }
        let g = &self.gtao;
        if !(g.radius.is_finite() && g.radius > 0.0) {
            return Err(invalid(
                "gtao.radius",
                g.radius,
                "must be a positive number of world units, e.g. 0.5",
            ));
        }
        if !(g.thickness_blend.is_finite() && (0.0..=1.0).contains(&g.thickness_blend)) {
            return Err(invalid(
                "gtao.thickness_blend",
                g.thickness_blend,
                "must be in [0, 1], e.g. 0 (the plain maximum horizon)",
            ));
        }
        if !(g.exponent.is_finite() && g.exponent > 0.0) {
            return Err(invalid(
                "gtao.exponent",
                g.exponent,
                "must be positive, e.g. 1",
            ));
        }
        if !(1..=GTAO_MAX_SLICES).contains(&g.slices) {
            return Err(invalid("gtao.slices", g.slices, "must be 1 to 16, e.g. 2"));
        }
        if !(1..=32).contains(&g.steps) {
            return Err(invalid("gtao.steps", g.steps, "must be 1 to 32, e.g. 2"));
        }
        let py = &self.pyramid;
        if !(1..=8).contains(&py.levels) {
            return Err(invalid(
                "pyramid.levels",
                py.levels,
                "must be 1 to 8, e.g. 5",
            ));
        }
        if !(2..=4).contains(&py.factor) {
            return Err(invalid(
                "pyramid.factor",
                py.factor,
                "must be 2, 3 or 4, e.g. 3",
            ));
        }
        let ph = &self.pyramid_hbao;
        if !(ph.radius.is_finite() && ph.radius > 0.0) {
            return Err(invalid(
                "pyramid_hbao.radius",
                ph.radius,
                "must be a positive number of world units, e.g. 0.5",
            ));
        }
        if !(ph.exponent.is_finite() && ph.exponent > 0.0) {
            return Err(invalid(
                "pyramid_hbao.exponent",
                ph.exponent,
                "must be positive, e.g. 1",
            ));
        }
        if !(1..=32).contains(&ph.directions) {
            return Err(invalid(
                "pyramid_hbao.directions",
                ph.directions,
                "must be 1 to 32, e.g. 8",
            ));
        }
        if !(1..=16).contains(&ph.steps) {
            return Err(invalid(
                "pyramid_hbao.steps",
                ph.steps,
                "must be 1 to 16, e.g. 4",
            ));
        }
        let sao = &self.sao;
        if !(sao.radius.is_finite() && sao.radius > 0.0) {
            return Err(invalid(
                "sao.radius",
                sao.radius,
                "must be a positive number of world units, e.g. 0.5",
            ));
        }
        if !(1..=64).contains(&sao.samples) {
            return Err(invalid(
                "sao.samples",
                sao.samples,
                "must be 1 to 64, e.g. 11",
            ));
        }
        if !(sao.spiral_turns.is_finite() && sao.spiral_turns > 0.0) {
            return Err(invalid(
                "sao.spiral_turns",
                sao.spiral_turns,
                "must be positive, e.g. 7",
            ));
        }
        if !(sao.bias.is_finite() && sao.bias >= 0.0) {
            return Err(invalid(
                "sao.bias",
                sao.bias,
                "must be zero or positive world units, e.g. 0.01",
            ));
        }
        if !(sao.intensity.is_finite() && sao.intensity > 0.0) {
            return Err(invalid(
                "sao.intensity",
                sao.intensity,
                "must be positive, e.g. 1",
            ));
        }
        let ss = &self.ssao;
        if !(ss.radius.is_finite() && ss.radius > 0.0) {
            return Err(invalid(
                "ssao.radius",
                ss.radius,
                "must be a positive number of world units, e.g. 0.5",
            ));
        }
        if !(1..=32).contains(&ss.samples) {
            return Err(invalid(
                "ssao.samples",
                ss.samples,
                "must be 1 to 32 (one bit per sample), e.g. 32",
            ));
        }
        if !(ss.intensity.is_finite() && ss.intensity > 0.0) {
            return Err(invalid(
                "ssao.intensity",
                ss.intensity,
                "must be positive, e.g. 1",
            ));
        }
        if !(ss.bias.is_finite() && ss.bias >= 0.0) {
            return Err(invalid(
                "ssao.bias",
                ss.bias,
                "must be zero or positive, e.g. 0.0001",
            ));
        }
        if !(ss.contrast.is_finite() && ss.contrast > 0.0) {
            return Err(invalid(
                "ssao.contrast",
                ss.contrast,
                "must be positive, e.g. 1",
            ));
        }
        let h = &self.hbao_plus;
        if !(h.radius.is_finite() && h.radius > 0.0) {
            return Err(invalid(
                "hbao_plus.radius",
                h.radius,
                "must be a positive number of world units, e.g. 1.0",
            ));
        }
        if !(h.bias.is_finite() && (0.0..1.0).contains(&h.bias)) {
            return Err(invalid(
                "hbao_plus.bias",
                h.bias,
                "must be in [0, 1), e.g. 0.1",
            ));
        }
        if !(h.exponent.is_finite() && h.exponent > 0.0) {
            return Err(invalid(
                "hbao_plus.exponent",
                h.exponent,
                "must be positive, e.g. 2",
            ));
        }
        if !(1..=32).contains(&h.directions) {
            return Err(invalid(
                "hbao_plus.directions",
                h.directions,
                "must be 1 to 32, e.g. 8",
            ));
        }
        if h.steps == 0 || h.directions * h.steps > 32 {
            return Err(invalid(
                "hbao_plus.steps",
                h.steps,
                "must be at least 1 with directions × steps ≤ 32 (one bit per sample), e.g. 4",
            ));
        }
        let g = &self.gtao_vb;
        if !(g.radius.is_finite() && g.radius > 0.0) {
            return Err(invalid(
                "gtao_vb.radius",
                g.radius,
                "must be a positive number of world units, e.g. 0.5",
            ));
        }
        if !(g.thickness.is_finite() && g.thickness >= 0.0) {
            return Err(invalid(
                "gtao_vb.thickness",
                g.thickness,
                "must be zero or positive world units, e.g. 0.25",
            ));
        }
        if !(g.exponent.is_finite() && g.exponent > 0.0) {
            return Err(invalid(
                "gtao_vb.exponent",
                g.exponent,
                "must be positive, e.g. 1",
            ));
        }
        if !(1..=3).contains(&g.slices) {
            return Err(invalid(
                "gtao_vb.slices",
                g.slices,
                "must be 1, 2 or 3 (one 32-bit mask each), e.g. 2",
            ));
        }
        if g.steps == 0 || g.slices * 2 * g.steps > 32 {
            return Err(invalid(
                "gtao_vb.steps",
                g.steps,
                "must be at least 1 with slices × 2 × steps ≤ 32 (one bit per sample), e.g. 2",
            ));
        }
        let t = &self.temporal;
        if !(1..=255).contains(&t.frames) {
            return Err(invalid(
                "temporal.frames",
                t.frames,
                "must be between 1 and 255, e.g. 16",
            ));
        }
        if !(t.depth_tolerance > 0.0 && t.depth_tolerance < 1.0) {
            return Err(invalid(
                "temporal.depth_tolerance",
                t.depth_tolerance,
                "must be a fraction of the depth in (0, 1), e.g. 0.03",
            ));
        }
        if !(t.normal_tolerance_deg > 0.0 && t.normal_tolerance_deg <= 180.0) {
            return Err(invalid(
                "temporal.normal_tolerance_deg",
                t.normal_tolerance_deg,
                "must be degrees in (0, 180], e.g. 30",
            ));
        }
        let b = &self.blur;
        if b.radius == 0 || b.radius > 16 {
            return Err(invalid("blur.radius", b.radius, "must be between 1 and 16"));
        }
        if !(b.sharpness.is_finite() && b.sharpness >= 0.0) {
            return Err(invalid(
                "blur.sharpness",
                b.sharpness,
                "must be zero or positive",
            ));
        }
        if let Some(sigma) = b.sigma.filter(|s| !(s.is_finite() && *s > 0.0)) {
            return Err(invalid(
                "blur.sigma",
                sigma,
                "must be a positive number of pixels, e.g. 1.5, or left out for HBAO+'s weights",
            ));
        }
        Ok(())
    }

    /// The world radius R of the technique's estimator (`vao.radius`, `hbao.radius`, …).
    pub fn radius(&self) -> f32 {
        let mut copy = *self;
        *copy.radius_mut()
    }

    /// [`Self::radius`], to change.
    pub fn radius_mut(&mut self) -> &mut f32 {
        match self.technique.estimator() {
            Estimator::Vao => &mut self.vao.radius,
            Estimator::Hbao => &mut self.hbao.radius,
            Estimator::HbaoPlus => &mut self.hbao_plus.radius,
            Estimator::Gtao => &mut self.gtao.radius,
            Estimator::GtaoVb => &mut self.gtao_vb.radius,
            Estimator::Ssao => &mut self.ssao.radius,
            Estimator::Sao => &mut self.sao.radius,
            Estimator::PyramidHbao => &mut self.pyramid_hbao.radius,
        }
    }

    /// The settings field that holds [`Self::radius`] (`vao.radius`, `hbao.radius`, …).
    pub fn radius_field(&self) -> &'static str {
        match self.technique.estimator() {
            Estimator::Vao => "vao.radius",
            Estimator::Hbao => "hbao.radius",
            Estimator::HbaoPlus => "hbao_plus.radius",
            Estimator::Gtao => "gtao.radius",
            Estimator::GtaoVb => "gtao_vb.radius",
            Estimator::Ssao => "ssao.radius",
            Estimator::Sao => "sao.radius",
            Estimator::PyramidHbao => "pyramid_hbao.radius",
        }
    }

    /// The path of every field, as settings files and [`SettingsError::Invalid`] name them
    /// (`technique`, `vao.radius`, …, `stochastic_depth.mask`), sorted.
    pub fn field_paths() -> Vec<String> {
        fn walk(prefix: &str, value: &serde_json::Value, out: &mut Vec<String>) {
            match value {
                serde_json::Value::Object(map) => {
                    for (key, v) in map {
                        let path = if prefix.is_empty() {
                            key.clone()
                        } else {
                            format!("{prefix}.{key}")
                        };
                        walk(&path, v, out);
                    }
                }
                _ => out.push(prefix.to_string()),
            }
        }
        let mut out = Vec::new();
        walk("", &to_value(&AoSettings::default()), &mut out);
        out
    }
}

fn to_value(settings: &AoSettings) -> serde_json::Value {
    serde_json::to_value(settings).expect("AoSettings serialises to JSON")
}

// ------------------------------------------------------------------------------------ presets

/// A quality level: [`AoSettings::preset`] says per technique what each sets.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Preset {
    /// The cheapest: blur radius 2 (VAO, HBAO+), fewer samples (HBAO 4 × 4, HBAO+ 4 directions,
    /// GTAO and GTAO-VB 1 × 2) and one stochastic depth sample per pixel.
    Low,
    /// The defaults ([`AoSettings::default`]) for every technique.
    #[default]
    Medium,
    /// More samples than the defaults where the estimator has room (VAO 16, HBAO 8 × 10, GTAO
    /// and GTAO-VB 3 × 3).
    High,
    /// The most samples (VAO 32, HBAO 16 × 20, GTAO 9 × 3, GTAO-VB 3 × 5, S = 8) and, for VAO
    /// and HBAO+, blur radius 6.
    Ultra,
}

impl Preset {
    /// Every preset, cheapest first.
    pub const ALL: [Preset; 4] = [Preset::Low, Preset::Medium, Preset::High, Preset::Ultra];

    /// The preset's name in settings files and on the command line (`low` … `ultra`).
    pub fn name(self) -> &'static str {
        match self {
            Preset::Low => "low",
            Preset::Medium => "medium",
            Preset::High => "high",
            Preset::Ultra => "ultra",
        }
    }
}

impl fmt::Display for Preset {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Preset {
    type Err = SettingsError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let wanted = s.trim().to_ascii_lowercase();
        Preset::ALL
            .into_iter()
            .find(|p| p.name() == wanted)
            .ok_or_else(|| SettingsError::UnknownPreset(s.to_string()))
    }
}

/// α of the authors' 2024 code (seed-code-notes §2.2): 1.5/S, so that a hidden fragment is kept
/// in 1.5 of its pixel's S samples on average whatever S is (at most 1).
pub fn sd_alpha_2024(samples: u32) -> f32 {
    (1.5 / samples as f32).min(1.0)
}

impl AoSettings {
    /// The settings of `technique` at a quality level: [`AoSettings::default`] with the fields
    /// below changed, chosen by the axes of the technique's row (estimator, hidden-depth source;
    /// the schedule changes nothing: a two-phase technique gets the settings of its single-pass
    /// twin, so that both give the same image). Every other field keeps its default: a preset
    /// never changes the scene-dependent radius, thickness, exponent, normalisation, peel
    /// separation or blur sharpness, nor the seed or `sd-svao`'s mask (and the guard band is not
    /// a setting at all). `Medium` is exactly [`AoSettings::default`] for every technique.
    ///
    /// Per estimator and source (docs/SETTINGS.md has the table with every column): VAO
    /// `vao.samples` 8, 8, 16, 32 and `blur.radius` 2, 4, 4, 6; HBAO+ 4 × 4 directions × steps
    /// at low, else 8 × 4, `blur.radius` as VAO; HBAO directions × steps 4×4, 8×4, 8×10, 16×20;
    /// GTAO slices × steps 1×2, 2×2, 3×3, 9×3; GTAO-VB 1×2, 2×2, 3×3, 3×5; the
    /// stochastic depth map S = 1, 4, 4, 8 with α = 1.5/S throughout (at most 1: at S = 1 the
    /// nearest hidden surface).
    ///
    /// `low` keeps to one sample per pixel, which every adapter with the map's format rasterises
    /// (WebGPU guarantees 1× and 4× multisampling only).
    pub fn preset(technique: Technique, preset: Preset) -> AoSettings {
        let row = technique.row();
        let mut s = AoSettings {
            technique,
            ..AoSettings::default()
        };
        match row.estimator {
            Estimator::Vao => match preset {
                Preset::Low => {
                    s.vao.samples = 8;
                    s.blur.radius = 2;
                }
                Preset::Medium => {}
                Preset::High => s.vao.samples = 16,
                Preset::Ultra => {
                    s.vao.samples = 32;
                    s.blur.radius = 6;
                }
            },
            // 8 × 4 = 32 samples is already the most the two-phase mask holds.
            Estimator::HbaoPlus => match preset {
                Preset::Low => {
                    s.hbao_plus.directions = 4;
                    s.blur.radius = 2;
                }
                Preset::Medium | Preset::High => {}
                Preset::Ultra => s.blur.radius = 6,
            },
            // Seed 001 Tab. 1's 8 × 4 as the default, seed 004's smallest grid (8 × 10) as high.
            Estimator::Hbao => {
                let (directions, steps) = match preset {
                    Preset::Low => (4, 4),
                    Preset::Medium => (8, 4),
                    Preset::High => (8, 10),
                    Preset::Ultra => (16, 20),
                };
                s.hbao.directions = directions;
                s.hbao.steps = steps;
            }
            // The common XeGTAO-style grid, slices × steps 1×2, 2×2, 3×3, 9×3.
            Estimator::Gtao => {
                let (slices, steps) = match preset {
                    Preset::Low => (1, 2),
                    Preset::Medium => (2, 2),
                    Preset::High => (3, 3),
                    Preset::Ultra => (9, 3),
                };
                s.gtao.slices = slices;
                s.gtao.steps = steps;
            }
            // Seed 004's 8 directions as the default; the steps per level are ours.
            Estimator::PyramidHbao => {
                let (directions, steps) = match preset {
                    Preset::Low => (4, 3),
                    Preset::Medium => (8, 4),
                    Preset::High => (8, 6),
                    Preset::Ultra => (16, 6),
                };
                s.pyramid_hbao.directions = directions;
                s.pyramid_hbao.steps = steps;
            }
            // Seed 001 Tab. 1's 32 as the default, the most the two-phase mask holds.
            Estimator::Ssao => {
                s.ssao.samples = match preset {
                    Preset::Low => 8,
                    Preset::Medium | Preset::High | Preset::Ultra => 32,
                };
            }
            // SAO's published code ships 11 taps; fewer and more around it.
            Estimator::Sao => {
                s.sao.samples = match preset {
                    Preset::Low => 7,
                    Preset::Medium => 11,
                    Preset::High => 16,
                    Preset::Ultra => 32,
                };
            }
            // The common GTAO grid (slices × steps 1×2, 2×2, 3×3) as far as three slices and 32
            // samples allow: ultra is 3 × 5 instead of 9 × 3.
            Estimator::GtaoVb => {
                let (slices, steps) = match preset {
                    Preset::Low => (1, 2),
                    Preset::Medium => (2, 2),
                    Preset::High => (3, 3),
                    Preset::Ultra => (3, 5),
                };
                s.gtao_vb.slices = slices;
                s.gtao_vb.steps = steps;
            }
        }
        match row.source {
            Source::StochasticDepth => {
                let sd = &mut s.stochastic_depth;
                match preset {
                    // One sample: every adapter with the format rasterises it (WebGPU
                    // guarantees 1× and 4× only). α stays 1.5/S throughout.
                    Preset::Low => sd.samples = 1,
                    Preset::Medium | Preset::High => {}
                    Preset::Ultra => sd.samples = 8,
                }
            }
            Source::FirstLayer
            | Source::DualDepth
            | Source::ColumnRays
            | Source::RayStochasticDepth
            | Source::DepthPyramid => {}
        }
        s
    }
}

// ------------------------------------------------------------------------------------- files

/// The format of a settings file, chosen by its extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SettingsFormat {
    /// `.json`
    Json,
    /// `.toml`
    Toml,
}

impl SettingsFormat {
    /// `.json` or `.toml` (any case); anything else is [`SettingsError::UnknownFormat`].
    pub fn of(path: &Path) -> Result<SettingsFormat, SettingsError> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        match ext.as_deref() {
            Some("json") => Ok(SettingsFormat::Json),
            Some("toml") => Ok(SettingsFormat::Toml),
            _ => Err(SettingsError::UnknownFormat {
                path: path.to_path_buf(),
            }),
        }
    }
}

/// Where a parser says it failed, 1-based.
struct ParseFailure {
    line: Option<usize>,
    column: Option<usize>,
    message: String,
}

/// One line, 1-based column, of byte `offset` in `text`.
fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, column)
}

fn parse<T: serde::de::DeserializeOwned>(
    text: &str,
    format: SettingsFormat,
) -> Result<T, ParseFailure> {
    match format {
        SettingsFormat::Json => serde_json::from_str(text).map_err(|e| {
            let full = e.to_string();
            let suffix = format!(" at line {} column {}", e.line(), e.column());
            let message = full.strip_suffix(&suffix).unwrap_or(&full).to_string();
            ParseFailure {
                line: (e.line() > 0).then_some(e.line()),
                column: (e.line() > 0).then_some(e.column()),
                message,
            }
        }),
        SettingsFormat::Toml => toml::from_str(text).map_err(|e| {
            let (line, column) = e.span().map(|span| line_column(text, span.start)).unzip();
            ParseFailure {
                line,
                column,
                message: e.message().trim().replace('\n', "; "),
            }
        }),
    }
}

/// `top`'s fields written over `base`'s, recursively.
fn merge(base: &mut serde_json::Value, top: serde_json::Value) {
    match (base, top) {
        (serde_json::Value::Object(base), serde_json::Value::Object(top)) => {
            for (key, value) in top {
                match base.get_mut(&key) {
                    Some(slot) => merge(slot, value),
                    None => {
                        base.insert(key, value);
                    }
                }
            }
        }
        (slot, value) => *slot = value,
    }
}

impl AoSettings {
    /// A settings file (`.json` or `.toml`, by extension) over the defaults, validated. The file
    /// may give any subset of the fields ([`AoSettings::field_paths`]); an unknown field, a value
    /// of the wrong type or one [`AoSettings::validate`] rejects is an error naming the file (and
    /// the line where the parser can tell).
    pub fn from_file(path: impl AsRef<Path>) -> Result<AoSettings, SettingsError> {
        AoSettings::default().with_file(path)
    }

    /// `self` with the fields a settings file gives replaced by the file's, validated: how a
    /// file goes over a [`Preset`] (fields the file leaves out keep `self`'s values, not the
    /// defaults). Errors as [`AoSettings::from_file`].
    pub fn with_file(&self, path: impl AsRef<Path>) -> Result<AoSettings, SettingsError> {
        let path = path.as_ref();
        let format = SettingsFormat::of(path)?;
        let text = std::fs::read_to_string(path).map_err(|e| SettingsError::Read {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
        let parse_error = |f: ParseFailure| SettingsError::Parse {
            path: path.to_path_buf(),
            line: f.line,
            column: f.column,
            message: f.message,
        };
        // Typed first, for the parser's positions on unknown fields and wrong types ...
        parse::<AoSettings>(&text, format).map_err(parse_error)?;
        // ... then as a tree, to keep the fields the file leaves out.
        let file: serde_json::Value = parse(&text, format).map_err(parse_error)?;
        let mut merged = to_value(self);
        merge(&mut merged, file);
        let settings: AoSettings =
            serde_json::from_value(merged).map_err(|e| SettingsError::Parse {
                path: path.to_path_buf(),
                line: None,
                column: None,
                message: e.to_string(),
            })?;
        settings.validate().map_err(|e| SettingsError::InFile {
            path: path.to_path_buf(),
            source: Box::new(e),
        })?;
        Ok(settings)
    }

    /// Every field as TOML (what a `.toml` settings file holds).
    pub fn to_toml_string(&self) -> String {
        toml::to_string(self).expect("AoSettings serialises to TOML")
    }

    /// Every field as pretty-printed JSON (what a `.json` settings file holds).
    pub fn to_json_string(&self) -> String {
        serde_json::to_string_pretty(self).expect("AoSettings serialises to JSON")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn file(dir: &Path, name: &str, text: &str) -> PathBuf {
        let p = dir.join(name);
        std::fs::write(&p, text).unwrap();
        p
    }

    fn odd() -> AoSettings {
        let mut s = AoSettings::preset(Technique::SdSvao, Preset::Ultra);
        s.vao.radius = 0.7;
        s.vao.exponent = 1.1;
        s.vao.normalization = Normalization::Hemisphere;
        s.blur.enabled = false;
        s.blur.sharpness = 3.25;
        s.peel_separation = 0.05;
        s.stochastic_depth.seed = 17;
        s.stochastic_depth.mask = SdMask::Discard;
        s
    }

    #[test]
    fn toml_and_json_round_trip() {
        let dir = tempfile::tempdir().unwrap();
        for s in [AoSettings::default(), odd()] {
            let toml_text = s.to_toml_string();
            assert_eq!(toml::from_str::<AoSettings>(&toml_text).unwrap(), s);
            let json_text = s.to_json_string();
            assert_eq!(serde_json::from_str::<AoSettings>(&json_text).unwrap(), s);
            let t = file(dir.path(), "s.toml", &toml_text);
            assert_eq!(AoSettings::from_file(&t).unwrap(), s, "{toml_text}");
            let j = file(dir.path(), "s.JSON", &json_text);
            assert_eq!(AoSettings::from_file(&j).unwrap(), s, "{json_text}");
        }
        // Enums by their lowercase names, numbers as written.
        let text = odd().to_toml_string();
        for needle in [
            "technique = \"sd-svao\"",
            "normalization = \"hemisphere\"",
            "mask = \"discard\"",
            "radius = 0.7",
        ] {
            assert!(text.contains(needle), "{needle} not in\n{text}");
        }
        let json = AoSettings::default().to_json_string();
        assert!(json.contains("\"normalization\": \"clipped\""), "{json}");
        assert!(json.contains("\"mask\": \"depth\""), "{json}");
    }

    #[test]
    fn a_partial_file_changes_only_its_fields() {
        let dir = tempfile::tempdir().unwrap();
        let t = file(dir.path(), "r.toml", "[vao]\nradius = 1.25\n");
        let mut want = AoSettings::default();
        want.vao.radius = 1.25;
        assert_eq!(AoSettings::from_file(&t).unwrap(), want);
        // Over a preset, the fields the file leaves out keep the preset's values.
        let base = AoSettings::preset(Technique::SdVao, Preset::Ultra);
        let mut want = base;
        want.vao.radius = 1.25;
        assert_eq!(base.with_file(&t).unwrap(), want);
        let j = file(
            dir.path(),
            "sd.json",
            r#"{"stochastic_depth": {"alpha": 0.5}, "peel_separation": 0}"#,
        );
        let mut want = base;
        want.stochastic_depth.alpha = Some(0.5);
        want.peel_separation = 0.0;
        assert_eq!(base.with_file(&j).unwrap(), want);
        let empty = file(dir.path(), "empty.toml", "");
        assert_eq!(base.with_file(&empty).unwrap(), base);
        let whole = file(dir.path(), "t.toml", "technique = \"rt-vao\"\n");
        assert_eq!(
            AoSettings::from_file(&whole).unwrap().technique,
            Technique::RtVao
        );
    }

    #[test]
    fn bad_files_are_one_clear_error_naming_the_file() {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        let check = |path: &Path, needles: &[&str]| {
            let e = AoSettings::from_file(path).unwrap_err();
            let msg = e.to_string();
            assert!(!msg.contains('\n'), "one line: {msg}");
            let name = path.file_name().unwrap().to_str().unwrap();
            for n in [name].iter().chain(needles) {
                assert!(msg.contains(n), "'{n}' not in: {msg}");
            }
            e
        };
        // Unknown fields, top level and nested, with the line.
        let e = check(
            &file(d, "typo.toml", "# comment\n[vao]\nradiu = 1.0\n"),
            &["radiu", "line 3", "radius"],
        );
        assert!(matches!(e, SettingsError::Parse { .. }), "{e:?}");
        check(
            &file(d, "typo.json", "{\n  \"peel_seperation\": 0.1\n}"),
            &["peel_seperation", "line 2"],
        );
        // Wrong types, unknown names, syntax errors.
        check(
            &file(d, "type.toml", "[vao]\nsamples = \"many\"\n"),
            &["line 2", "many"],
        );
        check(
            &file(d, "tech.toml", "technique = \"hbao-classic\"\n"),
            &["hbao-classic", "sd-svao"],
        );
        check(
            &file(d, "norm.toml", "[vao]\nnormalization = \"flat\"\n"),
            &["flat", "clipped"],
        );
        check(&file(d, "syntax.toml", "[vao\n"), &["line 1"]);
        check(
            &file(d, "syntax.json", "{\"vao\": {\"radius\": }}"),
            &["line 1"],
        );
        // Valid syntax, invalid value: the field and the rule, no CLI flag.
        let e = check(
            &file(d, "neg.toml", "[vao]\nradius = -1\n"),
            &["vao.radius", "-1", "positive"],
        );
        assert!(!e.to_string().contains("--"), "{e}");
        // Unreadable, and a format the extension does not say.
        let e = check(&d.join("missing.toml"), &["cannot read", "check the path"]);
        assert!(matches!(e, SettingsError::Read { .. }));
        let e = check(&file(d, "s.yaml", "vao: {}"), &[".toml", ".json"]);
        assert!(matches!(e, SettingsError::UnknownFormat { .. }));
        check(&file(d, "noext", "[vao]"), &[".toml"]);
    }

    #[test]
    fn presets_validate_and_medium_is_the_default() {
        for technique in Technique::all() {
            for preset in Preset::ALL {
                let s = AoSettings::preset(technique, preset);
                s.validate()
                    .unwrap_or_else(|e| panic!("{technique} {preset}: {e}"));
                assert_eq!(s.technique, technique);
                // Never the scene-dependent or technique-independent fields.
                let d = AoSettings::default();
                assert_eq!(
                    (s.vao.radius, s.vao.thickness, s.vao.exponent),
                    (d.vao.radius, d.vao.thickness, d.vao.exponent)
                );
                assert_eq!(s.peel_separation, d.peel_separation);
                assert_eq!(s.blur.sharpness, d.blur.sharpness);
                assert_eq!(s.blur.enabled, d.blur.enabled);
            }
            assert_eq!(
                AoSettings::preset(technique, Preset::Medium),
                AoSettings {
                    technique,
                    ..AoSettings::default()
                }
            );
        }
        // The documented table.
        let vao = |p| {
            let s = AoSettings::preset(Technique::Vao, p);
            (s.vao.samples, s.blur.radius, s.stochastic_depth)
        };
        let sd_default = StochasticDepthSettings::default();
        assert_eq!(vao(Preset::Low), (8, 2, sd_default));
        assert_eq!(vao(Preset::High), (16, 4, sd_default));
        assert_eq!(vao(Preset::Ultra), (32, 6, sd_default));
        let grid = |t, p| {
            let s = AoSettings::preset(t, p);
            match t.estimator() {
                Estimator::Hbao => (s.hbao.directions, s.hbao.steps),
                _ => (s.gtao.slices, s.gtao.steps),
            }
        };
        let hbao: Vec<_> = Preset::ALL.map(|p| grid(Technique::Hbao, p)).into();
        assert_eq!(hbao, [(4, 4), (8, 4), (8, 10), (16, 20)]);
        let gtao: Vec<_> = Preset::ALL.map(|p| grid(Technique::Gtao, p)).into();
        assert_eq!(gtao, [(1, 2), (2, 2), (3, 3), (9, 3)]);
        let sd = |p| {
            let s = AoSettings::preset(Technique::SdSvao, p);
            (
                s.vao.samples,
                s.stochastic_depth.samples,
                s.stochastic_depth.alpha(),
            )
        };
        assert_eq!(sd(Preset::Low), (8, 1, 1.0));
        assert_eq!(sd(Preset::Medium), (8, 4, 0.375));
        assert_eq!(sd(Preset::High), (16, 4, 0.375));
        assert_eq!(sd(Preset::Ultra), (32, 8, 0.1875));
        // A two-phase technique gets its single-pass twin's settings.
        for p in Preset::ALL {
            let (a, b) = (
                AoSettings::preset(Technique::SdVao, p),
                AoSettings::preset(Technique::SdSvao, p),
            );
            assert_eq!(
                AoSettings {
                    technique: b.technique,
                    ..a
                },
                b
            );
        }
        assert_eq!("ULTRA".parse::<Preset>().unwrap(), Preset::Ultra);
        let e = "max".parse::<Preset>().unwrap_err().to_string();
        assert!(e.contains("max") && e.contains("medium"), "{e}");
    }

    #[test]
    fn a_radius_cap_is_none_or_at_least_a_pixel() {
        for bad in [0.5, -512.0, f32::NAN, f32::INFINITY] {
            let s = AoSettings {
                max_radius_px: bad,
                ..AoSettings::default()
            };
            let e = s.validate().unwrap_err().to_string();
            assert!(
                e.contains("max_radius_px") && e.contains("512"),
                "{bad}: {e}"
            );
        }
        for good in [0.0, 1.0, 512.0] {
            let s = AoSettings {
                max_radius_px: good,
                ..AoSettings::default()
            };
            s.validate().unwrap();
        }
    }

    #[test]
    fn the_radius_is_the_estimators() {
        for technique in Technique::all() {
            let mut s = AoSettings::preset(technique, Preset::Medium);
            *s.radius_mut() = 1.75;
            assert_eq!(s.radius(), 1.75, "{technique}");
            let json = serde_json::to_string(&s).unwrap();
            assert_eq!(
                json.matches("1.75").count(),
                1,
                "{technique}: one radius field"
            );
        }
    }

    #[test]
    fn blur_sigma_is_a_natural_gaussian() {
        let mut b = BlurSettings {
            sigma: Some(1.5),
            ..BlurSettings::default()
        };
        for d in 1..=3 {
            let d2 = (d * d) as f32;
            let weight = (-d2 * b.falloff()).exp2();
            assert!(
                (weight - (-d2 / (2.0 * 1.5 * 1.5)).exp()).abs() < 1e-6,
                "d {d}"
            );
        }
        // Left out: HBAO+'s weights, σ' = (radius + 1)/2 in exp2 units.
        b.sigma = None;
        assert_eq!(b.falloff(), 1.0 / (2.0 * 2.5 * 2.5));
    }

    #[test]
    fn validation_names_fields_that_exist_and_no_flags() {
        let paths = AoSettings::field_paths();
        assert_eq!(paths.len(), 77, "{paths:?}");
        let mut broken: Vec<AoSettings> = Vec::new();
        let mut push = |f: &dyn Fn(&mut AoSettings)| {
            let mut s = AoSettings::default();
            f(&mut s);
            broken.push(s);
        };
        push(&|s| s.vao.radius = 0.0);
        push(&|s| s.vao.thickness = -1.0);
        push(&|s| s.vao.exponent = f32::NAN);
        push(&|s| s.vao.samples = 12);
        push(&|s| s.peel_separation = -0.1);
        push(&|s| s.stochastic_depth.samples = 3);
        push(&|s| s.stochastic_depth.alpha = Some(1.5));
        push(&|s| s.stochastic_depth.compensation = 0.5);
        push(&|s| s.stochastic_depth.guard_band = 4096);
        push(&|s| s.ray_sd.reservoir = 9);
        push(&|s| s.ray_sd.max_count = 2);
        push(&|s| s.ray_sd.resolution = 3);
        push(&|s| s.ray_sd.radius_cutoff = -1.0);
        push(&|s| s.ray_sd.guard_band = Some(4096));
        push(&|s| s.max_radius_px = 0.5);
        push(&|s| s.multiview.angle = 90.0);
        push(&|s| s.multiview.focus = Some(-1.0));
        push(&|s| s.blur.radius = 0);
        push(&|s| s.temporal.frames = 0);
        push(&|s| s.temporal.depth_tolerance = 1.0);
        push(&|s| s.temporal.normal_tolerance_deg = f32::NAN);
        push(&|s| s.blur.sharpness = -2.0);
        push(&|s| s.blur.sigma = Some(0.0));
        push(&|s| s.hbao_plus.radius = -1.0);
        push(&|s| s.hbao_plus.bias = 1.0);
        push(&|s| s.hbao_plus.exponent = 0.0);
        push(&|s| s.hbao_plus.directions = 0);
        push(&|s| s.hbao_plus.steps = 5);
        push(&|s| s.hbao.radius = 0.0);
        push(&|s| s.hbao.angle_bias = 1.6);
        push(&|s| s.hbao.exponent = f32::NAN);
        push(&|s| s.hbao.directions = 65);
        push(&|s| s.hbao.steps = 0);
        push(&|s| s.gtao.radius = -1.0);
        push(&|s| s.gtao.thickness_blend = 1.5);
        push(&|s| s.gtao.exponent = 0.0);
        push(&|s| s.gtao.slices = 17);
        push(&|s| s.gtao.steps = 33);
        push(&|s| s.pyramid.levels = 9);
        push(&|s| s.pyramid.factor = 1);
        push(&|s| s.pyramid_hbao.radius = f32::NAN);
        push(&|s| s.pyramid_hbao.exponent = -1.0);
        push(&|s| s.pyramid_hbao.directions = 0);
        push(&|s| s.pyramid_hbao.steps = 17);
        push(&|s| s.ssao.radius = -0.5);
        push(&|s| s.ssao.samples = 33);
        push(&|s| s.ssao.intensity = 0.0);
        push(&|s| s.ssao.bias = -1.0);
        push(&|s| s.ssao.contrast = f32::NAN);
        push(&|s| s.sao.radius = 0.0);
        push(&|s| s.sao.samples = 65);
        push(&|s| s.sao.spiral_turns = 0.0);
        push(&|s| s.sao.bias = -0.1);
        push(&|s| s.sao.intensity = f32::INFINITY);
        push(&|s| s.gtao_vb.radius = f32::INFINITY);
        push(&|s| s.gtao_vb.thickness = -0.5);
        push(&|s| s.gtao_vb.exponent = -1.0);
        push(&|s| s.gtao_vb.slices = 4);
        push(&|s| s.gtao_vb.steps = 9);
        let mut reported = Vec::new();
        for s in &broken {
            match s.validate() {
                Err(SettingsError::Invalid { field, rule, .. }) => {
                    assert!(paths.iter().any(|p| p == field), "{field} not in {paths:?}");
                    assert!(!rule.contains("--"), "{field}: '{rule}' names a flag");
                    reported.push(field);
                }
                other => panic!("{s:?}: {other:?}"),
            }
        }
        reported.dedup();
        assert_eq!(reported.len(), broken.len(), "{reported:?}");
        for (text, field) in [
            ("flat".parse::<Normalization>().err(), "vao.normalization"),
            ("both".parse::<SdMask>().err(), "stochastic_depth.mask"),
            (
                "closest".parse::<SdSelection>().err(),
                "stochastic_depth.selection",
            ),
            ("often".parse::<SdQuery>().err(), "stochastic_depth.query"),
            (
                "software".parse::<SdRasterizer>().err(),
                "stochastic_depth.rasterizer",
            ),
            ("quarter".parse::<Resolution>().err(), "resolution"),
            (
                "half".parse::<SectorActivation>().err(),
                "gtao_vb.activation",
            ),
        ] {
            match text {
                Some(SettingsError::Invalid { field: f, .. }) => {
                    assert_eq!(f, field);
                    assert!(paths.iter().any(|p| p == f));
                }
                other => panic!("{other:?}"),
            }
        }
    }
}
