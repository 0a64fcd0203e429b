//! The temporal part of a report (`compare --path`, issue 13): every technique's AO along a
//! camera path against the reference's, with the metrics of [`crate::metrics::temporal`], the
//! per-frame error, plots of both (SVG through `plotters`) and animated previews (GIF).

use super::files;
use super::ReportError;
use crate::metrics::temporal::{path_metrics, PathFrame};
use crate::metrics::{self, Image};
use plotters::prelude::*;

/// The frames of a path and every technique's AO along it.
#[derive(Clone, Debug)]
pub struct TemporalInput<'a> {
    /// The path's name (a built-in's, a file's).
    pub path: &'a str,
    /// Each frame's time along the path, seconds.
    pub times: &'a [f32],
    /// Each frame's view and visible linear depth.
    pub frames: &'a [PathFrame<'a>],
    /// The reference AO of each frame.
    pub reference: &'a [Vec<f32>],
    /// Each technique's name and AO per frame, in table order.
    pub techniques: Vec<(&'a str, &'a [Vec<f32>])>,
}

/// One technique's temporal results.
#[derive(serde::Serialize, serde::Deserialize, Clone, Debug, PartialEq)]
pub struct TemporalResult {
    /// Technique name.
    pub technique: String,
    /// Mean |(a_t − a'_{t−1}) − (r_t − r'_{t−1})| over matched pixels of all frame pairs.
    pub temporal_error: f64,
    /// Fraction of matched pixels that pop (AO change > 0.1 where the reference's < 0.02).
    pub popping: f64,
    /// MSE against the reference, per frame.
    pub mse: Vec<f64>,
    /// Bright halo (mean positive error near depth discontinuities), per frame.
    pub halo_bright: Vec<f64>,
    /// Temporal error per frame pair (entry k: frame k to k + 1).
    pub temporal_error_pairs: Vec<f64>,
    /// Popping per frame pair.
    pub popping_pairs: Vec<f64>,
    /// The frame with the largest MSE, and that MSE (the worst frame is what a viewer sees).
    pub worst_frame: usize,
    /// The largest per-frame MSE.
    pub worst_mse: f64,
}

/// The temporal section of a report.
#[derive(serde::Serialize, serde::Deserialize, Clone, Debug, PartialEq)]
pub struct TemporalReport {
    /// The path's name.
    pub path: String,
    /// Each frame's time, seconds.
    pub times: Vec<f32>,
    /// Fraction of pixels matched to the previous frame, per frame pair (the same for every
    /// technique: it depends on the geometry only).
    pub matched: Vec<f64>,
    /// One entry per technique.
    pub results: Vec<TemporalResult>,
}

/// Computes the temporal section; `halo_radius_px`/`halo_relative_jump` as the report's.
pub fn build_temporal(
    input: &TemporalInput,
    halo_radius_px: usize,
    halo_relative_jump: f32,
) -> Result<TemporalReport, ReportError> {
    let n = input.frames.len();
    if n < 2 || input.times.len() != n || input.reference.len() != n {
        return Err(ReportError::Input(format!(
            "a temporal report needs at least 2 frames with one time and one reference image \
             each (got {n} frames, {} times, {} reference images)",
            input.times.len(),
            input.reference.len()
        )));
    }
    let (w, h) = (
        input.frames[0].view.width as usize,
        input.frames[0].view.height as usize,
    );
    let mut matched = Vec::new();
    let results = input
        .techniques
        .iter()
        .map(|&(name, ao)| {
            if ao.len() != n {
                return Err(ReportError::Input(format!(
                    "technique '{name}' has {} frames but the path has {n}",
                    ao.len()
                )));
            }
            let m = path_metrics(input.frames, ao, input.reference)?;
            matched = m.pairs.iter().map(|p| p.matched).collect();
            let mut mse = Vec::with_capacity(n);
            let mut halo = Vec::with_capacity(n);
            for (f, frame) in input.frames.iter().enumerate() {
                let s = metrics::summarize(
                    &Image::new(w, h, &ao[f])?,
                    &Image::new(w, h, &input.reference[f])?,
                    &Image::new(w, h, frame.depth)?,
                    halo_radius_px,
                    halo_relative_jump,
                )?;
                mse.push(s.mse);
                halo.push(s.halo_bright);
            }
            let (worst_frame, worst_mse) = mse
                .iter()
                .copied()
                .enumerate()
                .fold((0, f64::NEG_INFINITY), |a, b| if b.1 > a.1 { b } else { a });
            Ok(TemporalResult {
                technique: name.to_owned(),
                temporal_error: m.temporal_error,
                popping: m.popping,
                mse,
                halo_bright: halo,
                temporal_error_pairs: m.pairs.iter().map(|p| p.temporal_error).collect(),
                popping_pairs: m.pairs.iter().map(|p| p.popping).collect(),
                worst_frame,
                worst_mse,
            })
        })
        .collect::<Result<Vec<_>, ReportError>>()?;
    Ok(TemporalReport {
        path: input.path.to_owned(),
        times: input.times.to_vec(),
        matched,
        results,
    })
}

/// A line chart of one series per technique against time, as SVG text. `pairs`: the series
/// has one value per frame pair, plotted at the later frame's time.
pub fn series_svg(
    report: &TemporalReport,
    title: &str,
    series: impl Fn(&TemporalResult) -> &[f64],
    pairs: bool,
) -> Result<String, String> {
    let times: &[f32] = if pairs {
        &report.times[1..]
    } else {
        &report.times
    };
    let top = report
        .results
        .iter()
        .flat_map(|r| series(r).iter().copied())
        .filter(|v| v.is_finite())
        .fold(0.0f64, f64::max)
        .max(1e-6)
        * 1.1;
    let (t0, t1) = (
        f64::from(report.times[0]),
        f64::from(*report.times.last().expect("at least 2 frames")),
    );
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (640, 320)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 16))
            .margin(10)
            .x_label_area_size(32)
            .y_label_area_size(60)
            .build_cartesian_2d(t0..t1.max(t0 + 1e-3), 0.0..top)
            .map_err(|e| e.to_string())?;
        chart
            .configure_mesh()
            .x_desc("time along the path (s)")
            .draw()
            .map_err(|e| e.to_string())?;
        for (k, r) in report.results.iter().enumerate() {
            let color = Palette99::pick(k).to_rgba();
            chart
                .draw_series(LineSeries::new(
                    times
                        .iter()
                        .zip(series(r))
                        .map(|(&t, &v)| (f64::from(t), v)),
                    color.stroke_width(2),
                ))
                .map_err(|e| e.to_string())?
                .label(r.technique.clone())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 16, y)], color.stroke_width(2))
                });
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .draw()
            .map_err(|e| e.to_string())?;
        root.present().map_err(|e| e.to_string())?;
    }
    Ok(svg)
}

/// An animation's frame time: the path's time between frames, kept within what GIF viewers
/// show (20 ms to 1 s).
pub fn frame_delay_ms(times: &[f32]) -> u32 {
    let span = times.last().copied().unwrap_or(0.0) - times.first().copied().unwrap_or(0.0);
    let per_frame = 1000.0 * span / times.len().saturating_sub(1).max(1) as f32;
    (per_frame.round() as u32).clamp(20, 1000)
}

/// The frames of `ao` as an animated grey GIF, `delay_ms` per frame, looping.
pub fn write_gif(
    out: &mut dyn std::io::Write,
    width: u32,
    height: u32,
    frames: &[Vec<f32>],
    delay_ms: u32,
) -> Result<(), String> {
    use ::image::codecs::gif::{GifEncoder, Repeat};
    use ::image::{Delay, Frame, RgbaImage};
    let mut encoder = GifEncoder::new_with_speed(out, 10);
    encoder
        .set_repeat(Repeat::Infinite)
        .map_err(|e| e.to_string())?;
    for ao in frames {
        let rgba: Vec<u8> = files::grey8(ao)
            .into_iter()
            .flat_map(|g| [g, g, g, 255])
            .collect();
        let image = RgbaImage::from_raw(width, height, rgba)
            .ok_or_else(|| "frame size does not match the image".to_string())?;
        encoder
            .encode_frame(Frame::from_parts(
                image,
                0,
                0,
                Delay::from_numer_denom_ms(delay_ms, 1),
            ))
            .map_err(|e| format!("GIF encoding failed: {e}"))?;
    }
    Ok(())
}

/// The temporal table's header cells.
pub const TEMPORAL_HEADERS: [&str; 5] = [
    "temporal error",
    "popping",
    "mean MSE",
    "worst-frame MSE",
    "worst frame",
];

/// One technique's cells under [`TEMPORAL_HEADERS`].
pub fn temporal_cells(r: &TemporalResult, report: &TemporalReport) -> [String; 5] {
    let mean_mse = r.mse.iter().sum::<f64>() / r.mse.len().max(1) as f64;
    [
        format!("{:.5}", r.temporal_error),
        format!("{:.2} %", 100.0 * r.popping),
        format!("{mean_mse:.3e}"),
        format!("{:.3e}", r.worst_mse),
        format!(
            "{} (t = {:.2} s)",
            r.worst_frame,
            report.times.get(r.worst_frame).copied().unwrap_or(0.0)
        ),
    ]
}

/// The sentence under the temporal table: what was matched and how the metrics are defined.
pub fn temporal_explanation(report: &TemporalReport) -> String {
    let (lo, hi) = report
        .matched
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), &m| {
            (lo.min(m), hi.max(m))
        });
    format!(
        "{} frames from t = {:.2} s to {:.2} s. Pixels are matched between consecutive frames by \
         reprojection (the camera motion is known, the scene static); {:.1}–{:.1} % of the \
         pixels were matched per frame pair, disocclusions and background excluded. Temporal \
         error: mean |(a_t − a_t−1) − (r_t − r_t−1)| over matched pixels, a the technique's AO, r \
         the reference's: change the reference does not have. Popping: the share of matched \
         pixels whose AO changes by more than {} while the reference's changes by less than {}.",
        report.times.len(),
        report.times.first().copied().unwrap_or(0.0),
        report.times.last().copied().unwrap_or(0.0),
        100.0 * lo,
        100.0 * hi,
        crate::metrics::temporal::POP_CHANGE,
        crate::metrics::temporal::POP_REFERENCE_STILL,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Camera;
    use crate::view::FrameView;
    use glam::Vec3;

    #[test]
    fn builds_plots_and_animates_a_small_path() {
        let (w, h) = (16u32, 12u32);
        let view = FrameView::new(
            Camera::new(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, 60.0).unwrap(),
            w,
            h,
            0,
            0.1,
        );
        let depth = vec![5.0; (w * h) as usize];
        let frames = [PathFrame {
            view,
            depth: &depth,
        }; 3];
        let reference = vec![vec![0.5; (w * h) as usize]; 3];
        // One technique flickers on every other frame; the other equals the reference.
        let flicker: Vec<Vec<f32>> = (0..3)
            .map(|f| vec![if f == 1 { 0.8 } else { 0.5 }; (w * h) as usize])
            .collect();
        let input = TemporalInput {
            path: "still",
            times: &[0.0, 0.5, 1.0],
            frames: &frames,
            reference: &reference,
            techniques: vec![("flicker", &flicker), ("exact", &reference)],
        };
        let report = build_temporal(&input, 4, 0.1).unwrap();
        let flicker = &report.results[0];
        assert!((flicker.temporal_error - 0.3).abs() < 1e-5, "{flicker:?}");
        assert_eq!(flicker.popping, 1.0);
        assert_eq!(flicker.worst_frame, 1);
        assert!((flicker.worst_mse - 0.09).abs() < 1e-5);
        assert_eq!(report.results[1].temporal_error, 0.0);
        assert_eq!(report.matched.len(), 2);
        let svg = series_svg(&report, "MSE per frame", |r| &r.mse, false).unwrap();
        assert!(svg.starts_with("<svg") && svg.contains("flicker") && svg.contains("exact"));
        let mut gif = Vec::new();
        write_gif(&mut gif, w, h, input.reference, 100).unwrap();
        assert!(gif.starts_with(b"GIF89a"), "{:?}", &gif[..6]);

        // Through write_report: the section, its plots and previews land beside the report.
        let dir = tempfile::tempdir().unwrap();
        let report_input = crate::report::ReportInput {
            scene: "plane",
            camera: "path still, frame 1",
            scene_options: "",
            width: w,
            height: h,
            guard_band: 0,
            reference_model: "vao",
            spp: None,
            reference_radius: None,
            reference: &reference[1],
            depth: &depth,
            techniques: ["flicker", "exact"]
                .into_iter()
                .zip([&input.techniques[0].1[1], &reference[1]])
                .map(|(name, ao)| crate::report::TechniqueImage {
                    name,
                    ao,
                    settings: None,
                    gpu_ms: None,
                })
                .collect(),
            halo_radius_px: 4,
            halo_relative_jump: 0.1,
            adapter: "test",
            software_adapter: true,
            diff_scale: None,
            temporal: Some(input.clone()),
        };
        let written = crate::report::write_report(dir.path(), &report_input).unwrap();
        assert_eq!(written.temporal.as_ref(), Some(&report));
        for file in [
            "temporal-mse.svg",
            "temporal-error.svg",
            "reference.gif",
            "flicker.gif",
            "exact.gif",
        ] {
            assert!(dir.path().join(file).is_file(), "{file} missing");
        }
        let md = std::fs::read_to_string(dir.path().join("report.md")).unwrap();
        assert!(
            md.contains("Along the camera path still")
                && md.contains("| `flicker` | 0.30000 | 100.00 %"),
            "{md}"
        );
        let html = std::fs::read_to_string(dir.path().join("index.html")).unwrap();
        assert!(html.contains("temporal-error.svg") && html.contains("flicker.gif"));
        let json: crate::report::Report =
            serde_json::from_str(&std::fs::read_to_string(dir.path().join("report.json")).unwrap())
                .unwrap();
        assert_eq!(json.temporal.unwrap().results[0].popping, 1.0);
        // The path's techniques must be the report's.
        let mut swapped = report_input.clone();
        swapped.temporal.as_mut().unwrap().techniques.reverse();
        let err = crate::report::build_report(&swapped)
            .unwrap_err()
            .to_string();
        assert!(err.contains("same techniques"), "{err}");

        let short = TemporalInput {
            times: &[0.0],
            frames: &frames[..1],
            reference: &reference[..1],
            ..input.clone()
        };
        assert!(build_temporal(&short, 4, 0.1).is_err());
    }
}
