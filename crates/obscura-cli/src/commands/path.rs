//! `obscura path`: AO along a camera path (issue 13): every frame of every technique, and of the
//! reference when asked, as numbered images, animated previews and per-frame JSON with the
//! temporal metrics (`obscura::metrics::temporal`). `compare --path` shares the rendering.

use super::reference::{compute_or_load, ReferenceArgs};
use crate::args::{parse_size, parse_technique_list, AoArgs, SceneArgs, TechniqueList};
use crate::progress::bar;
use anyhow::{bail, Context, Result};
use clap::Args;
use obscura::bvh::BvhCache;
use obscura::metrics::temporal::{path_metrics, PathFrame, PathMetrics};
use obscura::metrics::{self, Image};
use obscura::raster::GBufferImage;
use obscura::reference::as_compared;
use obscura::reference::ground_truth::ReferenceModel;
use obscura::report::temporal::frame_delay_ms;
use obscura::scene::{CameraPath, Scene};
use obscura::{output, AoSettings, FrameView, Gpu, Renderer, Technique};
use std::path::{Path, PathBuf};

/// Which path and how many frames of it (shared by `path` and `compare --path`).
#[derive(Args, Clone, Debug)]
pub struct PathChoice {
    /// Camera path: a name the scene lists (`obscura scenes`; files without paths of their own
    /// have `orbit`), or a .json keyframe file (docs/PATHS.md).
    #[arg(long = "path")]
    pub path: Option<String>,
    /// Frames sampled evenly along the path, first and last keyframe included (at most 100000;
    /// every frame's images stay in memory for the temporal metrics, so frames × size must also
    /// fit in 8 GiB).
    #[arg(long, default_value_t = 24,
          value_parser = clap::value_parser!(u32).range(0..=crate::args::MAX_FRAME_COUNT))]
    pub frames: u32,
}

impl PathChoice {
    /// The path asked for; `None` (no `--path`) gives the scene's first.
    pub fn resolve(&self, scene: &Scene, aspect: f32) -> Result<CameraPath> {
        let path = match self.path.as_deref() {
            Some(spec) if spec.to_ascii_lowercase().ends_with(".json") => {
                CameraPath::from_json_file(Path::new(spec))?
            }
            Some(name) => scene.path(name, aspect)?,
            None => {
                let first = scene
                    .path_names()
                    .into_iter()
                    .next()
                    .expect("orbit at least");
                scene.path(&first, aspect)?
            }
        };
        if self.frames < 2 {
            bail!(
                "--frames {} is too few to see motion: give at least 2 frames (default 24)",
                self.frames
            );
        }
        if path.keyframes().len() < 2 {
            // A still camera is a fair test (flicker without motion), so said, not refused.
            eprintln!(
                "warning: camera path '{}' has one keyframe: a still camera, all {} frames see \
                 the same view (give two or more keyframes to move; docs/PATHS.md)",
                path.name, self.frames
            );
        }
        Ok(path)
    }
}

/// Refuses single-camera options next to a path, which would silently do nothing.
pub fn check_no_camera(scene: &SceneArgs) -> Result<()> {
    if scene.camera.is_some() || scene.eye.is_some() || scene.fov.is_some() {
        bail!(
            "--camera, --eye/--target and --fov choose one view, but a camera path moves the \
             camera: leave them out, or put the views into a path file (--path file.json)"
        );
    }
    Ok(())
}

/// Everything rendered along a path.
pub struct PathRun {
    pub path: CameraPath,
    pub times: Vec<f32>,
    pub views: Vec<FrameView>,
    /// Visible linear depth of each frame (0: background).
    pub depths: Vec<Vec<f32>>,
    /// Each technique's AO, one visible image per frame.
    pub techniques: Vec<(Technique, serde_json::Value, Vec<Vec<f32>>)>,
    /// The reference's AO per frame, when asked for.
    pub reference: Option<Vec<Vec<f32>>>,
}

/// One technique's scores along the path against the reference.
pub struct Score {
    pub temporal: PathMetrics,
    /// MSE against the reference, per frame.
    pub mse: Vec<f64>,
}

impl PathRun {
    /// Each technique's scores, computed once (`None` without a reference).
    pub fn scores(&self) -> Result<Vec<Option<Score>>> {
        let frames = self.frames();
        self.techniques
            .iter()
            .map(|(_, _, images)| {
                self.reference
                    .as_ref()
                    .map(|r| {
                        Ok(Score {
                            temporal: path_metrics(&frames, images, r)?,
                            mse: frame_mse(self, images, r)?,
                        })
                    })
                    .transpose()
            })
            .collect()
    }

    /// The frames as the temporal metrics take them.
    pub fn frames(&self) -> Vec<PathFrame<'_>> {
        self.views
            .iter()
            .zip(&self.depths)
            .map(|(&view, depth)| PathFrame { view, depth })
            .collect()
    }
}

/// How to render a path: sizes, techniques, settings, and the reference model if any.
pub struct PathJob<'a> {
    pub scene: &'a Scene,
    pub path: CameraPath,
    pub frames: u32,
    pub width: u32,
    pub height: u32,
    pub guard_band: u32,
    pub techniques: &'a [Technique],
    pub ao: &'a AoArgs,
    pub reference: Option<(&'a ReferenceArgs, ReferenceModel)>,
    /// The scene's BVH, built once for every ray-traced technique and every frame's reference.
    pub bvh: BvhCache,
}

impl PathJob<'_> {
    /// A renderer of `technique` at the job's size, with its settings.
    pub fn renderer(&self, gpu: &Gpu, technique: Technique) -> Result<(Renderer, AoSettings)> {
        let settings = self.ao.settings(technique)?;
        let renderer = Renderer::with_bvh_cache(
            gpu,
            self.scene,
            &settings,
            self.width,
            self.height,
            self.guard_band,
            &self.bvh,
        )?;
        Ok((renderer, settings))
    }
}

/// Renders every frame of every technique (one renderer per technique, reused along the
/// path), then the reference of every frame when asked.
pub fn render_path(gpu: &Gpu, job: &PathJob) -> Result<PathRun> {
    check_path_memory(
        job.frames,
        (job.width, job.height),
        job.guard_band,
        job.techniques.len(),
        job.reference.is_some(),
    )?;
    let samples = job.path.sample(job.frames)?;
    let near = obscura::near_plane(job.scene);
    let views: Vec<FrameView> = samples
        .iter()
        .map(|(_, c)| FrameView::new(*c, job.width, job.height, job.guard_band, near))
        .collect();
    let progress = bar(
        u64::from(job.frames) * job.techniques.len() as u64,
        "rendering",
    );
    let mut gbuffers: Vec<GBufferImage> = Vec::new();
    let mut techniques = Vec::new();
    for &technique in job.techniques {
        let (mut renderer, settings) = job.renderer(gpu, technique)?;
        let mut images = Vec::with_capacity(samples.len());
        for (_, camera) in &samples {
            renderer.render_frame(camera)?;
            images.push(renderer.read_ao()?);
            if gbuffers.len() < samples.len() {
                gbuffers.push(renderer.read_gbuffer()?);
            }
            progress.inc(1);
        }
        crate::args::warn_stack_overflows(&renderer)?;
        techniques.push((
            technique,
            serde_json::to_value(settings.resolved())?,
            images,
        ));
    }
    progress.finish_and_clear();
    let depths = gbuffers
        .iter()
        .map(|g| g.visible_depth(job.guard_band))
        .collect();
    let reference = match job.reference {
        None => None,
        Some((args, model)) => {
            let settings = args.settings(model, job.ao)?;
            let blur = job.ao.settings(Technique::Vao)?.blur;
            let tracer = args.tracer(Some(gpu));
            let mut frames = Vec::with_capacity(views.len());
            for (k, (view, gbuffer)) in views.iter().zip(&gbuffers).enumerate() {
                eprintln!("reference: frame {} of {}", k + 1, views.len());
                let image = compute_or_load(
                    tracer,
                    job.scene,
                    &job.bvh,
                    *view,
                    &settings,
                    !args.no_cache,
                )?;
                frames.push(as_compared(image, model, &blur, gbuffer, view));
            }
            Some(frames)
        }
    };
    Ok(PathRun {
        path: job.path.clone(),
        times: samples.iter().map(|(t, _)| *t).collect(),
        views,
        depths,
        techniques,
        reference,
    })
}

/// Most bytes of images a path run keeps in memory ([`check_path_memory`]).
const PATH_MEMORY_LIMIT: u64 = 8 << 30;

/// What [`render_path`] keeps until the end, for the temporal metrics and the outputs: every
/// frame's AO image of every technique, its G-buffer (depth and normals over the framebuffer,
/// guard band included), its visible depth and, with a reference, the reference image. Refused
/// above [`PATH_MEMORY_LIMIT`] before anything is rendered (issue 62, defect 5: `--frames
/// 1000000000` aborted allocating).
pub fn check_path_memory(
    frames: u32,
    (width, height): (u32, u32),
    guard_band: u32,
    techniques: usize,
    with_reference: bool,
) -> Result<()> {
    let visible = u64::from(width) * u64::from(height);
    let guard = 2 * u64::from(guard_band);
    let framebuffer = (u64::from(width) + guard) * (u64::from(height) + guard);
    let images = techniques as u64 + 1 + u64::from(with_reference);
    let per_frame = visible * 4 * images + framebuffer * 16;
    let bytes = per_frame.saturating_mul(u64::from(frames));
    if bytes > PATH_MEMORY_LIMIT {
        let gib = |b: u64| b as f64 / f64::from(1u32 << 30);
        let fitting = PATH_MEMORY_LIMIT / per_frame.max(1);
        bail!(
            "--frames {} at --size {}x{} with {} technique(s) would keep {:.1} GiB of images in \
             memory (every frame's AO and G-buffer, for the temporal metrics), more than the \
             limit of {:.0} GiB: use at most {fitting} frames at this size, or a smaller --size",
            frames,
            width,
            height,
            techniques,
            gib(bytes),
            gib(PATH_MEMORY_LIMIT)
        );
    }
    Ok(())
}

#[derive(Args)]
pub struct PathArgs {
    #[command(flatten)]
    scene: SceneArgs,
    #[command(flatten)]
    choice: PathChoice,
    /// Visible image size WIDTHxHEIGHT.
    #[arg(long, value_parser = parse_size, default_value = "320x180")]
    size: (u32, u32),
    #[arg(long, default_value = "vao", value_parser = parse_technique_list, help = crate::args::techniques_help())]
    techniques: TechniqueList,
    /// Also trace the reference of every frame, and report each technique's temporal error,
    /// popping and per-frame error against it.
    #[arg(long = "with-reference")]
    with_reference: bool,
    /// Ground-truth model for --with-reference: vao, vao-mean (vao averaged over its pattern's 16
    /// turns, for --temporal) or hemisphere.
    #[arg(long, value_parser = |s: &str| s.parse::<ReferenceModel>(), default_value = "vao")]
    reference_model: ReferenceModel,
    #[command(flatten)]
    reference: ReferenceArgs,
    #[command(flatten)]
    ao: AoArgs,
    /// Also write every frame as a float EXR beside its PNG.
    #[arg(long)]
    exr: bool,
    /// Output folder (created if missing): one folder of numbered frames and an animation.gif
    /// per technique (and `reference/`), and path.json.
    #[arg(long)]
    out: PathBuf,
}

/// One frame in path.json.
#[derive(serde::Serialize)]
struct FrameInfo {
    index: usize,
    time: f32,
    eye: [f32; 3],
    target: [f32; 3],
    fov: f32,
    /// Fraction of pixels matched to the previous frame by reprojection (from frame 1 on).
    #[serde(skip_serializing_if = "Option::is_none")]
    matched: Option<f64>,
}

/// One technique in path.json.
#[derive(serde::Serialize)]
struct TechniqueInfo {
    technique: String,
    settings: serde_json::Value,
    /// Mean AO of each frame.
    mean_ao: Vec<f64>,
    /// MSE against the reference per frame (with --with-reference).
    #[serde(skip_serializing_if = "Option::is_none")]
    mse: Option<Vec<f64>>,
    /// Temporal error and popping, pooled and per frame pair (with --with-reference).
    #[serde(skip_serializing_if = "Option::is_none")]
    temporal: Option<PathMetrics>,
}

pub fn run(options: &obscura::GpuOptions, args: &PathArgs) -> Result<()> {
    check_no_camera(&args.scene)?;
    let techniques = args.techniques.0.clone();
    for &t in &techniques {
        args.ao.settings(t)?;
    }
    if args.with_reference {
        args.reference.settings(args.reference_model, &args.ao)?;
    }
    let (width, height) = args.size;
    // Before the scene is loaded and the output folder made (render_path checks again).
    check_path_memory(
        args.choice.frames,
        args.size,
        args.ao.guard_band(height),
        techniques.len(),
        args.with_reference,
    )?;
    let scene = args.scene.load()?;
    let path = args.choice.resolve(&scene, width as f32 / height as f32)?;
    let out_folder = crate::args::prepare_out_folder(&args.out, "the frames")?;
    let gpu = Gpu::new(options)?;
    let job = PathJob {
        scene: &scene,
        path,
        frames: args.choice.frames,
        width,
        height,
        guard_band: args.ao.guard_band(height),
        techniques: &techniques,
        ao: &args.ao,
        reference: args
            .with_reference
            .then_some((&args.reference, args.reference_model)),
        bvh: BvhCache::new(),
    };
    let run = render_path(&gpu, &job)?;
    let scores = run.scores()?;
    write_run(&run, &scores, &scene, args, width, height)?;
    out_folder.keep();
    print_summary(&run, &scores);
    Ok(())
}

/// Frames, previews and path.json.
fn write_run(
    run: &PathRun,
    scores: &[Option<Score>],
    scene: &Scene,
    args: &PathArgs,
    width: u32,
    height: u32,
) -> Result<()> {
    let delay_ms = frame_delay_ms(&run.times);
    let named = run
        .techniques
        .iter()
        .map(|(t, _, images)| (t.name(), images))
        .chain(run.reference.iter().map(|r| ("reference", r)));
    for (name, images) in named {
        let dir = args.out.join(name);
        std::fs::create_dir_all(&dir)
            .with_context(|| format!("cannot create '{}'", dir.display()))?;
        for (k, ao) in images.iter().enumerate() {
            output::write_ao(&dir.join(format!("frame_{k:04}.png")), width, height, ao)?;
            if args.exr {
                output::write_ao(&dir.join(format!("frame_{k:04}.exr")), width, height, ao)?;
            }
        }
        output::write_atomically(&dir.join("animation.gif"), |tmp| {
            let mut file =
                std::io::BufWriter::new(std::fs::File::create(tmp).map_err(|e| e.to_string())?);
            obscura::report::temporal::write_gif(&mut file, width, height, images, delay_ms)
        })?;
    }
    let matched = scores.iter().flatten().next().map(|s| &s.temporal.pairs);
    let reference_spp = args
        .reference
        .settings(args.reference_model, &args.ao)?
        .reported_spp();
    let json = serde_json::json!({
        "scene": scene.name,
        "path": run.path,
        "width": width,
        "height": height,
        "guard_band": args.ao.guard_band(height),
        "reference": run.reference.as_ref().map(|_| serde_json::json!({
            "model": args.reference_model.name(),
            "spp": reference_spp,
        })),
        "frames": run.views.iter().zip(&run.times).enumerate().map(|(k, (v, &time))| FrameInfo {
            index: k,
            time,
            eye: v.camera.eye.into(),
            target: v.camera.target.into(),
            fov: v.camera.fov_y_deg,
            matched: k.checked_sub(1).and_then(|p| matched.map(|m| m[p].matched)),
        }).collect::<Vec<_>>(),
        "techniques": run.techniques.iter().zip(scores).map(|((t, settings, images), score)| TechniqueInfo {
            technique: t.name().to_string(),
            settings: settings.clone(),
            mean_ao: images.iter().map(|a| mean(a)).collect(),
            mse: score.as_ref().map(|s| s.mse.clone()),
            temporal: score.as_ref().map(|s| s.temporal.clone()),
        }).collect::<Vec<_>>(),
    });
    let file = args.out.join("path.json");
    output::write_atomically(&file, |tmp| {
        std::fs::write(
            tmp,
            serde_json::to_string_pretty(&json).map_err(|e| e.to_string())? + "\n",
        )
        .map_err(|e| e.to_string())
    })?;
    eprintln!(
        "wrote {} frames of {} technique(s){} into {}",
        run.times.len(),
        run.techniques.len(),
        if run.reference.is_some() {
            " and the reference"
        } else {
            ""
        },
        args.out.display()
    );
    Ok(())
}

fn print_summary(run: &PathRun, scores: &[Option<Score>]) {
    if run.reference.is_none() {
        return;
    }
    println!("| technique | temporal error | popping | mean MSE | worst-frame MSE |");
    println!("|:--|--:|--:|--:|--:|");
    for ((t, _, _), score) in run.techniques.iter().zip(scores) {
        let Some(Score { temporal, mse }) = score else {
            continue;
        };
        println!(
            "| `{}` | {:.5} | {:.2} % | {:.3e} | {:.3e} |",
            t.name(),
            temporal.temporal_error,
            100.0 * temporal.popping,
            mse.iter().sum::<f64>() / mse.len() as f64,
            mse.iter().copied().fold(0.0, f64::max)
        );
    }
}

fn mean(a: &[f32]) -> f64 {
    a.iter().map(|&v| f64::from(v)).sum::<f64>() / a.len().max(1) as f64
}

/// MSE of every frame against the reference's.
fn frame_mse(run: &PathRun, images: &[Vec<f32>], reference: &[Vec<f32>]) -> Result<Vec<f64>> {
    let (w, h) = (run.views[0].width as usize, run.views[0].height as usize);
    images
        .iter()
        .zip(reference)
        .map(|(a, r)| Ok(metrics::mse(&Image::new(w, h, a)?, &Image::new(w, h, r)?)?))
        .collect()
}
