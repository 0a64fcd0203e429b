//! GPU timings per pass: warm-up frames, then timestamp queries around every pass for each
//! frame, medians reported. No CPU clocks are involved.

use crate::args::{parse_size, parse_technique_list, AoArgs, SceneArgs, TechniqueList};
use crate::progress::bar;
use anyhow::{bail, Result};
use clap::Args;
use obscura::bvh::BvhCache;
use obscura::{output, AoSettings, PassProfiler, Renderer};
use std::collections::BTreeMap;
use std::path::PathBuf;

#[derive(Args)]
pub struct BenchArgs {
    #[command(flatten)]
    scene: SceneArgs,
    /// Visible image size WIDTHxHEIGHT (the guard band is extra).
    #[arg(long, value_parser = parse_size, default_value = "1920x1080")]
    size: (u32, u32),
    #[arg(long, default_value = "vao", value_parser = parse_technique_list, help = crate::args::techniques_help())]
    techniques: TechniqueList,
    #[command(flatten)]
    ao: AoArgs,
    /// Timed frames.
    #[arg(long, default_value_t = 200,
          value_parser = clap::value_parser!(u32).range(1..=crate::args::MAX_FRAME_COUNT))]
    frames: u32,
    /// Untimed frames first.
    #[arg(long, default_value_t = 20,
          value_parser = clap::value_parser!(u32).range(0..=crate::args::MAX_FRAME_COUNT))]
    warmup: u32,
    /// Also write the results as JSON.
    #[arg(long)]
    json: Option<PathBuf>,
    /// Time along a camera path (a scene's path name or a .json file, docs/PATHS.md): the timed
    /// frames play the path from its first keyframe to its last, and each pass is reported as
    /// its median with the spread over the path (seed 002 Fig. 14–15).
    #[arg(long = "path")]
    path: Option<String>,
}

#[derive(serde::Serialize)]
struct BenchResult {
    technique: String,
    scene: String,
    camera: String,
    width: u32,
    height: u32,
    guard_band: u32,
    frames: u32,
    /// Everything the technique ran with (as a settings file holds it; `settings.technique`
    /// repeats `technique`).
    settings: AoSettings,
    /// Stochastic-depth techniques: how S samples were laid out on this adapter
    /// (`scripts/device-bench-sd.sh` reads it).
    #[serde(skip_serializing_if = "Option::is_none")]
    layout: Option<Layout>,
    passes: BTreeMap<String, f64>,
    /// The sum of the passes (median over frames).
    total_ms: f64,
    /// From the first pass's start to the last pass's end (median over frames): the passes and
    /// whatever the GPU does between them ([`obscura::gpu::PassProfiler::read_with_spans`]).
    span_ms: f64,
    /// Along a camera path (`--path`): each pass's fastest and slowest frame, and every frame's
    /// time along the path and total.
    #[serde(skip_serializing_if = "Option::is_none")]
    path: Option<PathTiming>,
    /// Raster passes: the median fragment-shader invocations per frame, and per framebuffer pixel
    /// (overdraw); absent where the adapter has no pipeline statistics queries. The compute
    /// rasteriser's passes (`sd_bin`, `sd_tiles`) count theirs themselves: the pixel centres
    /// they shade: covered and requested, the first layer's own included, which the
    /// hardware's early depth test drops before its count.
    #[serde(skip_serializing_if = "Option::is_none")]
    fragments: Option<BTreeMap<String, Fragments>>,
}

#[derive(serde::Serialize)]
struct PathTiming {
    name: String,
    /// Per pass: [fastest, slowest] frame along the path, ms.
    spread: BTreeMap<String, [f64; 2]>,
    /// Each timed frame's time along the path, seconds.
    times: Vec<f32>,
    /// Each timed frame's total, ms.
    totals: Vec<f64>,
}

#[derive(serde::Serialize)]
struct Fragments {
    invocations: u64,
    per_pixel: f64,
}

/// The stochastic depth map's layout (`obscura::sources::stochastic_depth::SdLayout`) as JSON.
#[derive(serde::Serialize)]
struct Layout {
    maps: u32,
    samples_per_map: u32,
}

#[derive(serde::Serialize)]
struct BenchReport {
    adapter: String,
    backend: String,
    driver: String,
    results: Vec<BenchResult>,
}

pub(crate) fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    let n = values.len();
    if n == 0 {
        return f64::NAN;
    }
    if n % 2 == 1 {
        values[n / 2]
    } else {
        0.5 * (values[n / 2 - 1] + values[n / 2])
    }
}

pub fn run(options: &obscura::GpuOptions, args: &BenchArgs) -> Result<()> {
    if args.frames == 0 {
        bail!("--frames must be at least 1");
    }
    if let Some(path) = &args.json {
        if !path
            .parent()
            .is_none_or(|p| p.as_os_str().is_empty() || p.is_dir())
        {
            bail!(
                "directory of --json '{}' does not exist: create it first",
                path.display()
            );
        }
    }
    let techniques = args.techniques.0.clone();
    let (width, height) = args.size;
    let guard_band = args.ao.guard_band(height);
    let scene = args.scene.load()?;
    let path = match &args.path {
        Some(spec) => {
            super::path::check_no_camera(&args.scene)?;
            let choice = super::path::PathChoice {
                path: Some(spec.clone()),
                frames: args.frames,
            };
            Some(choice.resolve(&scene, width as f32 / height as f32)?)
        }
        None => None,
    };
    // Without a path, every frame is seen from the one camera.
    let cameras: Vec<(f32, obscura::scene::Camera)> = match &path {
        Some(p) => p.sample(args.frames)?,
        None => vec![(
            0.0,
            args.scene.camera(&scene, width as f32 / height as f32)?,
        )],
    };
    let camera = cameras[0].1;
    let camera_name = match &path {
        Some(p) => format!("path {}", p.name),
        None => args.scene.camera.clone().unwrap_or_else(|| {
            if args.scene.eye.is_some() {
                "custom".into()
            } else {
                scene
                    .cameras
                    .first()
                    .map_or("auto".into(), |c| c.name.clone())
            }
        }),
    };
    let gpu = obscura::Gpu::new(options)?;
    if let Some(warning) = crate::args::software_timings_warning(&gpu) {
        eprintln!("warning: {warning}");
    }
    let mut results = Vec::new();
    let bvh = BvhCache::new();
    for technique in techniques {
        let settings = args.ao.settings(technique)?;
        let mut renderer =
            Renderer::with_bvh_cache(&gpu, &scene, &settings, width, height, guard_band, &bvh)?;
        let mut profiler = PassProfiler::new(&gpu, args.frames)?;
        let progress = bar(u64::from(args.warmup + args.frames), technique.name());
        // Under a time budget the warm-up frames settle the ray budget; the timed frames keep it.
        for _ in 0..args.warmup {
            renderer.render_frame(&camera)?;
            gpu.finish()?;
            progress.inc(1);
        }
        if let Some(ao) = renderer.ambient_occlusion() {
            if let Ok(report) = ao.read_ray_budget() {
                eprintln!(
                    "{technique}: ray budget {} rays a frame ({} granted of {} wanted)",
                    report.budget, report.granted, report.wanted
                );
            }
        }
        for k in 0..args.frames as usize {
            let camera = cameras[k % cameras.len()].1;
            renderer.render(&camera, Some(&mut profiler))?;
            // One frame in flight at a time, as a renderer presenting every frame would run.
            gpu.finish()?;
            progress.inc(1);
        }
        progress.finish_and_clear();
        let (frames, spans) = profiler.read_with_spans(&gpu)?;
        let pixels = f64::from(width + 2 * guard_band) * f64::from(height + 2 * guard_band);
        let fragments = profiler.read_fragments(&gpu)?.map(|frames| {
            let mut per_pass: BTreeMap<String, Vec<f64>> = BTreeMap::new();
            for frame in &frames {
                for (pass, &n) in frame {
                    per_pass.entry(pass.clone()).or_default().push(n as f64);
                }
            }
            per_pass
                .into_iter()
                .map(|(pass, counts)| {
                    let invocations = median(counts);
                    let counted = Fragments {
                        invocations: invocations as u64,
                        per_pixel: invocations / pixels,
                    };
                    (pass, counted)
                })
                .collect()
        });
        let mut per_pass: BTreeMap<String, Vec<f64>> = BTreeMap::new();
        let mut totals: Vec<f64> = Vec::new();
        for frame in &frames {
            for (pass, ms) in frame {
                per_pass.entry(pass.clone()).or_default().push(*ms);
            }
            let blur: f64 = frame
                .iter()
                .filter(|(p, _)| p.starts_with("blur_"))
                .map(|(_, ms)| ms)
                .sum();
            if blur > 0.0 {
                per_pass.entry("blur".into()).or_default().push(blur);
            }
            totals.push(frame.values().sum());
        }
        let layout = renderer
            .ambient_occlusion()
            .and_then(|ao| ao.stochastic_depth_layout())
            .map(|l| Layout {
                maps: l.maps,
                samples_per_map: l.samples_per_map,
            });
        let path_timing = path.as_ref().map(|p| PathTiming {
            name: p.name.clone(),
            spread: per_pass
                .iter()
                .map(|(pass, v)| {
                    let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
                    let hi = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                    (pass.clone(), [lo, hi])
                })
                .collect(),
            times: cameras.iter().map(|(t, _)| *t).collect(),
            totals: totals.clone(),
        });
        results.push(BenchResult {
            technique: technique.name().into(),
            settings: renderer.settings().resolved(),
            layout,
            scene: scene.name.clone(),
            camera: camera_name.clone(),
            width,
            height,
            guard_band,
            frames: args.frames,
            passes: per_pass.into_iter().map(|(k, v)| (k, median(v))).collect(),
            total_ms: median(totals),
            span_ms: median(spans),
            path: path_timing,
            fragments,
        });
    }
    let s = &gpu.summary;
    let report = BenchReport {
        adapter: s.name.clone(),
        backend: s.backend.clone(),
        driver: format!("{} {}", s.driver, s.driver_info).trim().to_string(),
        results,
    };
    println!(
        "adapter: {} ({}), driver: {}",
        report.adapter, report.backend, report.driver
    );
    for r in &report.results {
        let sd = match &r.layout {
            Some(l) => {
                let sd = &r.settings.stochastic_depth;
                let maps = match l.maps {
                    1 => "one map".to_string(),
                    n => format!("{n} maps of {}", l.samples_per_map),
                };
                let mask = if r.settings.technique.schedule().two_phase() {
                    format!(", mask {}", sd.mask)
                } else {
                    String::new()
                };
                // The raster map's rasteriser (`auto` resolved by the renderer).
                let rasterizer = if r.settings.technique.needs().stochastic_depth_map {
                    format!(", {} rasteriser", sd.rasterizer)
                } else {
                    String::new()
                };
                format!(
                    ", S = {} ({maps}), α = {}{mask}{rasterizer}",
                    sd.samples,
                    sd.alpha()
                )
            }
            None => String::new(),
        };
        let resolution = match r.settings.resolution {
            obscura::settings::Resolution::Full => "",
            obscura::settings::Resolution::Half => ", AO at half resolution",
        };
        println!(
            "{} on {} ({}) {}x{} +{} guard band{sd}{resolution}, median of {} frames:",
            r.technique, r.scene, r.camera, r.width, r.height, r.guard_band, r.frames
        );
        for (pass, ms) in &r.passes {
            match r.path.as_ref().and_then(|p| p.spread.get(pass)) {
                Some([lo, hi]) => {
                    println!("  {pass:<20} {ms:>9.4} ms  ({lo:.4} to {hi:.4} along the path)")
                }
                None => println!("  {pass:<20} {ms:>9.4} ms"),
            }
        }
        match &r.path {
            Some(p) => {
                let lo = p.totals.iter().copied().fold(f64::INFINITY, f64::min);
                let hi = p.totals.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                println!(
                    "  {:<20} {:>9.4} ms  ({lo:.4} to {hi:.4} along the path)",
                    "total", r.total_ms
                );
            }
            None => println!("  {:<20} {:>9.4} ms", "total", r.total_ms),
        }
        println!(
            "  {:<20} {:>9.4} ms  (first pass start to last pass end)",
            "frame span", r.span_ms
        );
        for (pass, f) in r.fragments.iter().flatten() {
            println!(
                "  {pass:<20} {:>9} fragments ({:.2} per framebuffer pixel)",
                f.invocations, f.per_pixel
            );
        }
    }
    if let Some(path) = &args.json {
        let text = serde_json::to_string_pretty(&report)?;
        output::write_atomically(path, |tmp| {
            std::fs::write(tmp, &text).map_err(|e| e.to_string())
        })?;
        eprintln!("wrote {}", path.display());
    }
    Ok(())
}
