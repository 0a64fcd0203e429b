//! `index.html`: one self-contained page — inline CSS, no script, no external
//! resource, only relative links to the PNGs beside it — so that it opens
//! straight from disk (or from an archived results folder) with no server.

use super::heatmap::{NEGATIVE_END, POSITIVE_END, ZERO};
use super::{
    format_scale, metric_cells, reference_description, Report, ReportInput, METRIC_HEADERS,
};
use std::fmt::{self, Write};

/// Images narrower than this are shown upscaled with hard pixel edges (a
/// blurred 64×48 test image hides exactly what one wants to see); larger ones
/// are usually shown downscaled, where smooth filtering is the better choice.
const PIXELATED_BELOW: u32 = 400;

/// Escapes text for HTML element content and attribute values.
pub(super) fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

pub(super) fn css_rgb([r, g, b]: [u8; 3]) -> String {
    format!("rgb({r}, {g}, {b})")
}

pub(super) fn render(report: &Report, input: &ReportInput, scale: f64) -> String {
    let mut page = String::new();
    write_page(&mut page, report, input, scale).expect("writing to a String cannot fail");
    page
}

const STYLE: &str = "
body { font-family: system-ui, -apple-system, 'Segoe UI', sans-serif; margin: 1.5em; color: #222; background: #fff; }
h1 { font-size: 1.4em; }
h2 { font-size: 1.2em; margin-top: 1.5em; }
h3 { font-size: 1.05em; margin: 1.2em 0 0.4em; }
code { font-size: 0.95em; }
dl.info { display: grid; grid-template-columns: max-content auto; gap: 0.2em 1em; }
dl.info dt { font-weight: 600; }
dl.info dd { margin: 0; }
table.metrics { border-collapse: collapse; }
table.metrics th, table.metrics td { border: 1px solid #ccc; padding: 0.25em 0.7em; }
table.metrics th { background: #f3f3f3; }
table.metrics td.num { text-align: right; font-variant-numeric: tabular-nums; }
.row { display: grid; grid-template-columns: repeat(3, minmax(0, 1fr)); gap: 0.8em; }
figure { margin: 0; }
figure img { display: block; width: 100%; height: auto; background: #808080; }
figcaption { font-size: 0.9em; margin-top: 0.3em; }
.legend { margin-top: 0.3em; }
.legend .bar { height: 0.9em; border: 1px solid #888; }
.legend .labels { display: flex; justify-content: space-between; font-size: 0.85em; font-variant-numeric: tabular-nums; }
";

fn write_page(page: &mut String, report: &Report, input: &ReportInput, scale: f64) -> fmt::Result {
    let title = format!(
        "AO report: {}, camera {}",
        escape(&report.scene),
        escape(&report.camera)
    );
    writeln!(page, "<!DOCTYPE html>")?;
    writeln!(page, "<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">")?;
    writeln!(
        page,
        "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">"
    )?;
    writeln!(page, "<title>{title}</title>")?;
    write!(page, "<style>{STYLE}")?;
    if report.width < PIXELATED_BELOW {
        writeln!(page, "figure img {{ image-rendering: pixelated; }}")?;
    }
    // CSS interpolates legacy `rgb()` colours in sRGB, linearly, exactly like
    // `heatmap_rgb`: the bar is the heat map's own colour ramp.
    writeln!(
        page,
        ".legend .bar {{ background: linear-gradient(to right, {}, {}, {}); }}",
        css_rgb(NEGATIVE_END),
        css_rgb(ZERO),
        css_rgb(POSITIVE_END)
    )?;
    writeln!(page, "</style>\n</head>\n<body>")?;
    writeln!(page, "<h1>{title}</h1>")?;

    writeln!(page, "<dl class=\"info\">")?;
    let info = [
        ("scene", escape(&report.scene)),
        ("camera", escape(&report.camera)),
        ("scene options", escape(&report.scene_options)),
        (
            "size",
            format!(
                "{}×{} px, guard band {} px",
                report.width, report.height, report.guard_band
            ),
        ),
        (
            "reference",
            escape(&reference_description(&report.reference)),
        ),
        ("adapter", escape(input.adapter)),
        (
            "halo band",
            format!(
                "pixels within {} px of a depth discontinuity (relative depth jump &gt; {})",
                input.halo_radius_px, input.halo_relative_jump
            ),
        ),
        (
            "heat map scale",
            format!(
                "±{} (technique − reference, same for every technique)",
                format_scale(scale)
            ),
        ),
    ];
    for (term, value) in info {
        writeln!(page, "<dt>{term}</dt><dd>{value}</dd>")?;
    }
    writeln!(page, "</dl>")?;

    writeln!(page, "<h2>Metrics</h2>")?;
    writeln!(
        page,
        "<table class=\"metrics\">\n<thead><tr><th>technique</th>"
    )?;
    for h in METRIC_HEADERS {
        write!(page, "<th>{h}</th>")?;
    }
    writeln!(page, "</tr></thead>\n<tbody>")?;
    for r in &report.results {
        // Technique names are `[a-z0-9+_-]+`, valid in ids and fragments.
        write!(
            page,
            "<tr><td><a href=\"#t-{0}\"><code>{0}</code></a></td>",
            r.technique
        )?;
        for cell in metric_cells(r, report.software_adapter) {
            write!(page, "<td class=\"num\">{cell}</td>")?;
        }
        writeln!(page, "</tr>")?;
    }
    writeln!(page, "</tbody>\n</table>")?;
    if report.results.iter().any(|r| r.gpu_ms.is_some()) {
        writeln!(page, "<h2>Quality against cost</h2>")?;
        writeln!(page, "<p>{}</p>", escape(&super::verdict(report)))?;
        writeln!(
            page,
            "<figure><img src=\"cost.svg\" alt=\"MSE against milliseconds per technique\" \
             style=\"max-width: 640px\"></figure>"
        )?;
    }
    writeln!(page, "<ul>")?;
    writeln!(
        page,
        "<li>MSE, MAE: mean squared and mean absolute difference to the reference; PSNR = \
         10·log10(1/MSE), ∞ for an exact match (<code>null</code> in report.json); SSIM: mean \
         structural similarity (11×11 Gaussian window, 1 = identical).</li>"
    )?;
    writeln!(
        page,
        "<li>Bright halo: the mean positive error (technique brighter than the reference) over \
         the halo band, i.e. occlusion the technique misses around silhouettes.</li>"
    )?;
    writeln!(
        page,
        "<li>Dark halo: the mean negative error (technique darker than the reference) over the \
         same band, i.e. occlusion it adds there; 0 is best for both.</li>"
    )?;
    writeln!(page, "</ul>")?;

    if let Some(t) = &report.temporal {
        write_temporal(page, report, t)?;
    }
    writeln!(page, "<h2>Images</h2>")?;
    writeln!(
        page,
        "<p>AO as grey (white = unoccluded). Heat maps: technique − reference; blue = darker \
         than the reference, white = equal, red = brighter; saturated beyond ±{}. Click an \
         image for full size.</p>",
        format_scale(scale)
    )?;
    let reference_caption = format!(
        "reference ({})",
        escape(&reference_description(&report.reference))
    );
    for r in &report.results {
        let name = &r.technique;
        writeln!(page, "<h3 id=\"t-{name}\"><code>{name}</code></h3>")?;
        writeln!(page, "<div class=\"row\">")?;
        write_figure(page, report, "reference.png", &reference_caption, "")?;
        write_figure(
            page,
            report,
            &format!("{name}.png"),
            &format!("<code>{name}</code>"),
            "",
        )?;
        let legend = format!(
            "<div class=\"legend\"><div class=\"bar\"></div><div class=\"labels\">\
             <span>−{s}</span><span>0</span><span>+{s}</span></div></div>",
            s = format_scale(scale)
        );
        write_figure(
            page,
            report,
            &format!("{name}.diff.png"),
            &format!("<code>{name}</code> − reference"),
            &legend,
        )?;
        writeln!(page, "</div>")?;
    }
    writeln!(page, "</body>\n</html>")
}

/// One image, linked to itself for full-size viewing. `caption` and `extra`
/// are HTML.
fn write_figure(
    page: &mut String,
    report: &Report,
    file: &str,
    caption: &str,
    extra: &str,
) -> fmt::Result {
    // The size attributes reserve the right aspect ratio before the image
    // loads; the CSS scales it to the column.
    writeln!(
        page,
        "<figure><a href=\"{file}\"><img src=\"{file}\" width=\"{w}\" height=\"{h}\" \
         alt=\"{file}\"></a><figcaption>{caption}{extra}</figcaption></figure>",
        w = report.width,
        h = report.height
    )
}

/// The camera-path section: the temporal table, the two plots and the animated previews.
fn write_temporal(
    page: &mut String,
    report: &Report,
    t: &super::temporal::TemporalReport,
) -> fmt::Result {
    use super::temporal::{temporal_cells, temporal_explanation, TEMPORAL_HEADERS};
    writeln!(
        page,
        "<h2>Along the camera path <code>{}</code></h2>",
        escape(&t.path)
    )?;
    writeln!(
        page,
        "<table class=\"metrics\">\n<thead><tr><th>technique</th>"
    )?;
    for h in TEMPORAL_HEADERS {
        write!(page, "<th>{h}</th>")?;
    }
    writeln!(page, "</tr></thead>\n<tbody>")?;
    for r in &t.results {
        write!(page, "<tr><td><code>{}</code></td>", r.technique)?;
        for cell in temporal_cells(r, t) {
            write!(page, "<td class=\"num\">{cell}</td>")?;
        }
        writeln!(page, "</tr>")?;
    }
    writeln!(page, "</tbody>\n</table>")?;
    writeln!(page, "<p>{}</p>", escape(&temporal_explanation(t)))?;
    for (file, alt) in [
        (super::TEMPORAL_MSE_SVG, "MSE per frame per technique"),
        (
            super::TEMPORAL_ERROR_SVG,
            "temporal error per frame pair per technique",
        ),
    ] {
        writeln!(
            page,
            "<figure><img src=\"{file}\" alt=\"{alt}\" style=\"max-width: 640px\"></figure>"
        )?;
    }
    writeln!(page, "<h3>Animated</h3>\n<div class=\"row\">")?;
    write_figure(page, report, "reference.gif", "reference", "")?;
    for r in &t.results {
        let name = &r.technique;
        write_figure(
            page,
            report,
            &format!("{name}.gif"),
            &format!("<code>{name}</code>"),
            "",
        )?;
    }
    writeln!(page, "</div>")
}
