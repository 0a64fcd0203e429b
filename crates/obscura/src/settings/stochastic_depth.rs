//! The hidden-depth sources' parameters: the rasterised stochastic depth map (seed 001 §3.1)
//! and the ray-traced one (seed 002).

use super::*;
use crate::knob::{Kind, Knob, Widget};

/// The stratified stochastic depth map (seed 001 §3.1, Alg. 1).
///
/// Defaults: S = 4 and α = 1.5/S (0.375 at S = 4), the authors' 2024 rule
/// (docs/AUTHORS_CODE.md §2.2, §2.4). Held against an outside renderer's ground truth, α = 1.5/S
/// gave a lower MSE than the authors' 2022 α = 0.2 on every view tried (1.04× to 7.6×), and 0.2
/// lost to depth peeling on one; 0.2 stays reachable (`alpha = 0.2`, `--sd-alpha 0.2`) to reproduce
/// the 2022 tables.
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
    /// 0 is off; at most 2048. It widens the map's raster pass by that much. `None` (the default;
    /// a file that leaves it out, JSON `null`, `--sd-map-guard-band auto`): the ray-traced map's
    /// 512 px at 1080p, scaled with the visible height
    /// ([`StochasticDepthSettings::guard_band_for`]). On by default because the map's edge is
    /// where it is least steady in motion: without it, every sample that leaves the framebuffer
    /// falls back to the first layer's edge, and those pixels flicker as the camera moves
    /// (docs/lab/2026-12-06-stochastic-map-band-selection-motion.md; its cost in BENCHMARKS.md,
    /// issue 62).
    pub guard_band: Option<u32>,
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
            guard_band: None,
            rasterizer: SdRasterizer::Auto,
        }
    }
}

/// α of the authors' 2024 code (docs/AUTHORS_CODE.md §2.2): 1.5/S, so that a hidden fragment is
/// kept in 1.5 of its pixel's S samples on average whatever S is (at most 1).
pub fn sd_alpha_2024(samples: u32) -> f32 {
    (1.5 / samples as f32).min(1.0)
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
    /// Checks these fields alone (their knobs and the rules between them), for a source given
    /// them without the rest of [`AoSettings`].
    pub fn validate(&self) -> Result<(), SettingsError> {
        AoSettings {
            ray_sd: *self,
            ..AoSettings::default()
        }
        .validate()
    }

    /// The map's guard band in pixels for a `visible_height` image, on a two-phase schedule or
    /// not: `guard_band`, or where that is `None`, 512 px at 1080p scaled with the height and
    /// rounded up to a multiple of 4 (whole texels at 1/4 resolution) on two-phase schedules,
    /// where only requested band texels are traced, and 0 on one-pass schedules, which would
    /// trace every band texel each frame (at 1080p + 64 px, 2.8× the rays of the framebuffer).
    pub fn guard_band_for(&self, visible_height: u32, two_phase: bool) -> u32 {
        self.guard_band.unwrap_or_else(|| {
            if two_phase {
                authors_guard_band(visible_height)
            } else {
                0
            }
        })
    }
}

/// Seed 002 §3.5's map guard band, 512 px at 1080p, scaled with the visible height and rounded
/// up to a multiple of 4 (whole texels at the ray-traced map's 1/4 resolution).
fn authors_guard_band(visible_height: u32) -> u32 {
    let scaled = 512.0 * f64::from(visible_height) / 1080.0;
    (scaled / 4.0).ceil() as u32 * 4
}

impl StochasticDepthSettings {
    /// The raster map's own guard band in pixels for a `visible_height` image: `guard_band`, or
    /// where that is `None`, the ray-traced map's default (512 px at 1080p scaled with the
    /// height, a multiple of 4) on every schedule. Unlike the ray-traced map's, the raster map's
    /// band costs no rays on one-pass rows, only a wider raster pass (+0.37 ms at 1080p on an
    /// H100 with the compute rasteriser, BENCHMARKS.md, issue 62).
    pub fn guard_band_for(&self, visible_height: u32) -> u32 {
        self.guard_band
            .unwrap_or_else(|| authors_guard_band(visible_height))
    }
}

/// The widest map guard band `ray_sd.guard_band` accepts (four times the authors' 512).
pub(super) const MAX_SD_GUARD_BAND: u32 = 2048;

impl StochasticDepthSettings {
    /// Every field's knob: range, unit, flag, help, widget (crate::knob).
    pub const KNOBS: &'static [Knob] = &[
        Knob::new(
            "stochastic_depth.samples",
            "--sd-samples",
            "Stochastic depth samples per pixel, S.",
            Kind::OneOf(&SD_SAMPLE_COUNTS),
        )
        .doc("S, depth samples per pixel of the stochastic depth map (every adapter)")
        .widget(Widget::Buttons),
        Knob::new(
            "stochastic_depth.alpha",
            "--sd-alpha",
            "Global transparency α: a hidden fragment is kept in ⌊αS + ξ⌋ samples; 0.2 is the \
             authors' 2022 value, auto = 1.5/S their 2024 rule.",
            Kind::number(0.0, 1.0, true, false),
        )
        .auto("1.5/S")
        .doc("α: a hidden fragment is kept in ⌊αS + ξ⌋ of its pixel's S samples"),
        Knob::new(
            "stochastic_depth.seed",
            "--sd-seed",
            "Seed of the stochastic depth map's hash.",
            Kind::int(0, u32::MAX),
        ),
        Knob::new(
            "stochastic_depth.mask",
            "--sd-mask",
            "sd-svao: limit the map to the requested pixels by 'depth' (the far plane written into \
             the map's depth test where nobody asked), 'stencil' (the paper's full-screen copy \
             into the stencil, then the stencil test) or 'discard' (the map's fragment shader \
             reads the request mask).",
            Kind::Choice(&["depth", "stencil", "discard"]),
        )
        .doc(
            "how `sd-svao` limits the map to the requested pixels: the far plane in the map's depth \
             test where nobody asked (default), the paper's stencil, or the map's shader skipping \
             them (the same image)",
        ),
        Knob::new(
            "stochastic_depth.query",
            "--sd-query",
            "Read the map only where the first layer cannot decide ('needed', seed 001 §3.3; SSAO \
             and GTAO-VB also skip samples no deeper surface can change), as the paper words it \
             ('first-layer': the same image, more reads) or for every sample ('always').",
            Kind::Choice(&["needed", "first-layer", "always"]),
        )
        .doc(
            "when a sample reads the map: where the first layer cannot decide (the default, seed \
             001 §3.3's heuristic; for SSAO also only where a deeper surface on the sample's camera \
             ray could occlude at all, for GTAO-VB only where one could mark a sector still free \
             (without compensation): exact tests), `first-layer` as the paper words it without \
             those tests (the same image, more reads), or for every sample that finds a surface",
        ),
        Knob::new(
            "stochastic_depth.compensation",
            "--sd-compensation",
            "Multiply the occlusion of stochastic samples by this factor (missing-occlusion \
             compensation, seed 001 §4; 1 = off, the paper used 2).",
            Kind::number(1.0, 8.0, false, false),
        )
        .widget(Widget::Range),
        Knob::new(
            "stochastic_depth.selection",
            "--sd-selection",
            "Which hidden fragments each pixel of the raster map keeps: 'stochastic' (seed 001 \
             Alg. 1: a hashed subset) or 'nearest' (ours: the S nearest layers behind the first, \
             steady in motion).",
            Kind::Choice(&["stochastic", "nearest"]),
        )
        .aliases(&["--sd-select"])
        .doc(
            "which hidden fragments each pixel of the raster map keeps in its S depths: a hashed \
             subset, each fragment in ⌊αS + ξ⌋ samples and each sample the nearest that chose it \
             (the default, seed 001 Alg. 1: every hidden layer has a chance, with noise), or the S \
             nearest distinct depths behind the first layer (ours: a k-buffer of `atomicMax` \
             chains, no hash and no α; exact and steady in motion where a pixel hides at most S \
             layers, but the deepest are always lost where it hides more). The ray-traced map \
             keeps its reservoir",
        ),
        Knob::new(
            "stochastic_depth.guard_band",
            "--sd-map-guard-band",
            "Rasterise the raster map this many pixels beyond the framebuffer on every side (0 = \
             off), so samples off the framebuffer read it; the ray-traced map's band is \
             --ray-sd-guard-band.",
            Kind::int(0, MAX_SD_GUARD_BAND),
        )
        .units("pixels")
        .doc(
            "the raster map's own guard band (ours, after seed 002 §3.5's for the ray-traced map): \
             the map is rasterised this far beyond the framebuffer on every side, every layer \
             there, so samples that fall off the framebuffer read it instead of the framebuffer's \
             edge; two-phase rows request its pixels as they do the others; 0 is off",
        )
        .auto("512 px at 1080p scaled with the height, as the ray-traced map's"),
        Knob::new(
            "stochastic_depth.rasterizer",
            "--sd-rasterizer",
            "What rasterises the raster map: 'auto' ('compute' where the GPU binds its buffers and \
             is not a CPU adapter, else 'hardware'), 'hardware' (the GPU's rasteriser) or 'compute' \
             (ours: compute passes clip, bin and rasterise the triangles; the same map up to \
             rounding).",
            Kind::Choice(&["auto", "hardware", "compute"]),
        )
        .doc(
            "what rasterises the raster map: `auto` (the default) takes the compute passes wherever \
             the device binds their storage buffers (12 per shader stage) and is not a CPU adapter, \
             else the hardware; a renderer reports the one it chose (`Renderer::settings`, \
             `bench`'s JSON). `hardware`: the GPU's rasteriser; `compute`: our compute passes \
             (`compute_raster.wgsl`), the same map up to rounding, for GPUs whose raster units are \
             slow next to their compute (BENCHMARKS.md has the timings)",
        )
        .widget(Widget::Buttons),
    ];
}

impl RaySdSettings {
    /// Every field's knob: range, unit, flag, help, widget (crate::knob).
    pub const KNOBS: &'static [Knob] = &[
        Knob::new(
            "ray_sd.reservoir",
            "--ray-sd-reservoir",
            "Depth slots per pixel of the ray-traced stochastic depth map, N (seed 002 §3.1, \
             reservoir sampling).",
            Kind::int(1, 8),
        )
        .aliases(&["--reservoir"])
        .doc(
            "depth slots per pixel of the ray-traced stochastic depth map, N (seed 002 §3.1: the \
             first N distinct depths behind the first layer fill them, each later hit takes one \
             with probability N/count)",
        )
        .widget(Widget::Range),
        Knob::new(
            "ray_sd.max_count",
            "--ray-sd-max-count",
            "Hits a ray of the ray-traced map handles before it stops (MAX_COUNT, seed 002 §3.1).",
            Kind::int(1, 64),
        )
        .aliases(&["--max-count"])
        .note("at least ray_sd.reservoir"),
        Knob::new(
            "ray_sd.z_cull",
            "--ray-sd-no-z-cull",
            "Plain reservoir sampling (every hit kept with probability N/count) instead of the \
             paper's z-culling, which overwrites a slot only with a nearer depth.",
            Kind::Switch { flag_sets: false },
        )
        .aliases(&["--no-z-cull"]),
        Knob::new(
            "ray_sd.seed",
            "--ray-sd-seed",
            "Seed of the ray-traced map's reservoir hash.",
            Kind::int(0, u32::MAX),
        ),
        Knob::new(
            "ray_sd.resolution",
            "--ray-sd-resolution",
            "Resolution divisor of the ray-traced map: a ray per 1, 4 or 16 pixels through a \
             jittered point of its block (seed 002 §3.3).",
            Kind::OneOf(&[1, 2, 4]),
        )
        .aliases(&["--ray-sd-res"])
        .widget(Widget::Buttons),
        Knob::new(
            "ray_sd.radius_cutoff",
            "--ray-sd-radius-cutoff",
            "Samples nearer than this many pixels to their pixel keep the first layer's answer and \
             never request the ray-traced map (seed 002 §3.4 used 6; 0 = off).",
            Kind::NON_NEGATIVE,
        )
        .aliases(&["--radius-cutoff"])
        .units("pixels"),
        Knob::new(
            "ray_sd.intervals",
            "--ray-sd-no-intervals",
            "Trace each ray of the ray-traced map from the first layer to the scene's end instead \
             of over the depths phase 1's samples need (seed 002 §3.2's ray intervals).",
            Kind::Switch { flag_sets: false },
        )
        .aliases(&["--no-intervals"]),
        Knob::new(
            "ray_sd.guard_band",
            "--ray-sd-guard-band",
            "The ray-traced map's own guard band in pixels beyond the framebuffer (seed 002 §3.5), \
             0 = off.",
            Kind::int(0, MAX_SD_GUARD_BAND),
        )
        .aliases(&["--sd-guard-band"])
        .units("pixels")
        .auto("512 px at 1080p scaled with the height on two-phase rows, off on one-pass rows"),
    ];
}
