//! Every built-in scene's close-up with every technique, side by side in one HTML page.

use crate::args::parse_size;
use crate::progress::bar;
use anyhow::{Context, Result};
use clap::Args;
use obscura::{output, scene, AoSettings, Renderer, Technique};
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
}

pub fn run(options: &obscura::GpuOptions, args: &DemoArgs) -> Result<()> {
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("cannot create output folder '{}'", args.out.display()))?;
    let gpu = obscura::Gpu::new(options)?;
    let (width, height) = args.size;
    let guard_band = obscura::default_guard_band(height);
    let names = scene::builtin_names();
    let progress = bar((names.len() * Technique::ALL.len()) as u64, "demo");
    let mut rows = String::new();
    for name in names {
        let scene = scene::builtin(name)?;
        let camera = scene.default_camera(width as f32 / height as f32);
        let camera_name = scene.cameras.first().map_or("auto", |c| c.name.as_str());
        let _ = write!(
            rows,
            "<h2>{name} <small>camera {camera_name}</small></h2><div class=row>"
        );
        for &technique in Technique::ALL {
            let settings = AoSettings {
                technique,
                ..Default::default()
            };
            let mut renderer = Renderer::new(&gpu, &scene, &settings, width, height, guard_band)?;
            renderer.render(&camera, None)?;
            let ao = renderer.read_ao()?;
            let file = format!("{name}-{technique}.png");
            let composite = format!("{name}-{technique}.composite.png");
            output::write_ao(&args.out.join(&file), width, height, &ao)?;
            output::write_composite(
                &args.out.join(&composite),
                width,
                height,
                &ao,
                &renderer.read_albedo()?,
            )?;
            let _ = write!(
                rows,
                "<figure><img src=\"{file}\"><figcaption>{technique}</figcaption></figure>\
                 <figure><img src=\"{composite}\"><figcaption>{technique} × colour</figcaption></figure>"
            );
            progress.inc(1);
        }
        rows.push_str("</div>");
    }
    progress.finish_and_clear();
    let html = format!(
        "<!doctype html><meta charset=utf-8><title>obscura demo</title>\
         <style>body{{font-family:sans-serif;background:#222;color:#eee}}.row{{display:flex;gap:8px;flex-wrap:wrap}}\
         figure{{margin:0}}img{{width:{width}px;max-width:45vw}}small{{color:#aaa}}</style>\
         <h1>obscura demo</h1><p>{adapter} ({backend}), {width}×{height} + {guard_band} px guard band, \
         default settings (R 0.5, τ 0.5, exponent 1.3, 8 samples, blur radius 4).</p>{rows}",
        adapter = gpu.summary.name,
        backend = gpu.summary.backend,
    );
    let index = args.out.join("index.html");
    output::write_atomically(&index, |tmp| {
        std::fs::write(tmp, &html).map_err(|e| e.to_string())
    })?;
    println!("wrote {}", index.display());
    Ok(())
}
