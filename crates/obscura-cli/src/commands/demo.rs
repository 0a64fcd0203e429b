//! Every built-in scene's close-up with every technique, its ray-traced reference (`vao` model)
//! and the error table, side by side in one HTML page.

use super::compare::{compare, Comparison, TimingArgs};
use super::reference::ReferenceArgs;
use crate::args::{parse_size, AoArgs};
use crate::progress::bar;
use anyhow::{Context, Result};
use clap::Args;
use obscura::reference::ground_truth::ReferenceModel;
use obscura::report::{self, METRIC_HEADERS};
use obscura::{output, scene, Technique};
use std::fmt::Write as _;
use std::path::PathBuf;

#[derive(Args)]
pub struct DemoArgs {
    /// Output folder (created if missing).
    #[arg(long, default_value = "demo-out")]
    out: PathBuf,
    /// Visible image size WIDTHxHEIGHT.
    #[arg(long, value_parser = parse_size, default_value = "640x360")]
    size: (u32, u32),
    #[command(flatten)]
    ao: AoArgs,
    #[command(flatten)]
    reference: ReferenceArgs,
    #[command(flatten)]
    timing: TimingArgs,
}

/// One heat-map scale for the whole page, so colours compare across scenes: differences of ±0.2
/// AO saturate (the horizon estimators' model differences against the vao reference reach that).
const PAGE_DIFF_SCALE: f64 = 0.2;

pub fn run(options: &obscura::GpuOptions, args: &DemoArgs) -> Result<()> {
    // Options that do not apply (the demo's reference is the vao model) are refused up front.
    args.reference.settings(ReferenceModel::Vao, &args.ao)?;
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("cannot create output folder '{}'", args.out.display()))?;
    let gpu = obscura::Gpu::new(options)?;
    let (width, height) = args.size;
    let guard_band = args.ao.guard_band(height);
    let names = scene::builtin_names();
    let progress = bar(names.len() as u64, "demo");
    let mut sections = String::new();
    let mut table = String::from("<table><tr><th>scene</th><th>technique</th><th>estimator</th>");
    for h in METRIC_HEADERS {
        let _ = write!(table, "<th>{h}</th>");
    }
    table.push_str("</tr>");
    let mut software = false;
    for name in names {
        let scene = scene::builtin(name)?;
        let camera = scene.default_camera(width as f32 / height as f32);
        let camera_name = scene.cameras.first().map_or("auto", |c| c.name.as_str());
        let dir = args.out.join(name);
        std::fs::create_dir_all(&dir)
            .with_context(|| format!("cannot create '{}'", dir.display()))?;
        let comparison = Comparison {
            scene: &scene,
            camera_name,
            camera,
            width,
            height,
            guard_band,
            timing_frames: args.timing.timing_frames,
            diff_scale: Some(PAGE_DIFF_SCALE),
            reference_image: None,
        };
        let report = compare(
            &gpu,
            &comparison,
            &Technique::all().collect::<Vec<_>>(),
            &args.ao,
            &args.reference,
            ReferenceModel::Vao,
            &dir,
            &mut |technique, renderer| {
                let path = dir.join(format!("{technique}.composite.png"));
                let ao = renderer.read_ao()?;
                output::write_composite(&path, width, height, &ao, &renderer.read_albedo()?)?;
                Ok(())
            },
        )?;
        software = report.software_adapter;
        let _ = write!(
            sections,
            "<h2 id=\"{name}\">{name} <small>camera {camera_name} · <a href=\"{name}/index.html\">full report</a></small></h2>"
        );
        if report.results.iter().any(|r| r.gpu_ms.is_some()) {
            let _ = write!(
                sections,
                "<div class=cost><img src=\"{name}/cost.svg\" alt=\"quality against cost\"><p>{}</p></div>",
                report::verdict(&report)
            );
        }
        let _ = write!(
            sections,
            "<div class=grid><div></div><div class=head>AO</div><div class=head>AO − reference</div>\
             <div class=head>AO × colour</div>\
             <div class=label>reference<br><small>vao model, ray traced</small></div>\
             <figure><img src=\"{name}/reference.png\"></figure><div></div><div></div>"
        );
        for r in &report.results {
            let t = &r.technique;
            let estimator = t.parse::<Technique>().map_or("?", |t| t.estimator().name());
            let cells = report::metric_cells(r, software);
            let _ = write!(
                sections,
                "<div class=label><code>{t}</code><br><small>MSE {} · {} ms</small></div>\
                 <figure><img src=\"{name}/{t}.png\"></figure>\
                 <figure><img src=\"{name}/{t}.diff.png\"></figure>\
                 <figure><img src=\"{name}/{t}.composite.png\"></figure>",
                cells[0], cells[6]
            );
            let _ = write!(
                table,
                "<tr><td><a href=\"#{name}\">{name}</a></td><td>{t}</td><td>{estimator}</td>"
            );
            for cell in cells {
                let _ = write!(table, "<td>{cell}</td>");
            }
            table.push_str("</tr>");
        }
        sections.push_str("</div>");
        progress.inc(1);
    }
    progress.finish_and_clear();
    table.push_str("</table>");
    // What the techniques ran with (preset, settings file and flags applied).
    let shown = args.ao.settings(Technique::Vao)?;
    let timing = if software {
        "GPU ms: the median frame time of each technique's passes without the G-buffer; this \
         adapter is a CPU (software) device, so the times are shown in brackets and say nothing \
         about a GPU."
    } else {
        "GPU ms: the median frame time of each technique's passes without the G-buffer."
    };
    let html = format!(
        "<!doctype html><meta charset=utf-8><title>obscura demo</title>\
         <style>body{{font-family:sans-serif;background:#222;color:#eee;margin:1.5em}}\
         .grid{{display:grid;grid-template-columns:11em repeat(3,minmax(0,{img}px));gap:6px;align-items:center}}\
         .head{{font-weight:600;text-align:center}}.label{{font-size:0.95em}}\
         figure{{margin:0}}img{{width:100%;display:block}}small{{color:#aaa}}a{{color:#9cf}}\
         .cost{{display:flex;gap:1em;align-items:center;margin-bottom:1em}}.cost img{{width:480px;background:#fff}}\
         .legend{{display:flex;align-items:center;gap:0.5em}}.bar{{width:16em;height:0.9em;\
         background:linear-gradient(to right,rgb(0,0,255),rgb(255,255,255),rgb(255,0,0))}}\
         table{{border-collapse:collapse}}td,th{{padding:2px 8px;border-bottom:1px solid #555;text-align:right;\
         font-variant-numeric:tabular-nums}}</style>\
         <h1>obscura demo</h1><p>{adapter} ({backend}), {width}×{height} + {guard_band} px guard band, \
         R {r}, τ {t}, exponent {e}, {s} samples, blur radius {br}. Errors against the ray-traced \
         <code>vao</code> reference (the quantity VAO estimates with nothing hidden, blurred the same way). \
         The horizon estimators (hbao+, gtao-vb) estimate another quantity, so their errors here include \
         the difference of the models; compare them with <code>obscura compare --reference-model \
         hemisphere</code>. Bright halo: mean positive error within 4 px of depth discontinuities. \
         {timing}</p>\
         <div class=legend>AO − reference, one scale for the whole page: <span>−{scale}</span>\
         <span class=bar></span><span>+{scale}</span> (blue: darker than the reference, red: brighter)</div>\
         {table}{sections}",
        img = width.min(420),
        adapter = gpu.summary.name,
        backend = gpu.summary.backend,
        r = shown.vao.radius,
        t = shown.vao.thickness,
        e = shown.vao.exponent,
        s = shown.vao.samples,
        br = shown.blur.radius,
        scale = PAGE_DIFF_SCALE,
    );
    let index = args.out.join("index.html");
    output::write_atomically(&index, |tmp| {
        std::fs::write(tmp, &html).map_err(|e| e.to_string())
    })?;
    println!("wrote {}", index.display());
    Ok(())
}
