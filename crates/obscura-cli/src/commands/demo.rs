//! Every built-in scene's close-up with every technique, each scored against the ray-traced
//! reference of its estimator's quantity (`vao` model for the VAO rows, `hemisphere` for the
//! others: `report::demo_page::fair_reference`), in one HTML page with a verdict per scene.

use super::compare::{compare, Comparison, TimingArgs};
use super::reference::ReferenceArgs;
use crate::args::{parse_size, AoArgs};
use crate::progress::bar;
use anyhow::{Context, Result};
use clap::Args;
use obscura::reference::ground_truth::ReferenceModel;
use obscura::report::demo_page::{self, DemoPage, DemoReport, DemoScene};
use obscura::{output, scene, Technique};
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

/// One heat-map scale for the whole page, so colours compare across scenes and rows: ±0.2 AO
/// saturates.
const PAGE_DIFF_SCALE: f64 = 0.2;

/// The hemisphere reference's rays per pixel unless --spp says otherwise: 64 moved no MAE of
/// stairs' hemisphere-scored rows (gtao, hbao+, gtao-vb, hemisphere, rtao) by more than 0.001
/// against 1024 rays (lavapipe, 2-core VM, 640x360), and traces grass, the slowest scene, in
/// 7.9 s on the CPU tracer where 256 took 43 s (the GPU tracer on lavapipe: 65 s and 335 s).
const DEMO_SPP: u32 = 64;

pub fn run(options: &obscura::GpuOptions, args: &DemoArgs) -> Result<()> {
    // The vao reference takes no hemisphere options (spp, falloff, seed): they go to the
    // hemisphere reference only.
    let vao_reference = ReferenceArgs {
        spp: None,
        falloff: false,
        seed: None,
        ..args.reference.clone()
    };
    let hemisphere_reference = ReferenceArgs {
        spp: Some(args.reference.spp.unwrap_or(DEMO_SPP)),
        ..args.reference.clone()
    };
    let families = [
        (ReferenceModel::Vao, &vao_reference),
        (ReferenceModel::Hemisphere, &hemisphere_reference),
    ];
    // Options are checked before anything slow.
    for (model, reference) in families {
        reference.settings(model, &args.ao)?;
    }
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("cannot create output folder '{}'", args.out.display()))?;
    let gpu = obscura::Gpu::new(options)?;
    let (width, height) = args.size;
    let guard_band = args.ao.guard_band(height);
    let names = scene::builtin_names();
    let progress = bar(names.len() as u64, "demo");
    // Per scene: its camera and one report per reference model.
    let mut scenes = Vec::new();
    for &name in names {
        let scene = scene::builtin(name)?;
        let camera = scene.default_camera(width as f32 / height as f32);
        let camera_name = scene
            .cameras
            .first()
            .map_or("auto".to_owned(), |c| c.name.clone());
        let dir = args.out.join(name);
        std::fs::create_dir_all(&dir)
            .with_context(|| format!("cannot create '{}'", dir.display()))?;
        let comparison = Comparison {
            scene: &scene,
            camera_name: &camera_name,
            camera,
            width,
            height,
            guard_band,
            timing_frames: args.timing.timing_frames,
            diff_scale: Some(PAGE_DIFF_SCALE),
            reference_image: None,
        };
        let mut reports = Vec::new();
        for (model, reference) in families {
            let techniques: Vec<Technique> = Technique::all()
                .filter(|t| demo_page::fair_reference(*t) == model)
                .collect();
            let folder = format!("{name}/{model}");
            let report = compare(
                &gpu,
                &comparison,
                &techniques,
                &args.ao,
                reference,
                model,
                &args.out.join(&folder),
                &mut |technique, renderer| {
                    let path = dir.join(format!("{technique}.composite.png"));
                    let ao = renderer.read_ao()?;
                    output::write_composite(&path, width, height, &ao, &renderer.read_albedo()?)?;
                    Ok(())
                },
            )?;
            reports.push((folder, report));
        }
        scenes.push((name, camera_name, reports));
        progress.inc(1);
    }
    progress.finish_and_clear();
    // What the techniques ran with (preset, settings file and flags applied).
    let shown = args.ao.settings(Technique::Vao)?;
    let settings = format!(
        "{width}×{height} + {guard_band} px guard band; vao: R {}, τ {}, exponent {}, {} samples; \
         blur radius {}; every technique timed over {} frames (median of the passes without the \
         G-buffer)",
        shown.vao.radius,
        shown.vao.thickness,
        shown.vao.exponent,
        shown.vao.samples,
        shown.blur.radius,
        args.timing.timing_frames,
    );
    let adapter = format!("{} ({})", gpu.summary.name, gpu.summary.backend);
    let page = DemoPage {
        adapter: &adapter,
        settings: &settings,
        software_adapter: gpu.summary.device_type == "Cpu",
        diff_scale: PAGE_DIFF_SCALE,
        composites: true,
        scenes: scenes
            .iter()
            .map(|(name, camera, reports)| DemoScene {
                name,
                camera,
                reports: reports
                    .iter()
                    .map(|(folder, report)| DemoReport { folder, report })
                    .collect(),
            })
            .collect(),
    };
    let html = demo_page::demo_page(&page);
    let index = args.out.join("index.html");
    output::write_atomically(&index, |tmp| {
        std::fs::write(tmp, &html).map_err(|e| e.to_string())
    })?;
    println!("wrote {}", index.display());
    Ok(())
}
