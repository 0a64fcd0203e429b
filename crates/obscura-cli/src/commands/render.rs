use crate::args::{parse_size, parse_technique, AoArgs, SceneArgs};
use crate::progress::spinner;
use anyhow::Result;
use clap::Args;
use obscura::{output, Renderer, Technique};
use std::path::PathBuf;

#[derive(Args)]
pub struct RenderArgs {
    #[command(flatten)]
    scene: SceneArgs,
    /// Visible image size WIDTHxHEIGHT (the guard band is extra).
    #[arg(long, value_parser = parse_size, default_value = "1280x720")]
    size: (u32, u32),
    /// AO technique (vao).
    #[arg(long, value_parser = parse_technique, default_value = "vao")]
    technique: Technique,
    #[command(flatten)]
    ao: AoArgs,
    /// Output image: .png (8-bit) or .exr (float).
    #[arg(long)]
    out: PathBuf,
    /// Also write AO × base colour next to it (NAME.composite.png/.exr).
    #[arg(long)]
    composite: bool,
}

pub fn run(options: &obscura::GpuOptions, args: &RenderArgs) -> Result<()> {
    // Everything the user typed is checked before the (slow) scene load and GPU work.
    output::check_writable(&args.out)?;
    let settings = args.ao.settings(args.technique)?;
    let (width, height) = args.size;
    let guard_band = args.ao.guard_band(height);
    let loading = spinner(&format!("loading {}", args.scene.scene));
    let scene = args.scene.load();
    loading.finish_and_clear();
    let scene = scene?;
    let camera = args.scene.camera(&scene, width as f32 / height as f32)?;
    let gpu = obscura::Gpu::new(options)?;
    let mut renderer = Renderer::new(&gpu, &scene, &settings, width, height, guard_band)?;
    renderer.render(&camera, None)?;
    let ao = renderer.read_ao()?;
    crate::args::warn_stack_overflows(&renderer)?;
    output::write_ao(&args.out, width, height, &ao)?;
    if args.composite {
        let path = output::composite_path(&args.out);
        output::write_composite(&path, width, height, &ao, &renderer.read_albedo()?)?;
        eprintln!("wrote {} and {}", args.out.display(), path.display());
    } else {
        eprintln!("wrote {}", args.out.display());
    }
    Ok(())
}
