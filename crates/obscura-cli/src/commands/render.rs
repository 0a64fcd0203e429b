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
    /// AO technique: vao, vao-dual, rt-vao, rt-svao or rt-svao-dense.
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
    /// Two-phase techniques (rt-svao, rt-svao-dense): write the per-pixel count of samples that
    /// needed rays (samples.png) and the frame's ray statistics (stats.json) into this folder.
    #[arg(long)]
    debug_out: Option<PathBuf>,
}

pub fn run(options: &obscura::GpuOptions, args: &RenderArgs) -> Result<()> {
    // Everything the user typed is checked before the (slow) scene load and GPU work.
    output::check_writable(&args.out)?;
    let settings = args.ao.settings(args.technique)?;
    if let Some(dir) = &args.debug_out {
        if !matches!(args.technique, Technique::RtSvao | Technique::RtSvaoDense) {
            anyhow::bail!(
                "--debug-out shows the two-phase pipeline's flagged samples: use it with --technique rt-svao or rt-svao-dense"
            );
        }
        std::fs::create_dir_all(dir).map_err(|e| {
            anyhow::anyhow!("cannot create --debug-out folder '{}': {e}", dir.display())
        })?;
    }
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
    if let Some(dir) = &args.debug_out {
        write_debug(dir, &renderer, width, height, settings.vao.samples)?;
    }
    if args.composite {
        let path = output::composite_path(&args.out);
        output::write_composite(&path, width, height, &ao, &renderer.read_albedo()?)?;
        eprintln!("wrote {} and {}", args.out.display(), path.display());
    } else {
        eprintln!("wrote {}", args.out.display());
    }
    Ok(())
}

/// The two-phase pipeline's flagged samples: an image of their count per pixel and the totals.
fn write_debug(
    dir: &std::path::Path,
    renderer: &Renderer,
    width: u32,
    height: u32,
    samples: u32,
) -> Result<()> {
    let masks = renderer
        .read_sample_masks()?
        .ok_or_else(|| anyhow::anyhow!("this technique has no phase 1"))?;
    let counts: Vec<f32> = masks
        .iter()
        .map(|m| m.count_ones() as f32 / samples as f32)
        .collect();
    output::write_ao(&dir.join("samples.png"), width, height, &counts)?;
    let flagged_pixels = masks.iter().filter(|&&m| m != 0).count();
    let rays: u64 = masks.iter().map(|m| u64::from(m.count_ones())).sum();
    let stats = serde_json::json!({
        "pixels": masks.len(),
        "flagged_pixels": flagged_pixels,
        "flagged_fraction": flagged_pixels as f64 / masks.len().max(1) as f64,
        "rays_traced": rays,
        "stack_overflows": renderer.read_stack_overflows()?,
    });
    let text = serde_json::to_string_pretty(&stats)?;
    output::write_atomically(&dir.join("stats.json"), |tmp| {
        std::fs::write(tmp, &text).map_err(|e| e.to_string())
    })?;
    eprintln!(
        "debug: {flagged_pixels} of {} pixels ({:.1} %) flagged, {rays} rays traced; wrote {}",
        masks.len(),
        100.0 * flagged_pixels as f64 / masks.len().max(1) as f64,
        dir.display()
    );
    Ok(())
}
