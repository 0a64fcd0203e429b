//! Every built-in scene's close-up with every technique, its ray-traced reference (`vao` model)
//! and the error table, side by side in one HTML page.

use super::compare::{compare, Comparison};
use super::reference::ReferenceArgs;
use crate::args::{parse_size, AoArgs};
use crate::progress::bar;
use anyhow::{Context, Result};
use clap::Args;
use obscura::reference::ground_truth::ReferenceModel;
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
}

fn fmt(v: f64) -> String {
    if v.is_finite() {
        format!("{v:.4}")
    } else {
        "∞".into()
    }
}

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
    let mut table = String::from(
        "<table><tr><th>scene</th><th>technique</th><th>estimator</th><th>MSE</th><th>PSNR (dB)</th>\
         <th>SSIM</th><th>bright halo</th><th>dark halo</th></tr>",
    );
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
        let _ = write!(
            sections,
            "<h2>{name} <small>camera {camera_name} · <a href=\"{name}/index.html\">full report</a></small></h2>\
             <div class=row><figure><img src=\"{name}/reference.png\"><figcaption>reference (vao model, ray traced)</figcaption></figure>"
        );
        for r in &report.results {
            let t = &r.technique;
            let _ = write!(
                sections,
                "<figure><img src=\"{name}/{t}.png\"><figcaption>{t}</figcaption></figure>\
                 <figure><img src=\"{name}/{t}.diff.png\"><figcaption>{t} − reference</figcaption></figure>\
                 <figure><img src=\"{name}/{t}.composite.png\"><figcaption>{t} × colour</figcaption></figure>"
            );
            let estimator = t.parse::<Technique>().map_or("?", |t| t.estimator().name());
            let _ = write!(
                table,
                "<tr><td>{name}</td><td>{t}</td><td>{estimator}</td><td>{:.3e}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
                r.mse,
                fmt(r.psnr),
                fmt(r.ssim),
                fmt(r.halo_bright),
                fmt(r.halo_dark)
            );
        }
        sections.push_str("</div>");
        progress.inc(1);
    }
    progress.finish_and_clear();
    table.push_str("</table>");
    // What the techniques ran with (preset, settings file and flags applied).
    let shown = args.ao.settings(Technique::Vao)?;
    let html = format!(
        "<!doctype html><meta charset=utf-8><title>obscura demo</title>\
         <style>body{{font-family:sans-serif;background:#222;color:#eee}}.row{{display:flex;gap:8px;flex-wrap:wrap}}\
         figure{{margin:0}}img{{width:{img}px;max-width:31vw}}small{{color:#aaa}}a{{color:#9cf}}\
         table{{border-collapse:collapse}}td,th{{padding:2px 8px;border-bottom:1px solid #555;text-align:right}}</style>\
         <h1>obscura demo</h1><p>{adapter} ({backend}), {width}×{height} + {guard_band} px guard band, \
         R {r}, τ {t}, exponent {e}, {s} samples, blur radius {br}. Errors against the ray-traced \
         <code>vao</code> reference (the quantity VAO estimates with nothing hidden, blurred the same way). \
         The horizon estimators (hbao+, gtao-vb) estimate another quantity, so their errors here include \
         the difference of the models; compare them with <code>obscura compare --reference-model \
         hemisphere</code>. Heat maps: blue = darker, red = brighter than the reference. Bright halo: mean positive error \
         within 4 px of depth discontinuities.</p>{table}{sections}",
        img = width.min(420),
        adapter = gpu.summary.name,
        backend = gpu.summary.backend,
        r = shown.vao.radius,
        t = shown.vao.thickness,
        e = shown.vao.exponent,
        s = shown.vao.samples,
        br = shown.blur.radius,
    );
    let index = args.out.join("index.html");
    output::write_atomically(&index, |tmp| {
        std::fs::write(tmp, &html).map_err(|e| e.to_string())
    })?;
    println!("wrote {}", index.display());
    Ok(())
}
