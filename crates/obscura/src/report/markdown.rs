//! `report.md`: the metrics as a Markdown table.

use super::{
    format_scale, metric_cells, reference_description, Report, ReportInput, METRIC_HEADERS,
};
use std::fmt::Write;

/// Backslash-escapes the characters Markdown could interpret in free text
/// (scene and camera names are arbitrary strings) and flattens line breaks,
/// which would end the header line or a table row.
fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        if c.is_control() {
            out.push(' ');
        } else {
            if "\\`*_[]<>|~&#!".contains(c) {
                out.push('\\');
            }
            out.push(c);
        }
    }
    out
}

pub(super) fn render(report: &Report, input: &ReportInput, scale: f64) -> String {
    let mut md = String::new();
    write_md(&mut md, report, input, scale).expect("writing to a String cannot fail");
    md
}

fn write_md(md: &mut String, report: &Report, input: &ReportInput, scale: f64) -> std::fmt::Result {
    writeln!(
        md,
        "# AO report: scene {}, camera {}, {}×{}, reference {}",
        escape(&report.scene),
        escape(&report.camera),
        report.width,
        report.height,
        escape(&reference_description(&report.reference)),
    )?;
    writeln!(md)?;
    writeln!(md, "| technique | {} |", METRIC_HEADERS.join(" | "))?;
    writeln!(md, "|:--|{}", "--:|".repeat(METRIC_HEADERS.len()))?;
    for r in &report.results {
        // Technique names are `[a-z0-9+_-]+`: safe inside a code span.
        writeln!(
            md,
            "| `{}` | {} |",
            r.technique,
            metric_cells(r, report.software_adapter).join(" | ")
        )?;
    }
    writeln!(md)?;
    if report.results.iter().any(|r| r.gpu_ms.is_some()) {
        writeln!(md, "{}", escape(&super::verdict(report)))?;
        writeln!(md)?;
    }
    if let Some(t) = &report.temporal {
        use super::temporal::{temporal_cells, temporal_explanation, TEMPORAL_HEADERS};
        writeln!(md, "## Along the camera path {}", escape(&t.path))?;
        writeln!(md)?;
        writeln!(md, "| technique | {} |", TEMPORAL_HEADERS.join(" | "))?;
        writeln!(md, "|:--|{}", "--:|".repeat(TEMPORAL_HEADERS.len()))?;
        for r in &t.results {
            writeln!(
                md,
                "| `{}` | {} |",
                r.technique,
                temporal_cells(r, t).join(" | ")
            )?;
        }
        writeln!(md)?;
        writeln!(md, "{}", escape(&temporal_explanation(t)))?;
        writeln!(md)?;
        writeln!(
            md,
            "Plots: `{}`, `{}`; animated previews: `reference.gif`, `<technique>.gif`.",
            super::TEMPORAL_MSE_SVG,
            super::TEMPORAL_ERROR_SVG
        )?;
        writeln!(md)?;
    }
    writeln!(
        md,
        "Guard band {} px. Scene options: {}. GPU adapter: {}.",
        report.guard_band,
        escape(&report.scene_options),
        escape(input.adapter)
    )?;
    writeln!(md)?;
    writeln!(
        md,
        "PSNR ∞ (`null` in report.json): identical to the reference. Bright halo: mean positive \
         error (technique − reference) over pixels within {} px of a depth discontinuity \
         (relative jump > {}), i.e. missing occlusion around silhouettes. Dark halo: mean \
         negative error over the same pixels, i.e. excess occlusion there.",
        input.halo_radius_px, input.halo_relative_jump
    )?;
    writeln!(md)?;
    writeln!(
        md,
        "Heat maps (`<technique>.diff.png`): technique − reference, blue −{s} … white 0 … red \
         +{s}, the same scale for every technique.",
        s = format_scale(scale)
    )
}
