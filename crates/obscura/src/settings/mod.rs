//! What a user chooses: the technique and its parameters, as data. Defaults are the papers' /
//! authors'; [`Preset`]s are per technique; settings files are JSON or TOML
//! ([`AoSettings::from_file`]); `docs/SETTINGS.md` documents every field.

pub use crate::error::SettingsError;
use crate::knob::{Kind, Knob, Widget};
use crate::technique::Estimator;
pub use crate::technique::{Technique, UnknownTechnique};
use serde::{Deserialize, Serialize};
use std::fmt;
use std::path::Path;
use std::str::FromStr;

mod estimators;
mod files;
mod knobs;
mod layers;
mod presets;
mod stochastic_depth;
#[cfg(test)]
mod tests;
mod validate;

pub use crate::estimators::gtao::GTAO_MAX_SLICES;
pub use crate::estimators::gtao_vb::SectorActivation;
pub use crate::estimators::hbao::HBAO_MAX_DIRECTIONS;
pub use crate::estimators::vao::Normalization;
pub use estimators::*;
pub use files::*;
pub use layers::units_per_metre;
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

/// `AoSettings` and its defaults, with one field per estimator of the registry
/// (`estimators::registry`), each re-exported here by its settings struct.
macro_rules! ao_settings {
    ($($(#[$attr:meta])* $name:ident: $variant:ident($settings:ident) = $doc:literal,)*) => {
        $($(#[$attr])* pub use crate::estimators::$name::$settings;)*

        /// Everything a technique's kernels read, as data: every field has a default (the papers' /
        /// authors' values), and settings files (JSON or TOML, [`AoSettings::from_file`]) name the
        /// same fields, nested as here (`vao.radius`, `stochastic_depth.alpha`, …). A file may give
        /// any subset; an unknown field is an error. `docs/SETTINGS.md` lists every field.
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
            /// Which row of the technique table runs (estimator × hidden-depth source × schedule);
            /// default `vao`.
            pub technique: Technique,
            $($(#[$attr])* #[doc = concat!("The estimator `", stringify!($name), "`: ", $doc)]
            pub $name: $settings,)*
            /// The bilateral blur that filters every technique's raw AO.
            pub blur: BlurSettings,
            /// The à-trous denoiser, in the blur's place when enabled.
            pub denoise: DenoiseSettings,
            /// `vao-dual`: the second layer is the nearest surface more than this many world units
            /// behind the first (the authors' `minSeparationDistance`, docs/AUTHORS_CODE.md §2.1).
            /// Also the minimum distance behind the first layer for a fragment to enter the
            /// stochastic depth map (`sd-vao`, `sd-svao`).
            pub peel_separation: f32,
            /// The stochastic depth map (`sd-vao`, `sd-svao`).
            pub stochastic_depth: StochasticDepthSettings,
            /// The ray-traced stochastic depth map (`ray-sd-vao`).
            pub ray_sd: RaySdSettings,
            /// The depth pyramid (`sao`, `pyramid-hbao`).
            pub pyramid: PyramidSettings,
            /// Where the technique runs: at the inputs' resolution, or at half of it in each axis
            /// and brought back by a depth-aware upsample (seed 001 Tab. 1–2; every technique can).
            pub resolution: Resolution,
            /// The AO radius's cap on screen, in pixels of the output image (seed 002 §3.5; the
            /// authors' `ssMaxRadius`): where a shading point's radius R would cover more pixels (a
            /// surface close to the camera), R is shrunk for that pixel to cover exactly this many,
            /// so the kernel keeps its shape. Every estimator honours it; the ground truths never
            /// do. 0 (the default): no cap. The authors pair 512 px with their map's 512 px guard
            /// band at 1080p, so that samples never fall beyond the map; it costs accuracy near the
            /// camera (measured: docs/SETTINGS.md), so it is off unless asked for.
            pub max_radius_px: f32,
            /// Also write the bent normal, the mean unoccluded direction, next to the AO (seed 001
            /// §4, Fig. 9): view space, unit length, for the techniques whose estimator reports one
            /// (GTAO, GTAO-VB, VAO, HBAO+ and their dual and stochastic-depth rows), on the
            /// single-pass schedule at full resolution.
            pub bent_normals: bool,
            /// The multi-view schedule's second view (`sd-hbao+-multiview`).
            pub multiview: MultiviewSettings,
            /// Temporal accumulation of the AO over frames (off by default).
            pub temporal: TemporalSettings,
        }

        impl Default for AoSettings {
            fn default() -> Self {
                Self {
                    technique: Technique::default(),
                    $($(#[$attr])* $name: $settings::default(),)*
                    pyramid: PyramidSettings::default(),
                    blur: BlurSettings::default(),
                    denoise: DenoiseSettings::default(),
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
    };
}
crate::estimators::registry!(ao_settings);

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

impl TemporalSettings {
    /// Every field's knob: range, unit, flag, help, widget (crate::knob).
    pub const KNOBS: &'static [Knob] = &[
        Knob::new(
            "temporal.enabled",
            "--temporal",
            "Temporal accumulation: each pixel's AO averaged with its history over frames, \
             reprojected by the camera motion and rejected where the surface differs; the \
             estimators turn their 4×4 pattern per frame (docs/PATHS.md). For paths and the viewer.",
            Kind::Switch { flag_sets: true },
        )
        .doc(
            "temporal accumulation before the blur: each pixel averaged with its reprojected \
             history; the estimators' 4×4 pattern turned by one entry per frame, and the \
             stochastic depth maps' seeds (and the ray-traced map's jitter) changed per frame \
             (docs/PATHS.md)",
        )
        .widget(Widget::Checkbox),
        Knob::new(
            "temporal.frames",
            "--temporal-frames",
            "--temporal: the most frames averaged.",
            Kind::int(1, 255),
        )
        .doc(
            "the most frames averaged: a running mean up to this many, then an exponential blend \
             with weight 1/frames",
        ),
        Knob::new(
            "temporal.depth_tolerance",
            "--temporal-depth-tolerance",
            "--temporal: relative depth difference within which the history is the same surface.",
            Kind::number(MIN_TEMPORAL_DEPTH_TOLERANCE as f64, 1.0, false, true),
        )
        .note("a fraction of the depth: the history keeps depth to 0.1 %")
        .doc(
            "relative depth difference within which the history is the same surface (else \
             rejected: disocclusion); the history keeps depth in 16 bits to 0.1 % at any depth \
             from 2⁻⁶⁴ to 2⁶⁴ world units, hence the lower bound",
        ),
        Knob::new(
            "temporal.normal_tolerance_deg",
            "--temporal-normal-tolerance",
            "--temporal: degrees between normals within which the history is the same surface.",
            Kind::number(0.0, 180.0, true, false),
        )
        .units("degrees"),
        Knob::new(
            "temporal.clamp",
            "--temporal-no-clamp",
            "--temporal: keep the history unclipped (by default it is clipped to the spread of this \
             frame's AO around the pixel, which stops view-dependent occlusion from lagging).",
            Kind::Switch { flag_sets: false },
        )
        .doc(
            "clip the history to mean ± σ of this frame's AO at the pixel and its four neighbours \
             (variance clipping), so view-dependent occlusion (halos moving with parallax) does \
             not lag behind",
        ),
    ];
}

impl MultiviewSettings {
    /// Every field's knob: range, unit, flag, help, widget (crate::knob).
    pub const KNOBS: &'static [Knob] = &[
        Knob::new(
            "multiview.angle",
            "--mv-angle",
            "sd-hbao+-multiview: degrees the second view is swung about the camera's up axis \
             around the focus point (seed 001 §3.4).",
            Kind::number(0.0, 60.0, true, false),
        )
        .units("degrees"),
        Knob::new(
            "multiview.focus",
            "--mv-focus",
            "sd-hbao+-multiview: distance from the camera to the point both views look at.",
            Kind::POSITIVE,
        )
        .length()
        .auto("the distance along the view axis to the scene's bounding-box centre"),
        Knob::new(
            "multiview.resolution",
            "--mv-resolution",
            "sd-hbao+-multiview: the second view's map and pass at 'full' or 'half' resolution \
             (seed 001 Tab. 3).",
            Kind::Choice(&["full", "half"]),
        ),
    ];
}

impl AoSettings {
    /// The knobs of the fields at the top level of a settings file (the technique is chosen
    /// apart; crate::knob).
    pub const KNOBS: &'static [Knob] = &[
        Knob::new(
            "peel_separation",
            "--peel-separation",
            "vao-dual and the stochastic depth maps: hidden layers start this many world units \
             behind the first.",
            Kind::NON_NEGATIVE,
        )
        .length()
        .doc(
            "how far behind the first layer the second layer (`vao-dual`) and the stochastic depth \
             map's fragments start",
        ),
        Knob::new(
            "resolution",
            "--resolution",
            "Run the technique at 'full' resolution or at 'half' (a quarter of the pixels, seed 001 \
             Tab. 1-2) with a depth-aware upsample; half needs an even size and guard band.",
            Kind::Choice(&["full", "half"]),
        )
        .widget(Widget::Buttons),
        Knob::new(
            "max_radius_px",
            "--max-radius-px",
            "Cap the AO radius on screen at this many output pixels: a surface closer to the \
             camera runs with the radius that covers exactly that many (seed 002 §3.5; the authors \
             used 512 at 1080p with a 512 px ray-traced map guard band).",
            Kind::number(1.0, 1e6, false, false).or_zero("no cap"),
        )
        .units("pixels")
        .note("the authors used 512 at 1080p")
        .doc(
            "the AO radius's cap on screen (seed 002 §3.5, the authors' `ssMaxRadius`), in output \
             pixels: a shading point whose radius would cover more (a surface close to the camera) \
             runs with the radius that covers exactly that many, so the kernel keeps its shape and \
             every world-radius term follows; for GTAO it binds the samples' reach, 1.457 R; the \
             ground truths are never capped. The authors paired 512 px with their map's 512 px \
             `ray_sd.guard_band` at 1080p, so that no sample falls beyond the map",
        )
        .widget(Widget::Slider {
            min: 0.0,
            max: 2048.0,
            log: false,
        }),
        Knob::new(
            "bent_normals",
            "--bent-normals",
            "Also compute the bent normal (seed 001 §4) for the single-pass GTAO, GTAO-VB, VAO and \
             HBAO+ rows; `render` writes it next to the AO as NAME.bent.png (view space, RGB = \
             0.5 n + 0.5) or NAME.bent.exr.",
            Kind::Switch { flag_sets: true },
        )
        .doc(
            "also write the bent normal, the weighted mean unoccluded direction (seed 001 §4), for \
             the single-pass GTAO, GTAO-VB, VAO and HBAO+ rows (and their dual and stochastic-depth \
             twins) at full resolution: view space, unit length (`AmbientOcclusion::bent_normals`; \
             `render` writes `NAME.bent.png` with RGB = 0.5·n + 0.5, or `.exr` with raw xyz)",
        ),
    ];
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
