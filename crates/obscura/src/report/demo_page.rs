//! The demo page (`obscura demo`): every scene's reports on one self-contained page — a verdict
//! per scene, one sortable table of every row, and per scene a collapsible grid of images.
//!
//! Each row is scored against the reference of the quantity its estimator computes
//! ([`fair_reference`]): a horizon estimator scored against the VAO model's reference shows the
//! difference of the two models, not its own error (issue 62). A scene therefore has one
//! [`Report`] per reference model, each written by [`super::write_report`] into its own folder.
//!
//! Like `index.html` of a report, the page opens from disk: inline CSS, one inline script (the
//! table's sorting; the page reads the same without it), relative links only.

use super::heatmap::{NEGATIVE_END, POSITIVE_END, ZERO};
use super::html::{css_rgb, escape};
use super::{fixed4, format_scale, metric_cells, reference_description, Report, TechniqueResult};
use crate::reference::ground_truth::ReferenceModel;
use crate::technique::Estimator;
use crate::technique::Technique;
use std::fmt::{self, Write};

/// The reference a row is scored against: the `vao` model for rows whose estimator is VAO (the
/// quantity seed 000 §3.6 defines for it), the `hemisphere` model for every other estimator
/// (the horizon, obscurance and hemisphere estimators approximate cosine-weighted visibility
/// within R, seed 001 §3.2, seed 003).
pub fn fair_reference(technique: Technique) -> ReferenceModel {
    if technique.estimator() == Estimator::Vao {
        ReferenceModel::Vao
    } else {
        ReferenceModel::Hemisphere
    }
}

/// One report of a scene: the rows scored against one reference.
#[derive(Clone, Copy, Debug)]
pub struct DemoReport<'a> {
    /// Its folder, relative to the page (`stairs/vao`): its images, `cost.svg` and `index.html`.
    pub folder: &'a str,
    /// The report.
    pub report: &'a Report,
}

/// One scene of the page.
#[derive(Clone, Debug)]
pub struct DemoScene<'a> {
    /// Scene name; also the folder of its composites (`NAME/<technique>.composite.png`).
    pub name: &'a str,
    /// Camera name.
    pub camera: &'a str,
    /// One report per reference model, in page order.
    pub reports: Vec<DemoReport<'a>>,
}

/// Everything on the page.
#[derive(Clone, Debug)]
pub struct DemoPage<'a> {
    /// Adapter and backend, printed.
    pub adapter: &'a str,
    /// What the techniques ran with (size, radius, …), printed as text.
    pub settings: &'a str,
    /// The adapter is a CPU (software) device: its times do not rank GPU cost.
    pub software_adapter: bool,
    /// The one heat-map scale every report of the page was written with.
    pub diff_scale: f64,
    /// Each scene folder holds `<technique>.composite.png` (AO × colour).
    pub composites: bool,
    /// The scenes, in page order.
    pub scenes: Vec<DemoScene<'a>>,
}

/// A time as the page prints it: `0.123 ms`, or `2.2 ms (CPU)` from a software adapter.
pub fn format_ms(ms: f64, software_adapter: bool) -> String {
    if software_adapter {
        format!("{ms:.1} ms (CPU)")
    } else {
        format!("{ms:.3} ms")
    }
}

/// Which rows a reference model is fair to, in words.
fn family(model: &str) -> &'static str {
    match model {
        "vao" | "vao-mean" => "rows whose estimator is VAO",
        "hemisphere" => "horizon, obscurance and hemisphere rows",
        _ => "its rows",
    }
}

/// The time within which a row counts as one of the scene's fastest third: the time of the
/// row at rank ⌈n/3⌉ of the scene's n timed rows, all references together. `None` untimed.
pub fn fastest_third(scene: &DemoScene) -> Option<f64> {
    let mut times: Vec<f64> = rows(scene)
        .filter_map(|(_, r)| r.gpu_ms)
        .filter(|ms| ms.is_finite())
        .collect();
    times.sort_by(f64::total_cmp);
    let n = times.len().div_ceil(3);
    n.checked_sub(1).map(|i| times[i])
}

/// Every row of a scene with its report.
fn rows<'a>(scene: &'a DemoScene) -> impl Iterator<Item = (&'a Report, &'a TechniqueResult)> {
    scene
        .reports
        .iter()
        .flat_map(|d| d.report.results.iter().map(move |r| (d.report, r)))
}

/// The lowest-MAE row among `rows` (ties: the faster, then the first).
fn best<'a>(rows: impl Iterator<Item = &'a TechniqueResult>) -> Option<&'a TechniqueResult> {
    let time = |r: &TechniqueResult| r.gpu_ms.unwrap_or(f64::INFINITY);
    rows.filter(|r| r.mae.is_finite())
        .min_by(|a, b| a.mae.total_cmp(&b.mae).then(time(a).total_cmp(&time(b))))
}

/// Whether the row traces rays through the scene's BVH (`rt-vao`, `rtao`, …): nothing is hidden
/// from it, so only its sampling separates it from the reference.
fn traces_the_scene(technique: &str) -> bool {
    technique.parse::<Technique>().is_ok_and(|t| t.needs().bvh)
}

/// `name (MAE 0.0123, 2.2 ms (CPU))`.
fn row_words(r: &TechniqueResult, software: bool) -> String {
    let ms = r
        .gpu_ms
        .map(|ms| format!(", {}", format_ms(ms, software)))
        .unwrap_or_default();
    format!("{} (MAE {}{ms})", r.technique, fixed4(r.mae))
}

/// The scene's verdict: per reference, the lowest-MAE row of all and the lowest-MAE row among
/// the scene's fastest third ([`fastest_third`]), with their numbers; one sentence each, and
/// what the times are.
pub fn scene_verdict(scene: &DemoScene, software: bool) -> String {
    let budget = fastest_third(scene);
    let mut out = Vec::new();
    for d in &scene.reports {
        let model = &d.report.reference.model;
        let Some(top) = best(d.report.results.iter()) else {
            continue;
        };
        let mut sentence = format!(
            "Against the {model} reference ({}): the closest is {}",
            family(model),
            row_words(top, software)
        );
        // A ray-traced row's near-zero error would read like a bug without saying why, and an
        // engine without rays wants the best of the rest.
        let traced = traces_the_scene(&top.technique).then(|| {
            let screen = d
                .report
                .results
                .iter()
                .filter(|r| !traces_the_scene(&r.technique));
            let rest = best(screen).map_or(String::new(), |r| {
                format!(
                    ", and of the rows that trace none the closest is {}",
                    row_words(r, software)
                )
            });
            format!(
                "; {} traces rays through the scene's geometry as the reference does{rest}",
                top.technique
            )
        });
        if let Some(budget) = budget {
            let within = |r: &&TechniqueResult| r.gpu_ms.is_some_and(|ms| ms <= budget);
            let budget_words = format!(
                "the scene's fastest third (≤ {})",
                format_ms(budget, software)
            );
            match best(d.report.results.iter().filter(within)) {
                Some(fast) if fast.technique == top.technique => {
                    let _ = write!(sentence, ", which is also among {budget_words}");
                }
                Some(fast) => {
                    let _ = write!(
                        sentence,
                        "; among {budget_words}, {}",
                        row_words(fast, software)
                    );
                }
                None => {
                    let _ = write!(sentence, "; none of them is among {budget_words}");
                }
            }
        }
        sentence.push_str(&traced.unwrap_or_default());
        sentence.push('.');
        out.push(sentence);
    }
    if budget.is_some() {
        out.push(
            if software {
                "The times come from a software (CPU) adapter: they do not rank GPU cost."
            } else {
                "Times: GPU ms per frame without the G-buffer, median of the timed frames."
            }
            .to_owned(),
        );
    }
    out.join(" ")
}

const STYLE: &str = "
body { font-family: system-ui, sans-serif; background: #222; color: #eee; margin: 1.5em; }
a { color: #9cf; } small { color: #aaa; } code { font-size: 0.95em; }
.grid { display: grid; grid-template-columns: 12em repeat(3, minmax(0, 420px)); gap: 6px; align-items: center; }
.head { font-weight: 600; text-align: center; } .label { font-size: 0.95em; }
figure { margin: 0; } figure img { width: 100%; display: block; }
.costs { display: flex; flex-wrap: wrap; gap: 1em; margin: 0.5em 0; } .costs img { width: 560px; background: #fff; }
.legend { display: flex; align-items: center; gap: 0.5em; margin: 0.5em 0; }
.legend .bar { width: 16em; height: 0.9em; border: 1px solid #888; }
table.rows { border-collapse: collapse; } table.rows th { cursor: pointer; user-select: none; }
table.rows td, table.rows th { padding: 2px 8px; border-bottom: 1px solid #555; text-align: right; font-variant-numeric: tabular-nums; }
table.rows td.text { text-align: left; }
details > summary { cursor: pointer; margin: 0.5em 0; }
";

/// Sorts the table by the clicked column (again: the other way). A cell's `data-v` is its
/// numeric key; cells without one sort as text.
const SCRIPT: &str = "
for (const th of document.querySelectorAll('table.rows th')) {
  th.addEventListener('click', () => {
    const body = th.closest('table').tBodies[0];
    const i = th.cellIndex;
    const dir = th.dataset.dir === 'up' ? -1 : 1;
    for (const o of th.parentNode.cells) delete o.dataset.dir;
    th.dataset.dir = dir > 0 ? 'up' : 'down';
    const key = r => { const c = r.cells[i]; return 'v' in c.dataset ? parseFloat(c.dataset.v) : c.textContent; };
    const rows = Array.from(body.rows);
    rows.sort((a, b) => { const x = key(a), y = key(b);
      const c = typeof x === 'number' ? (x === y ? 0 : x < y ? -1 : 1) : x.localeCompare(y);
      return c * dir; });
    for (const r of rows) body.appendChild(r);
  });
}
";

/// The page.
pub fn demo_page(page: &DemoPage) -> String {
    let mut out = String::new();
    write_page(&mut out, page).expect("writing to a String cannot fail");
    out
}

fn write_page(out: &mut String, page: &DemoPage) -> fmt::Result {
    let scale = format_scale(page.diff_scale);
    writeln!(
        out,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <title>obscura demo</title>\n<style>{STYLE}\
         .legend .bar {{ background: linear-gradient(to right, {}, {}, {}); }}\n</style>\n\
         </head>\n<body>\n<h1>obscura demo</h1>",
        css_rgb(NEGATIVE_END),
        css_rgb(ZERO),
        css_rgb(POSITIVE_END)
    )?;
    writeln!(
        out,
        "<p>{} · {}</p>",
        escape(page.adapter),
        escape(page.settings)
    )?;
    writeln!(
        out,
        "<p>Each row is scored against the ray-traced reference of the quantity its estimator \
         computes, named in its <em>reference</em> column: rows whose estimator is VAO against \
         the <code>vao</code> model (VAO's kernel with nothing hidden, blurred like the rows); \
         the horizon, obscurance and hemisphere rows against the <code>hemisphere</code> model \
         (cosine-weighted rays within R). MAE is the mean absolute difference to that \
         reference; bright halo the mean positive error within 4 px of depth discontinuities.</p>"
    )?;
    writeln!(out, "<h2>Verdict</h2>\n<ul>")?;
    for scene in &page.scenes {
        writeln!(
            out,
            "<li><a href=\"#{0}\">{0}</a>: <span class=\"verdict\">{1}</span></li>",
            escape(scene.name),
            escape(&scene_verdict(scene, page.software_adapter))
        )?;
    }
    writeln!(out, "</ul>")?;
    writeln!(
        out,
        "<div class=\"legend\">Every difference image on this page (row − its reference) uses \
         one scale: <span>−{scale}</span><span class=\"bar\"></span><span>+{scale}</span> \
         (blue: darker than the reference, white: equal, red: brighter; saturated beyond \
         ±{scale}).</div>"
    )?;
    write_table(out, page)?;
    for (i, scene) in page.scenes.iter().enumerate() {
        write_scene(out, page, scene, i == 0)?;
    }
    writeln!(out, "<script>{SCRIPT}</script>\n</body>\n</html>")
}

/// Every row of every scene: scene, then reference, then MAE (click a header to sort by it).
fn write_table(out: &mut String, page: &DemoPage) -> fmt::Result {
    writeln!(
        out,
        "<h2>Every row</h2>\n<p>Sorted by scene, reference and MAE; click a column header to \
         sort by it.</p>\n<table class=\"rows\">\n<thead><tr><th>scene</th><th>technique</th>\
         <th>estimator</th><th>reference</th><th>MSE</th><th>MAE</th><th>PSNR (dB)</th>\
         <th>SSIM</th><th>bright halo</th><th>dark halo</th><th>time</th></tr></thead>\n<tbody>"
    )?;
    for scene in &page.scenes {
        for d in &scene.reports {
            let reference = reference_description(&d.report.reference);
            for r in by_mae(&d.report.results) {
                let estimator = r
                    .technique
                    .parse::<Technique>()
                    .map_or("?", |t| t.estimator().name());
                write!(
                    out,
                    "<tr><td class=\"text\"><a href=\"#{0}\">{0}</a></td>\
                     <td class=\"text\"><code>{1}</code></td><td class=\"text\">{estimator}</td>\
                     <td class=\"text\">{2}</td>",
                    escape(scene.name),
                    escape(&r.technique),
                    escape(&reference)
                )?;
                let cells = metric_cells(r, page.software_adapter);
                let values = [r.mse, r.mae, r.psnr, r.ssim, r.halo_bright, r.halo_dark];
                for (cell, v) in cells.iter().zip(values) {
                    write!(out, "<td data-v=\"{}\">{cell}</td>", sort_key(v))?;
                }
                match r.gpu_ms {
                    Some(ms) => write!(
                        out,
                        "<td data-v=\"{}\">{}</td>",
                        sort_key(ms),
                        format_ms(ms, page.software_adapter)
                    )?,
                    None => write!(out, "<td data-v=\"Infinity\">–</td>")?,
                }
                writeln!(out, "</tr>")?;
            }
        }
    }
    writeln!(out, "</tbody>\n</table>")
}

/// A number for `parseFloat`; NaN (n/a) sorts last.
fn sort_key(v: f64) -> String {
    if v.is_nan() {
        "Infinity".to_owned()
    } else {
        format!("{v}")
    }
}

/// The rows by MAE, lowest first (NaN last).
fn by_mae(results: &[TechniqueResult]) -> Vec<&TechniqueResult> {
    let mut sorted: Vec<&TechniqueResult> = results.iter().collect();
    let key = |r: &TechniqueResult| if r.mae.is_nan() { f64::INFINITY } else { r.mae };
    sorted.sort_by(|a, b| key(a).total_cmp(&key(b)));
    sorted
}

/// A scene: its verdict, then its charts and image grid in a `<details>` (open for the first).
fn write_scene(out: &mut String, page: &DemoPage, scene: &DemoScene, open: bool) -> fmt::Result {
    let name = escape(scene.name);
    writeln!(
        out,
        "<h2 id=\"{name}\">{name} <small>camera {}</small></h2>\n<p>{}</p>",
        escape(scene.camera),
        escape(&scene_verdict(scene, page.software_adapter))
    )?;
    writeln!(
        out,
        "<details{}><summary>images and quality-against-cost charts</summary>",
        if open { " open" } else { "" }
    )?;
    let timed = rows(scene).any(|(_, r)| r.gpu_ms.is_some());
    if timed {
        writeln!(out, "<div class=\"costs\">")?;
        for d in &scene.reports {
            writeln!(
                out,
                "<figure><img src=\"{0}/cost.svg\" loading=\"lazy\" alt=\"MSE against time, \
                 {1} reference\"><figcaption>MSE against the {1} reference ({2}) against time; \
                 <a href=\"{0}/index.html\">full report</a></figcaption></figure>",
                escape(d.folder),
                escape(&d.report.reference.model),
                family(&d.report.reference.model)
            )?;
        }
        writeln!(out, "</div>")?;
    }
    writeln!(
        out,
        "<div class=\"grid\"><div></div><div class=\"head\">AO</div>\
         <div class=\"head\">AO − its reference</div><div class=\"head\">{}</div>",
        if page.composites { "AO × colour" } else { "" }
    )?;
    for d in &scene.reports {
        let folder = escape(d.folder);
        writeln!(
            out,
            "<div class=\"label\">reference<br><small>{}, ray traced</small></div>\
             <figure><img src=\"{folder}/reference.png\" loading=\"lazy\" alt=\"reference\">\
             </figure><div></div><div></div>",
            escape(&reference_description(&d.report.reference))
        )?;
        for r in by_mae(&d.report.results) {
            let t = escape(&r.technique);
            let ms = r
                .gpu_ms
                .map(|ms| format!(" · {}", format_ms(ms, page.software_adapter)))
                .unwrap_or_default();
            let composite = if page.composites {
                format!("<figure><img src=\"{name}/{t}.composite.png\" loading=\"lazy\" alt=\"{t} × colour\"></figure>")
            } else {
                "<div></div>".to_owned()
            };
            writeln!(
                out,
                "<div class=\"label\"><code>{t}</code><br><small>MAE {} · vs {}{ms}</small></div>\
                 <figure><img src=\"{folder}/{t}.png\" loading=\"lazy\" alt=\"{t}\"></figure>\
                 <figure><img src=\"{folder}/{t}.diff.png\" loading=\"lazy\" alt=\"{t} − reference\">\
                 </figure>{composite}",
                fixed4(r.mae),
                escape(&d.report.reference.model),
            )?;
        }
    }
    writeln!(out, "</div>\n</details>")
}
