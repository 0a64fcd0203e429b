//! Comparison reports: the evidence researchers read when they compare AO
//! techniques against a ray-traced reference.
//!
//! [`build_report`] computes the metrics of every technique (see
//! [`crate::metrics::summarize`]) and returns a [`Report`]; [`write_report`]
//! does the same and also writes, into an existing directory:
//!
//! | file | content |
//! |---|---|
//! | `report.json` | the [`Report`], pretty-printed (see *JSON* below) |
//! | `report.md` | the same as a Markdown table under a header line naming scene, camera, size and reference |
//! | `reference.png` | the reference AO, 8-bit grey |
//! | `<technique>.png` | each technique's AO, 8-bit grey |
//! | `<technique>.diff.png` | heat map of technique − reference (see [`heatmap_rgb`]) |
//! | `cost.svg` | MSE against time per technique with the Pareto front, when techniques were timed |
//! | `temporal-mse.svg`, `temporal-error.svg` | along a camera path ([`ReportInput::temporal`]): per-frame MSE and per-pair temporal error of every technique (plotted with `plotters`) |
//! | `<technique>.gif`, `reference.gif` | along a camera path: every frame, animated |
//! | `index.html` | a self-contained page: metrics table, the quality-against-cost chart, and per technique the reference, the technique and its heat map side by side with a colour legend |
//!
//! # Images
//! Grey PNGs hold the AO value clamped to `[0, 1]` times 255, rounded — the
//! raw value, not gamma-encoded, like `output::write_ao`, so the pictures look
//! the same as the renderer's own outputs.
//!
//! Heat maps use one symmetric scale `±s` for every technique, so that their
//! colours are comparable: `s` is the 99th percentile (nearest rank) of
//! `|technique − reference|` pooled over all pixels of all techniques,
//! rounded *up* to the next value of the 1-2-5 series (0.01, 0.02, 0.05,
//! 0.1, 0.2, 0.5, 1, …; never below 0.01). The percentile rather than the
//! maximum keeps a few outlier pixels (fireflies, single silhouette pixels)
//! from washing out the whole map; the floor keeps an exact match white
//! instead of amplifying rounding noise; the rounding gives a legend that
//! reads at a glance. Differences beyond `±s` saturate.
//!
//! # JSON
//! JSON has no infinity or NaN, but PSNR is `+∞` for a technique identical to
//! the reference. Every `f64` metric is therefore written as `null` when it is
//! not finite. Reading back, `null` becomes `+∞` for `psnr` (the only
//! non-finite value a PSNR of finite images can take: `MSE = 0`) and NaN for
//! the other metrics (which are always finite for valid inputs, so `null`
//! never appears there in a report written by this module). Other readers
//! (Python's `json`, `jq`) see `null` and must treat a `null` PSNR as "exact
//! match". Finite values round-trip to within one ulp: serde_json's default
//! float parser is not always correctly rounded (enable its `float_roundtrip`
//! feature for bit-exact values).
//!
//! # Files and failures
//! Technique names become file names, so they must match `[a-z0-9+_-]+`, be
//! unique and not be `reference`. All inputs are validated before anything is
//! written. Every file is then first written to a temporary sibling
//! `.NAME.partial`; only when all of them were written are they renamed into
//! place (`index.html` last, so the page never points at a missing picture).
//! On any error the temporary files — and the files this call already renamed
//! into place, should a rename fail — are removed, so a failed call leaves no
//! half-written or partial report behind (files of an older report that this
//! call did not reach stay as they were). Two concurrent calls on the same
//! directory are not supported: they share the temporary names.

mod chart;
pub mod demo_page;
#[cfg(test)]
mod demo_page_tests;
mod files;
mod heatmap;
mod html;
mod json;
mod markdown;
pub mod temporal;
#[cfg(test)]
mod tests;

pub use self::chart::{cost_chart_svg, pareto_front};
pub use self::heatmap::heatmap_rgb;
pub use self::temporal::{TemporalInput, TemporalReport, TemporalResult};

use crate::metrics::{self, Image, MetricsError};
use std::fmt;
use std::path::{Path, PathBuf};

/// One technique's AO image, `width × height` values, row-major, top row
/// first.
#[derive(Debug, Clone, Copy)]
pub struct TechniqueImage<'a> {
    /// Short name used in the tables and in file names: `[a-z0-9+_-]+`.
    pub name: &'a str,
    /// AO values, nominally in `[0, 1]` (1 = unoccluded); must be finite.
    pub ao: &'a [f32],
    /// The settings it was rendered with, as data (`compare` passes the serialised
    /// [`crate::AoSettings`]); written to `report.json` as they are.
    pub settings: Option<&'a serde_json::Value>,
    /// Its GPU time per frame in milliseconds (`compare`: the median over a few frames of every
    /// pass but the G-buffer, which an engine has anyway), if measured.
    pub gpu_ms: Option<f64>,
}

/// Everything a report is made of. Every image is the `width × height`
/// visible image, row-major, top row first.
#[derive(Debug, Clone)]
pub struct ReportInput<'a> {
    /// Scene name, printed in the report.
    pub scene: &'a str,
    /// Camera name, printed in the report.
    pub camera: &'a str,
    /// The scene-wide choices the images depend on (e.g. `Scene::options_description`: sides
    /// and normals), printed in the report; empty when not known.
    pub scene_options: &'a str,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Guard band the frame was rendered with, in pixels (printed only).
    pub guard_band: u32,
    /// How the reference was computed: `"vao"`, `"vao-mean"` or `"hemisphere"`, or where it
    /// came from: `"image 'FILE'"` for an outside renderer's image (`compare --reference-image`).
    pub reference_model: &'a str,
    /// Hemisphere rays per pixel; `Some` exactly when `reference_model` is
    /// `"hemisphere"`, `None` for the `"vao"` and `"vao-mean"` models and an image.
    pub spp: Option<u32>,
    /// The ground truth's radius R in world units (the vao models' sphere, the hemisphere
    /// model's ray length), printed beside the model so that every technique's radius
    /// (its settings) can be held against it; `None` where not known (an outside image).
    pub reference_radius: Option<f32>,
    /// Reference AO, the ground truth every technique is compared against.
    pub reference: &'a [f32],
    /// Linear view depth of the visible image (≤ 0 or non-finite:
    /// background); defines the halo band.
    pub depth: &'a [f32],
    /// The techniques to compare, in table order.
    pub techniques: Vec<TechniqueImage<'a>>,
    /// Halo band radius in pixels around depth discontinuities, e.g. 4.
    pub halo_radius_px: usize,
    /// Relative depth jump that makes a discontinuity, e.g. 0.1.
    pub halo_relative_jump: f32,
    /// GPU adapter description, printed in the page.
    pub adapter: &'a str,
    /// The adapter is a CPU (software) device: timings are marked as no GPU timings.
    pub software_adapter: bool,
    /// The heat maps' scale `±s`; `None`: chosen from the differences (see the module docs).
    /// A page comparing several reports passes one scale to all of them.
    pub diff_scale: Option<f64>,
    /// Along a camera path (`compare --path`): every frame of every technique and of the
    /// reference, for the temporal section; `None` for a single view.
    pub temporal: Option<TemporalInput<'a>>,
}

/// The metrics of one technique against the reference.
///
/// In JSON a non-finite value is written as `null`; a `null` `psnr` reads
/// back as `+∞` (exact match), any other `null` as NaN (see the module docs).
#[derive(serde::Serialize, serde::Deserialize, Clone, Debug, PartialEq)]
pub struct TechniqueResult {
    /// Technique name.
    pub technique: String,
    /// Mean squared error.
    #[serde(with = "json::finite_or_null")]
    pub mse: f64,
    /// Mean absolute error.
    #[serde(with = "json::finite_or_null")]
    pub mae: f64,
    /// PSNR in dB (data range 1); `+∞` (JSON `null`) for an exact match.
    #[serde(with = "json::psnr")]
    pub psnr: f64,
    /// Mean SSIM.
    #[serde(with = "json::finite_or_null")]
    pub ssim: f64,
    /// Mean positive error over the halo band (≥ 0).
    #[serde(with = "json::finite_or_null")]
    pub halo_bright: f64,
    /// Mean negative error over the halo band (≤ 0).
    #[serde(with = "json::finite_or_null")]
    pub halo_dark: f64,
    /// The settings it was rendered with ([`TechniqueImage::settings`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub settings: Option<serde_json::Value>,
    /// GPU milliseconds per frame ([`TechniqueImage::gpu_ms`]), if measured.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gpu_ms: Option<f64>,
}

/// How the reference image was computed.
#[derive(serde::Serialize, serde::Deserialize, Clone, Debug, PartialEq)]
pub struct ReferenceInfo {
    /// `"vao"`, `"vao-mean"` or `"hemisphere"`.
    pub model: String,
    /// Hemisphere rays per pixel (`None` for the vao models).
    pub spp: Option<u32>,
    /// The ground truth's radius R in world units (`None` where not known: an outside image,
    /// or a report written before it was recorded).
    #[serde(default)]
    pub radius: Option<f32>,
}

/// A whole comparison: what was rendered and every technique's metrics.
#[derive(serde::Serialize, serde::Deserialize, Clone, Debug, PartialEq)]
pub struct Report {
    /// Scene name.
    pub scene: String,
    /// Camera name.
    pub camera: String,
    /// The scene-wide choices (sides, normals), as [`ReportInput::scene_options`].
    #[serde(default)]
    pub scene_options: String,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Guard band in pixels.
    pub guard_band: u32,
    /// How the reference was computed.
    pub reference: ReferenceInfo,
    /// The adapter that rendered the techniques.
    #[serde(default)]
    pub adapter: String,
    /// The adapter is a CPU (software) device, so `gpu_ms` are no GPU timings.
    #[serde(default)]
    pub software_adapter: bool,
    /// The heat maps' scale `±s` (technique − reference).
    #[serde(default)]
    pub diff_scale: f64,
    /// One entry per technique, in input order.
    pub results: Vec<TechniqueResult>,
    /// Along a camera path: temporal error, popping and per-frame metrics.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub temporal: Option<TemporalReport>,
}

/// Why a report could not be built or written.
#[derive(Debug)]
pub enum ReportError {
    /// A metric rejected its input (e.g. images smaller than the 11×11 SSIM
    /// window, or a negative `halo_relative_jump`).
    Metrics(MetricsError),
    /// A file or the output directory could not be written.
    Io {
        /// The file (or directory) concerned.
        path: PathBuf,
        /// What went wrong and, where known, what to do about it.
        message: String,
    },
    /// The [`ReportInput`] is inconsistent; the message names the field and
    /// the fix.
    Input(String),
}

impl fmt::Display for ReportError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ReportError::Metrics(e) => write!(
                f,
                "could not compute the report metrics: {e} (check the images and halo \
                 parameters passed in ReportInput)"
            ),
            ReportError::Io { path, message } => {
                write!(f, "could not write '{}': {message}", path.display())
            }
            ReportError::Input(message) => write!(f, "invalid report input: {message}"),
        }
    }
}

// The metrics error is part of the Display text, so it is deliberately not
// also returned by `source()` (error reporters would print it twice).
impl std::error::Error for ReportError {}

impl From<MetricsError> for ReportError {
    fn from(e: MetricsError) -> Self {
        ReportError::Metrics(e)
    }
}

/// Computes every technique's metrics against the reference. Writes nothing.
///
/// # Errors
/// [`ReportError::Input`] for an inconsistent input (slice length, technique
/// name, reference model/spp, non-finite AO value, no techniques);
/// [`ReportError::Metrics`] when a metric rejects it (image smaller than
/// 11×11, negative `halo_relative_jump`).
pub fn build_report(input: &ReportInput) -> Result<Report, ReportError> {
    validate(input)?;
    let (w, h) = (input.width as usize, input.height as usize);
    let reference = Image::new(w, h, input.reference)?;
    let depth = Image::new(w, h, input.depth)?;
    let results = input
        .techniques
        .iter()
        .map(|t| {
            let s = metrics::summarize(
                &Image::new(w, h, t.ao)?,
                &reference,
                &depth,
                input.halo_radius_px,
                input.halo_relative_jump,
            )?;
            Ok(TechniqueResult {
                technique: t.name.to_owned(),
                mse: s.mse,
                mae: s.mae,
                psnr: s.psnr,
                ssim: s.ssim,
                halo_bright: s.halo_bright,
                halo_dark: s.halo_dark,
                settings: t.settings.cloned(),
                gpu_ms: t.gpu_ms,
            })
        })
        .collect::<Result<Vec<_>, ReportError>>()?;
    Ok(Report {
        scene: input.scene.to_owned(),
        camera: input.camera.to_owned(),
        scene_options: input.scene_options.to_owned(),
        width: input.width,
        height: input.height,
        guard_band: input.guard_band,
        reference: ReferenceInfo {
            model: input.reference_model.to_owned(),
            spp: input.spp,
            radius: input.reference_radius,
        },
        adapter: input.adapter.to_owned(),
        software_adapter: input.software_adapter,
        diff_scale: input.diff_scale.unwrap_or_else(|| {
            heatmap::diff_scale(input.reference, input.techniques.iter().map(|t| t.ao))
        }),
        results,
        temporal: input
            .temporal
            .as_ref()
            .map(|t| temporal::build_temporal(t, input.halo_radius_px, input.halo_relative_jump))
            .transpose()?,
    })
}

/// [`build_report`], then writes the report files into `dir`, which must
/// exist (see the module docs for the files and the failure guarantees).
///
/// # Errors
/// As [`build_report`], plus [`ReportError::Io`] when `dir` is not an
/// existing directory or a file cannot be written.
pub fn write_report(dir: &Path, input: &ReportInput) -> Result<Report, ReportError> {
    // Cheap checks first: a typo in the directory should not cost a full
    // metrics pass.
    if !dir.is_dir() {
        let message = if dir.exists() {
            "this is not a directory: pass the directory the report files should go into"
        } else {
            "the output directory does not exist: create it first (write_report does not \
             create directories)"
        };
        return Err(ReportError::Io {
            path: dir.to_path_buf(),
            message: message.to_owned(),
        });
    }
    let report = build_report(input)?;
    let scale = report.diff_scale;
    let (w, h) = (input.width, input.height);

    let mut staging = files::Staging::new(dir);
    staging.stage("reference.png", |out| {
        files::write_png(
            out,
            w,
            h,
            &files::grey8(input.reference),
            files::Color::Grey,
        )
    })?;
    for t in &input.techniques {
        staging.stage(&format!("{}.png", t.name), |out| {
            files::write_png(out, w, h, &files::grey8(t.ao), files::Color::Grey)
        })?;
        staging.stage(&format!("{}.diff.png", t.name), |out| {
            // f32 is plenty for a picture quantised to 8 bits.
            let diff: Vec<f32> =
                t.ao.iter()
                    .zip(input.reference)
                    .map(|(a, r)| a - r)
                    .collect();
            let rgb = heatmap_rgb(&diff, scale as f32);
            files::write_png(out, w, h, &rgb, files::Color::Rgb)
        })?;
    }
    staging.stage("report.json", |out| {
        serde_json::to_writer_pretty(&mut *out, &report).map_err(|e| e.to_string())?;
        out.write_all(b"\n").map_err(|e| e.to_string())
    })?;
    if let (Some(t), Some(tr)) = (&input.temporal, &report.temporal) {
        stage_temporal(&mut staging, t, tr, w, h)?;
    }
    if let Some(svg) = chart::cost_chart_svg(&report) {
        staging.stage("cost.svg", |out| {
            out.write_all(svg.as_bytes()).map_err(|e| e.to_string())
        })?;
    }
    let md = markdown::render(&report, input, scale);
    staging.stage("report.md", |out| {
        out.write_all(md.as_bytes()).map_err(|e| e.to_string())
    })?;
    let page = html::render(&report, input, scale);
    // Staged (and therefore renamed) last: see the module docs.
    staging.stage("index.html", |out| {
        out.write_all(page.as_bytes()).map_err(|e| e.to_string())
    })?;
    staging.commit()?;
    Ok(report)
}

/// The temporal section's files: two plots and an animated preview per technique and of the
/// reference.
fn stage_temporal(
    staging: &mut files::Staging,
    input: &TemporalInput,
    report: &TemporalReport,
    w: u32,
    h: u32,
) -> Result<(), ReportError> {
    let plots = [
        (
            TEMPORAL_MSE_SVG,
            "MSE against the reference, per frame",
            temporal::series_svg(
                report,
                "MSE against the reference, per frame",
                |r| &r.mse,
                false,
            ),
        ),
        (
            TEMPORAL_ERROR_SVG,
            "temporal error, per frame pair",
            temporal::series_svg(
                report,
                "temporal error (flicker beyond the reference's), per frame pair",
                |r| &r.temporal_error_pairs,
                true,
            ),
        ),
    ];
    for (file, what, svg) in plots {
        let svg =
            svg.map_err(|e| ReportError::Input(format!("plotting the {what} failed: {e}")))?;
        staging.stage(file, |out| {
            out.write_all(svg.as_bytes()).map_err(|e| e.to_string())
        })?;
    }
    let delay_ms = temporal::frame_delay_ms(input.times);
    let previews = std::iter::once(("reference", input.reference))
        .chain(input.techniques.iter().map(|&(name, ao)| (name, ao)));
    for (name, frames) in previews {
        staging.stage(&format!("{name}.gif"), |out| {
            temporal::write_gif(out, w, h, frames, delay_ms)
        })?;
    }
    Ok(())
}

/// File name of the per-frame MSE plot.
pub const TEMPORAL_MSE_SVG: &str = "temporal-mse.svg";
/// File name of the per-pair temporal error plot.
pub const TEMPORAL_ERROR_SVG: &str = "temporal-error.svg";

/// The one place that decides which file names are allowed.
fn is_valid_name(name: &str) -> bool {
    !name.is_empty()
        && name
            .bytes()
            .all(|b| b.is_ascii_lowercase() || b.is_ascii_digit() || b"+_-".contains(&b))
}

/// A valid name close to `name`, offered in the error message.
fn suggest_name(name: &str) -> String {
    let s: String = name
        .chars()
        .map(|c| {
            let c = c.to_ascii_lowercase();
            if is_valid_name(c.encode_utf8(&mut [0; 4])) {
                c
            } else {
                '-'
            }
        })
        .collect();
    if s.is_empty() || s == "reference" {
        format!("{s}-technique").trim_start_matches('-').to_owned()
    } else {
        s
    }
}

/// Checks a slice's length, naming it in the error.
fn check_len(what: &str, len: usize, width: u32, height: u32, n: usize) -> Result<(), ReportError> {
    if len == n {
        Ok(())
    } else {
        Err(ReportError::Input(format!(
            "{what} has {len} values but the image is {width}x{height} = {n} pixels: pass \
             exactly width*height values (the visible image, row-major, top row first)"
        )))
    }
}

/// The first non-finite value, named for the error message.
fn check_finite(what: &str, data: &[f32], width: u32) -> Result<(), ReportError> {
    match data.iter().position(|v| !v.is_finite()) {
        None => Ok(()),
        Some(i) => Err(ReportError::Input(format!(
            "{what} has a non-finite AO value ({}) at pixel ({}, {}): AO values must be \
             finite, nominally in [0, 1]",
            data[i],
            i % width as usize,
            i / width as usize
        ))),
    }
}

/// Every check that does not need a metric, so that inconsistent input fails
/// with a message naming the field before any work (or any file) is done.
fn validate(input: &ReportInput) -> Result<(), ReportError> {
    let (w, h) = (input.width, input.height);
    if w == 0 || h == 0 {
        return Err(ReportError::Input(format!(
            "the image is {w}x{h}: width and height must both be positive"
        )));
    }
    let n = (w as usize).checked_mul(h as usize).ok_or_else(|| {
        ReportError::Input(format!("a {w}x{h} image is too large for this platform"))
    })?;

    let image = input.reference_model.starts_with("image '");
    match (input.reference_model, input.spp) {
        ("vao" | "vao-mean", None) => {}
        (_, None) if image => {}
        (model, Some(spp)) if image => {
            return Err(ReportError::Input(format!(
                "spp is Some({spp}) but the reference {model} was not traced here: pass spp: None"
            )))
        }
        ("vao" | "vao-mean", Some(spp)) => {
            return Err(ReportError::Input(format!(
                "spp is Some({spp}) but the \"vao\" reference model has no rays per pixel: \
                 pass spp: None"
            )))
        }
        ("hemisphere", Some(spp)) if spp > 0 => {}
        ("hemisphere", _) => {
            return Err(ReportError::Input(
                "the \"hemisphere\" reference model needs spp: Some(rays per pixel), at least 1"
                    .to_owned(),
            ))
        }
        (model, _) => {
            return Err(ReportError::Input(format!(
                "unknown reference_model {model:?}: use \"vao\", \"vao-mean\", \"hemisphere\" or \
                 \"image 'FILE'\""
            )))
        }
    }

    if let Some(r) = input
        .reference_radius
        .filter(|r| !(r.is_finite() && *r > 0.0))
    {
        return Err(ReportError::Input(format!(
            "reference_radius is Some({r}): pass the ground truth's radius in world units (> 0), \
             or None where it is not known"
        )));
    }

    if input.techniques.is_empty() {
        return Err(ReportError::Input(
            "no techniques: a report compares at least one technique against the reference"
                .to_owned(),
        ));
    }
    for (i, t) in input.techniques.iter().enumerate() {
        if !is_valid_name(t.name) {
            return Err(ReportError::Input(format!(
                "technique name {:?} cannot be used in file names ({0}.png, {0}.diff.png): use \
                 only lowercase ASCII letters, digits, '+', '_' and '-', e.g. {:?}",
                t.name,
                suggest_name(t.name)
            )));
        }
        if t.name == "reference" {
            return Err(ReportError::Input(
                "technique name \"reference\" would overwrite reference.png: rename the technique"
                    .to_owned(),
            ));
        }
        if input.techniques[..i].iter().any(|o| o.name == t.name) {
            return Err(ReportError::Input(format!(
                "technique name {:?} appears twice: names must be unique (they name the files)",
                t.name
            )));
        }
    }

    check_len("reference", input.reference.len(), w, h, n)?;
    check_len("depth", input.depth.len(), w, h, n)?;
    for t in &input.techniques {
        check_len(&format!("technique {:?}", t.name), t.ao.len(), w, h, n)?;
    }
    // The metrics check this too, but cannot say *which* technique is bad.
    check_finite("reference", input.reference, w)?;
    for t in &input.techniques {
        check_finite(&format!("technique {:?}", t.name), t.ao, w)?;
    }
    if let Some(temporal) = &input.temporal {
        let names: Vec<&str> = input.techniques.iter().map(|t| t.name).collect();
        let path_names: Vec<&str> = temporal.techniques.iter().map(|t| t.0).collect();
        if names != path_names {
            return Err(ReportError::Input(format!(
                "the camera path's techniques {path_names:?} differ from the report's {names:?}: \
                 pass the same techniques in the same order"
            )));
        }
        for frame in temporal.frames {
            if (frame.view.width, frame.view.height) != (w, h) {
                return Err(ReportError::Input(format!(
                    "a camera path frame is {}x{} but the report is {w}x{h}: render the path at \
                     the report's size",
                    frame.view.width, frame.view.height
                )));
            }
        }
    }
    Ok(())
}

/// The metric cells of a table row, shared by the Markdown and HTML tables (and the demo page)
/// so that all print the same numbers. The JSON keeps full precision; these are for reading.
pub fn metric_cells(r: &TechniqueResult, software_adapter: bool) -> [String; 7] {
    let psnr = if r.psnr == f64::INFINITY {
        "∞".to_owned()
    } else if r.psnr.is_nan() {
        "n/a".to_owned()
    } else {
        format!("{:.2}", r.psnr)
    };
    let ms = match r.gpu_ms {
        // A CPU adapter's time says nothing about a GPU: shown, but marked.
        Some(ms) if software_adapter => format!("{ms:.1} (CPU)"),
        Some(ms) => format!("{ms:.3}"),
        None => "–".to_owned(),
    };
    [
        // MSE spans orders of magnitude between techniques: scientific
        // notation keeps its significant digits comparable.
        if r.mse.is_nan() {
            "n/a".to_owned()
        } else {
            format!("{:.3e}", r.mse)
        },
        fixed4(r.mae),
        psnr,
        fixed4(r.ssim),
        fixed4(r.halo_bright),
        fixed4(r.halo_dark),
        ms,
    ]
}

/// One sentence naming the techniques on the Pareto front of MSE against time ([`pareto_front`]),
/// and what the times are.
pub fn verdict(report: &Report) -> String {
    let front = pareto_front(&report.results);
    let times = if report.software_adapter {
        "the times come from a CPU (software) adapter and say nothing about a GPU"
    } else {
        "GPU time per frame without the G-buffer, median of the measured frames"
    };
    match front.as_slice() {
        [] => format!("No technique was timed ({times})."),
        [one] => format!(
            "{one} is both the fastest and the most accurate of these techniques ({times})."
        ),
        _ => format!(
            "Pareto front (no other technique is both faster and more accurate), fastest first: \
             {} ({times}).",
            front_by_time(report, &front).join(", ")
        ),
    }
}

/// `front` sorted by time, fastest first.
fn front_by_time<'a>(report: &Report, front: &[&'a str]) -> Vec<&'a str> {
    let ms = |name: &str| {
        report
            .results
            .iter()
            .find(|r| r.technique == name)
            .and_then(|r| r.gpu_ms)
            .unwrap_or(f64::INFINITY)
    };
    let mut sorted = front.to_vec();
    sorted.sort_by(|a, b| ms(a).total_cmp(&ms(b)));
    sorted
}

/// Four decimals; a value that rounds to zero prints as `0.0000`, never `-0.0000`.
pub fn fixed4(v: f64) -> String {
    if v.is_nan() {
        return "n/a".to_owned();
    }
    let rounded = (v * 1e4).round() / 1e4;
    // `+ 0.0` turns −0 into +0.
    format!("{:.4}", rounded + 0.0)
}

/// Column headers matching [`metric_cells`].
pub const METRIC_HEADERS: [&str; 7] = [
    "MSE",
    "MAE",
    "PSNR (dB)",
    "SSIM",
    "bright halo",
    "dark halo",
    "GPU ms",
];

/// `"vao, R = 0.5"` or `"hemisphere, R = 1, 256 rays per pixel"`.
fn reference_description(info: &ReferenceInfo) -> String {
    let mut out = info.model.clone();
    if let Some(r) = info.radius {
        out += &format!(", R = {r}");
    }
    if let Some(spp) = info.spp {
        out += &format!(", {spp} rays per pixel");
    }
    out
}

/// The heat map scale as printed in legends: `0.05`, `1`, or `2e30` for
/// absurd inputs.
fn format_scale(scale: f64) -> String {
    if scale < 1e4 {
        format!("{scale}")
    } else {
        format!("{scale:e}")
    }
}
