//! `obscura view`: the interactive viewer (issue 13). A window (eframe/egui on wgpu) around the
//! same `Renderer` every other command uses, on the window's own wgpu device (shared with obscura
//! through `Gpu::from_device`), plus two windowless modes for tests and timing:
//! `--screenshot FILE --frames N` (run N frames in the window, save the image, exit) and
//! `--offscreen-frames N` (no window: render N frames of the same render path and print their
//! times).
//!
//! - `frame.rs`: one frame of the viewer (renderers, display pass, debug views, GPU timings);
//! - `display.rs` + `display.wgsl`: obscura's textures into the RGBA image egui shows;
//! - `camera.rs`: the fly camera and its flags / keyframe;
//! - `app.rs`: the window, its panels and keys; `controls.rs`: the settings widgets;
//! - `reference.rs`: the ground truth traced in the background.

mod app;
mod camera;
mod controls;
mod display;
mod frame;
mod reference;

use crate::args::{parse_size, parse_technique, AoArgs, SceneArgs};
use anyhow::{bail, Context, Result};
use clap::Args;
use frame::{DebugView, Frame};
use obscura::{Gpu, Technique};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

#[derive(Args)]
pub struct ViewArgs {
    #[command(flatten)]
    scene: SceneArgs,
    #[arg(long, value_parser = parse_technique, default_value = "vao", help = crate::args::technique_help())]
    technique: Technique,
    /// Split screen: this technique on the right half (A's settings, its own technique).
    #[arg(long, value_parser = parse_technique)]
    split: Option<Technique>,
    #[command(flatten)]
    ao: AoArgs,
    /// What the image shows first: ao, composite, normals, depth, sd-layer, sample-masks,
    /// requested-pixels or reference.
    #[arg(long = "view", value_parser = DebugView::parse, default_value = "ao")]
    debug_view: DebugView,
    /// Fixed image size WIDTHxHEIGHT (default: the window's image area; 1920x1080 offscreen).
    #[arg(long, value_parser = parse_size)]
    size: Option<(u32, u32)>,
    /// Save the image after --frames frames to this PNG and exit (for tests and CI: run it under
    /// Xvfb where there is no display).
    #[arg(long, value_name = "FILE")]
    screenshot: Option<PathBuf>,
    /// Frames to run before --screenshot is taken and the window closes [default: 5 with
    /// --screenshot; without it, run until closed].
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=crate::args::MAX_FRAME_COUNT))]
    frames: Option<u32>,
    /// No window: render this many frames of the viewer's render path (renderers and display
    /// pass) at --size, waiting for the GPU after each, and print the frame times and per-pass
    /// GPU medians. For timing on machines without a display; --screenshot saves the last frame.
    #[arg(long, value_name = "N",
          value_parser = clap::value_parser!(u32).range(1..=crate::args::MAX_FRAME_COUNT))]
    offscreen_frames: Option<u32>,
}

pub fn run(options: &obscura::GpuOptions, args: &ViewArgs) -> Result<()> {
    // Everything the user typed is checked before the scene load and the window.
    if let Some(path) = &args.screenshot {
        if obscura::output::ImageFormat::from_path(path)? != obscura::output::ImageFormat::Png {
            bail!("--screenshot '{}' must be a .png file", path.display());
        }
        obscura::output::check_writable(path)?;
    }
    if args.frames == Some(0) || args.offscreen_frames == Some(0) {
        bail!("--frames and --offscreen-frames must be at least 1");
    }
    let settings = args.ao.settings(args.technique)?;
    if let Some(t) = args.split {
        frame::with_technique(&settings, t)
            .validate()
            .map_err(|e| crate::args::for_user(e.into()))
            .with_context(|| format!("--split {t}"))?;
    }
    if args.scene.up.is_some() {
        bail!(
            "--up: the viewer's fly camera keeps +Y up (it turns about +Y); --up is for render, \
             compare, reference and bench"
        );
    }
    let scene = Arc::new(args.scene.load()?);
    let aspect = args.size.map_or(16.0 / 9.0, |(w, h)| w as f32 / h as f32);
    let camera = args.scene.camera(&scene, aspect)?;
    let start = StartState {
        scene,
        camera,
        settings,
        units_per_metre: args.ao.units_per_metre()?,
        split: args.split,
        view: args.debug_view,
        size: args.size,
        guard_band: args.ao.guard_band,
        screenshot: args.screenshot.clone(),
        frames: args.frames.or(args.screenshot.as_ref().map(|_| 5)),
    };
    match args.offscreen_frames {
        Some(n) => offscreen(options, start, n),
        None => app::run_window(options, start),
    }
}

/// What the viewer starts with, from the command line.
pub struct StartState {
    pub scene: Arc<obscura::scene::Scene>,
    pub camera: obscura::scene::Camera,
    pub settings: obscura::AoSettings,
    /// `--units` as world units per metre (1 without it): the preset buttons convert with it.
    pub units_per_metre: f32,
    pub split: Option<Technique>,
    pub view: DebugView,
    pub size: Option<(u32, u32)>,
    /// `--guard-band`; None: the default for the image height.
    pub guard_band: Option<u32>,
    pub screenshot: Option<PathBuf>,
    pub frames: Option<u32>,
}

impl StartState {
    pub fn guard_band(&self, height: u32) -> u32 {
        self.guard_band
            .unwrap_or_else(|| obscura::default_guard_band(height))
    }
}

/// Write the display image (RGBA8, display-encoded) as a PNG.
pub fn save_png(path: &Path, width: u32, height: u32, rgba: Vec<u8>) -> Result<()> {
    let image = image::RgbaImage::from_raw(width, height, rgba)
        .context("the display image has the wrong size")?;
    obscura::output::write_atomically(path, |tmp| {
        image
            .save_with_format(tmp, image::ImageFormat::Png)
            .map_err(|e| e.to_string())
    })?;
    Ok(())
}

/// `--offscreen-frames N`: the window's render path without a window.
fn offscreen(options: &obscura::GpuOptions, start: StartState, frames: u32) -> Result<()> {
    let (width, height) = start.size.unwrap_or((1920, 1080));
    let guard_band = start.guard_band(height);
    let gpu = Gpu::new(options)?;
    if let Some(warning) = crate::args::software_timings_warning(&gpu) {
        eprintln!("warning: {warning}");
    }
    let camera = start.camera;
    let mut frame = Frame::new(
        gpu.clone(),
        start.scene.clone(),
        start.settings,
        start.split,
        (width, height, guard_band),
        camera,
    );
    for pane in std::iter::once(&frame.a).chain(frame.b.as_ref()) {
        if let Some(e) = &pane.error {
            bail!("{}: {e}", pane.settings.technique);
        }
    }
    let split_x = start.split.map(|_| width / 2);
    let view = match start.view {
        DebugView::Reference => {
            eprintln!("note: --offscreen-frames shows no reference: timing the AO view");
            DebugView::Ao
        }
        v => v,
    };
    // The first frame builds pipelines: warm up, then time.
    frame.render(&camera, view, split_x, None, false)?;
    gpu.finish()?;
    let mut times = Vec::with_capacity(frames as usize);
    let mut passes: std::collections::BTreeMap<String, Vec<f64>> = Default::default();
    for i in 0..frames {
        let t = Instant::now();
        frame.render(&camera, view, split_x, None, false)?;
        gpu.finish()?;
        times.push(t.elapsed().as_secs_f64() * 1e3);
        // Per-pass GPU times on separate frames, so the read-backs stay out of the frame times.
        if i < 16 && frame.timings.is_some() {
            frame.render(&camera, view, split_x, None, true)?;
            for (pane, timings) in frame.timings.iter().flatten().enumerate() {
                for (name, ms) in timings {
                    let key = if pane == 0 {
                        name.clone()
                    } else {
                        format!("B {name}")
                    };
                    passes.entry(key).or_default().push(*ms);
                }
            }
        }
    }
    for pane in std::iter::once(&frame.a).chain(frame.b.as_ref()) {
        if let Some(e) = &pane.error {
            bail!("{}: {e}", pane.settings.technique);
        }
    }
    let median = |v: &mut Vec<f64>| {
        v.sort_by(|a, b| a.total_cmp(b));
        v[v.len() / 2]
    };
    let mean = times.iter().sum::<f64>() / times.len() as f64;
    let med = median(&mut times.clone());
    println!(
        "view offscreen: {} {width}x{height} (guard band {guard_band}), view {}, on '{}' ({}): \
         {frames} frames, median {med:.3} ms, mean {mean:.3} ms = {:.1} frames/s (median; each \
         frame waits for the GPU)",
        start.settings.technique,
        view.name(),
        gpu.summary.name,
        gpu.summary.backend,
        1e3 / med,
    );
    if passes.is_empty() {
        println!("no GPU timings on this adapter (no timestamp queries)");
    }
    for (name, mut ms) in passes {
        println!("  {name}: {:.3} ms (median GPU time)", median(&mut ms));
    }
    if let Some(path) = &start.screenshot {
        save_png(path, width, height, frame.read_rgba()?)?;
        eprintln!("wrote {}", path.display());
    }
    Ok(())
}
