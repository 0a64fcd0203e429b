//! What a user chooses: the technique and its parameters, as data. Defaults are the papers' /
//! authors'; [`Preset`]s are per technique; settings files are JSON or TOML
//! ([`AoSettings::from_file`]); `docs/SETTINGS.md` documents every field.

pub use crate::error::SettingsError;
use crate::technique::{Estimator, Source};
pub use crate::technique::{Technique, UnknownTechnique};
use serde::{Deserialize, Serialize};
use std::fmt;
use std::path::Path;
use std::str::FromStr;

mod estimators;
mod files;
mod presets;
mod stochastic_depth;
#[cfg(test)]
mod tests;
mod validate;

pub use estimators::*;
pub use files::*;
pub use presets::*;
pub use stochastic_depth::*;
use validate::*;

impl AoSettings {
    /// These settings with every rule-derived value written out (α = 1.5/S as a number), for
    /// records that must say what ran (bench and compare JSON).
    pub fn resolved(&self) -> AoSettings {
        let mut s = *self;
        s.stochastic_depth.alpha = Some(s.stochastic_depth.alpha());
        s
    }
}

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
    /// Relative depth difference within which the history holds the same surface, at least
    /// 0.002 (the history keeps depth to 0.1 %, at any scene scale).
    pub depth_tolerance: f32,
    /// Degrees between normals within which the history holds the same surface.
    pub normal_tolerance_deg: f32,
    /// Clip the history to mean ± σ of this frame's AO at the pixel and its four neighbours (as
    /// engines' TAA does): screen-space AO changes with the view (halos move with parallax), and
    /// without the clamp that change lags `frames` frames behind.
    pub clamp: bool,
}

/// The smallest `temporal.depth_tolerance` accepted: about twice the rounding of the history's
/// 16-bit depth (`shaders/filter/temporal_accumulation.wgsl`, `pack_history_depth`: 2^-10 relative).
pub const MIN_TEMPORAL_DEPTH_TOLERANCE: f32 = 0.002;

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
