//! `obscura compare`: techniques against a ray-traced reference, with an HTML report.

use super::path::{check_no_camera, render_path, PathChoice, PathJob};
use super::reference::{compute_or_load, ReferenceArgs};
use crate::args::{parse_size, parse_technique_list, AoArgs, SceneArgs, TechniqueList};
use anyhow::{Context, Result};
use clap::Args;
use obscura::bvh::BvhCache;
use obscura::reference::as_compared;
use obscura::reference::ground_truth::ReferenceModel;
use obscura::report::{write_report, Report, ReportInput, TechniqueImage, TemporalInput};
use obscura::scene::Scene;
use obscura::{FrameView, Gpu, PassProfiler, Renderer};
use std::path::{Path, PathBuf};

#[derive(Args)]
pub struct CompareArgs {
    #[command(flatten)]
    scene: SceneArgs,
    /// Visible image size WIDTHxHEIGHT.
    #[arg(long, value_parser = parse_size, default_value = "640x360")]
    size: (u32, u32),
    #[arg(long, default_value = "vao", value_parser = parse_technique_list, help = crate::args::techniques_help())]
    techniques: TechniqueList,
    /// Ground-truth model: vao, vao-mean (vao averaged over its pattern's 16 turns, for
    /// --temporal) or hemisphere.
    #[arg(long, value_parser = |s: &str| s.parse::<ReferenceModel>(), default_value = "vao")]
    reference_model: ReferenceModel,
    /// An outside renderer's AO of this view to compare against instead of tracing one: EXR or
    /// PNG, --size pixels, rows top to bottom, 1 = unoccluded, the first channel (PNG values
    /// read as 0..1, no gamma). Render it with the same camera (--camera, or --eye, --target and
    /// --fov, the vertical field of view) and AO distance (the techniques' radius). Used as it
    /// is (not blurred like the vao model's reference), but for its background: pixels with no
    /// geometry in the view count as 1 whatever the file holds there.
    #[arg(long, conflicts_with = "reference_model")]
    reference_image: Option<PathBuf>,
    /// The --reference-image's values are sRGB-encoded (a PNG saved through a display transform,
    /// as renderers often write 8-bit images): decode them to linear AO before comparing. Not
    /// with an EXR, whose values are linear.
    #[arg(long, requires = "reference_image")]
    reference_srgb: bool,
    #[command(flatten)]
    reference: ReferenceArgs,
    #[command(flatten)]
    ao: AoArgs,
    /// Output folder (created if missing): report.json, report.md, index.html and the images.
    #[arg(long)]
    out: PathBuf,
    #[command(flatten)]
    timing: TimingArgs,
    /// Along a camera path (--path NAME or file.json, --frames N): the report adds each
    /// technique's temporal error, popping and per-frame error; its images are the middle frame.
    #[command(flatten)]
    path: PathChoice,
}

/// How techniques are timed for the report's cost column and chart.
#[derive(Args, Clone, Copy, Debug)]
pub struct TimingArgs {
    /// Frames timed per technique after its first (the median is reported; 0: no timings). On a
    /// CPU adapter the times are marked as no GPU timings.
    #[arg(long, default_value_t = 3,
          value_parser = clap::value_parser!(u32).range(0..=crate::args::MAX_FRAME_COUNT))]
    pub timing_frames: u32,
}

/// Everything `compare` needs about one view, also used by `demo`.
pub struct Comparison<'a> {
    pub scene: &'a Scene,
    pub camera_name: &'a str,
    pub camera: obscura::scene::Camera,
    pub width: u32,
    pub height: u32,
    pub guard_band: u32,
    /// Frames timed per technique after the first (0: no timings).
    pub timing_frames: u32,
    /// The heat maps' scale; `None`: chosen from this comparison's differences.
    pub diff_scale: Option<f64>,
    /// An outside renderer's AO of this view, compared against instead of a traced reference.
    pub reference_image: Option<&'a ExternalReference>,
}

/// An AO image of the view made elsewhere (`compare --reference-image`).
pub struct ExternalReference {
    /// How the report names it: `image 'file.exr'`.
    pub name: String,
    /// Its values, row-major, the visible size.
    pub values: Vec<f32>,
}

impl ExternalReference {
    /// The image at `path`, which must be `width`×`height` with finite values; `srgb`: its values
    /// are sRGB-encoded (a PNG only) and are decoded to linear.
    pub fn load(path: &Path, (width, height): (u32, u32), srgb: bool) -> Result<Self> {
        let format = obscura::output::ImageFormat::from_path(path)?;
        if srgb && format == obscura::output::ImageFormat::Exr {
            anyhow::bail!(
                "--reference-srgb with --reference-image '{}': an EXR holds linear values; leave \
                 --reference-srgb out (it is for PNGs saved with the sRGB transfer)",
                path.display()
            );
        }
        let mut image = obscura::output::read_ao(path)?;
        if srgb {
            image
                .values
                .iter_mut()
                .for_each(|v| *v = srgb_to_linear(*v));
        }
        if (image.width, image.height) != (width, height) {
            anyhow::bail!(
                "--reference-image '{}' is {}x{} but the comparison renders {width}x{height}: \
                 give --size {}x{} (the size it was rendered at), or render it at {width}x{height}",
                path.display(),
                image.width,
                image.height,
                image.width,
                image.height
            );
        }
        let bad = image.values.iter().filter(|v| !v.is_finite()).count();
        if bad > 0 {
            anyhow::bail!(
                "--reference-image '{}': {bad} of its {} values are NaN or infinite: give an AO \
                 image with values in 0..1 (1 = unoccluded)",
                path.display(),
                image.values.len()
            );
        }
        let file = path.file_name().unwrap_or(path.as_os_str());
        Ok(Self {
            name: format!(
                "image '{}'{}",
                file.to_string_lossy(),
                if srgb { " (sRGB decoded)" } else { "" }
            ),
            values: image.values,
        })
    }
}

/// An outside reference with its background pixels (no geometry in our G-buffer) set to 1, as
/// obscura's own images have them: renderers write the background as 0, 1 or anything, and it
/// would otherwise count as error where no technique shades anything. Says on stderr how many
/// background pixels held another value.
fn outside_background_unoccluded(image: &ExternalReference, depth: &[f32]) -> Vec<f32> {
    let mut values = image.values.clone();
    let mut changed = 0;
    for (v, &d) in values.iter_mut().zip(depth) {
        if !obscura::metrics::has_geometry(d) {
            changed += usize::from(*v != 1.0);
            *v = 1.0;
        }
    }
    if changed > 0 {
        eprintln!(
            "note: {changed} background pixels of the {} (no geometry there in this view) held \
             values other than 1; they are compared as 1 (unoccluded), as obscura writes them",
            image.name
        );
    }
    values
}

/// The sRGB transfer function's inverse (IEC 61966-2-1): an encoded value in [0, 1] to linear.
fn srgb_to_linear(v: f32) -> f32 {
    if v <= 0.04045 {
        v / 12.92
    } else {
        ((v + 0.055) / 1.055).powf(2.4)
    }
}

/// Render every technique, get the reference (cached), write the report into `out`.
/// `on_render` sees each technique's renderer after its frame (e.g. to write a composite).
#[allow(clippy::too_many_arguments)]
pub fn compare(
    gpu: &Gpu,
    c: &Comparison,
    techniques: &[obscura::Technique],
    ao: &AoArgs,
    reference: &ReferenceArgs,
    model: ReferenceModel,
    out: &Path,
    on_render: &mut dyn FnMut(obscura::Technique, &Renderer) -> Result<()>,
) -> Result<Report> {
    let reference_settings = reference.settings(model, ao)?;
    let (model_name, spp, reference_radius) = match c.reference_image {
        Some(image) => (image.name.as_str(), None, None),
        None => (
            model.name(),
            reference_settings.reported_spp(),
            Some(reference_settings.vao.radius),
        ),
    };
    let mut images = Vec::new();
    let mut gbuffer = None;
    // One BVH for every ray-traced row and the reference.
    let bvh = BvhCache::new();
    for &technique in techniques {
        let settings = ao.settings(technique)?;
        let mut renderer = Renderer::with_bvh_cache(
            gpu,
            c.scene,
            &settings,
            c.width,
            c.height,
            c.guard_band,
            &bvh,
        )?;
        renderer.render(&c.camera, None)?;
        let ms = gpu_ms(gpu, &mut renderer, &c.camera, c.timing_frames)?;
        images.push((
            technique.name(),
            renderer.read_ao()?,
            serde_json::to_value(settings.resolved())?,
            ms,
        ));
        crate::args::warn_stack_overflows(&renderer)?;
        gbuffer = Some(renderer.read_gbuffer()?);
        on_render(technique, &renderer)?;
    }
    let gbuffer = gbuffer.context("no technique rendered")?;
    let depth = gbuffer.visible_depth(c.guard_band);
    let view = FrameView::new(
        c.camera,
        c.width,
        c.height,
        c.guard_band,
        obscura::near_plane(c.scene),
    );
    // The reference's values, owned here whichever way they came.
    let reference_values;
    let reference_image: &[f32] = match c.reference_image {
        Some(image) => {
            reference_values = outside_background_unoccluded(image, &depth);
            &reference_values
        }
        None => {
            let image = compute_or_load(
                reference.tracer(Some(gpu)),
                c.scene,
                &bvh,
                view,
                &reference_settings,
                !reference.no_cache,
            )?;
            let blur = ao.settings(obscura::Technique::Vao)?.blur;
            reference_values = as_compared(image, model, &blur, &gbuffer, &view);
            &reference_values
        }
    };
    std::fs::create_dir_all(out)
        .with_context(|| format!("cannot create output folder '{}'", out.display()))?;
    let input = ReportInput {
        scene: &c.scene.name,
        camera: c.camera_name,
        scene_options: &c.scene.options_description(),
        width: c.width,
        height: c.height,
        guard_band: c.guard_band,
        reference_model: model_name,
        spp,
        reference_radius,
        reference: reference_image,
        depth: &depth,
        techniques: images
            .iter()
            .map(|(name, ao, settings, ms)| TechniqueImage {
                name,
                ao,
                settings: Some(settings),
                gpu_ms: *ms,
            })
            .collect(),
        halo_radius_px: 4,
        halo_relative_jump: 0.1,
        adapter: &gpu.summary.name,
        software_adapter: gpu.summary.device_type == "Cpu",
        diff_scale: c.diff_scale,
        temporal: None,
    };
    Ok(write_report(out, &input)?)
}

/// The median over `frames` frames (after the one already rendered, which warmed up) of the
/// technique's GPU time: every pass but the G-buffer, which an engine has anyway. `None` when
/// not asked for, or when the adapter cannot time passes (said once).
fn gpu_ms(
    gpu: &Gpu,
    renderer: &mut Renderer,
    camera: &obscura::scene::Camera,
    frames: u32,
) -> Result<Option<f64>> {
    if frames == 0 {
        return Ok(None);
    }
    if renderer.settings().hemisphere.time_budget > 0.0 && renderer.settings().ray_budget_active() {
        // A time budget follows each frame's timings: one profiler a frame.
        let mut totals = Vec::new();
        for _ in 0..frames {
            let timings = renderer.render_frame(camera)?.unwrap_or_default();
            totals.push(obscura::TimeBudget::ao_ms(&timings));
        }
        return Ok(Some(super::bench::median(totals)));
    }
    let mut profiler = match PassProfiler::new(gpu, frames) {
        Ok(p) => p,
        Err(e) => {
            static SAID: std::sync::Once = std::sync::Once::new();
            SAID.call_once(|| eprintln!("warning: no timings in the report: {e}"));
            return Ok(None);
        }
    };
    for _ in 0..frames {
        renderer.render(camera, Some(&mut profiler))?;
        gpu.finish()?;
    }
    let totals = profiler
        .read(gpu)?
        .iter()
        // Every pass but the G-buffer's raster pass and its resolve.
        .map(obscura::TimeBudget::ao_ms)
        .collect();
    Ok(Some(super::bench::median(totals)))
}

pub fn run(options: &obscura::GpuOptions, args: &CompareArgs) -> Result<()> {
    // Check everything typed before the slow parts.
    let techniques = args.techniques.0.clone();
    args.reference.settings(args.reference_model, &args.ao)?;
    for &t in &techniques {
        args.ao.settings(t)?;
    }
    let out_folder = crate::args::prepare_out_folder(
        &args.out,
        "the report (report.json, report.md, index.html and the images go into it)",
    )?;
    let (width, height) = args.size;
    let reference_image = match &args.reference_image {
        Some(_) if args.path.path.is_some() => anyhow::bail!(
            "--reference-image is one view's AO and --path renders many: leave one of them out"
        ),
        Some(path) => Some(ExternalReference::load(
            path,
            (width, height),
            args.reference_srgb,
        )?),
        None => None,
    };
    let scene = args.scene.load()?;
    if args.path.path.is_some() {
        check_no_camera(&args.scene)?;
        let path = args.path.resolve(&scene, width as f32 / height as f32)?;
        let gpu = Gpu::new(options)?;
        let job = PathJob {
            scene: &scene,
            path,
            frames: args.path.frames,
            width,
            height,
            guard_band: args.ao.guard_band(height),
            techniques: &techniques,
            ao: &args.ao,
            reference: Some((&args.reference, args.reference_model)),
            bvh: BvhCache::new(),
        };
        compare_path(&gpu, &job, args.timing.timing_frames, &args.out)?;
        out_folder.keep();
        return print_report(&args.out, techniques.len());
    }
    let camera = args.scene.camera(&scene, width as f32 / height as f32)?;
    let camera_name = args.scene.camera_name(&scene);
    let gpu = Gpu::new(options)?;
    let comparison = Comparison {
        scene: &scene,
        camera_name: &camera_name,
        camera,
        width,
        height,
        guard_band: args.ao.guard_band(height),
        timing_frames: args.timing.timing_frames,
        diff_scale: None,
        reference_image: reference_image.as_ref(),
    };
    let report = compare(
        &gpu,
        &comparison,
        &techniques,
        &args.ao,
        &args.reference,
        args.reference_model,
        &args.out,
        &mut |_, _| Ok(()),
    )?;
    out_folder.keep();
    print_report(&args.out, report.results.len())
}

fn print_report(out: &Path, techniques: usize) -> Result<()> {
    println!(
        "{}",
        std::fs::read_to_string(out.join("report.md")).unwrap_or_default()
    );
    eprintln!(
        "wrote {} ({techniques} techniques)",
        out.join("index.html").display(),
    );
    Ok(())
}

/// `compare --path`: every frame of every technique and of the reference; the report's images
/// and single-frame metrics are the middle frame's, its temporal section covers the whole path.
fn compare_path(gpu: &Gpu, job: &PathJob, timing_frames: u32, out: &Path) -> Result<Report> {
    let run = render_path(gpu, job)?;
    let reference = run
        .reference
        .as_ref()
        .context("the reference was asked for")?;
    let mid = run.times.len() / 2;
    let view = run.views[mid];
    let mut timings = Vec::new();
    for (technique, _, _) in &run.techniques {
        let (mut renderer, _) = job.renderer(gpu, *technique)?;
        renderer.render(&view.camera, None)?;
        timings.push(gpu_ms(gpu, &mut renderer, &view.camera, timing_frames)?);
    }
    let frames = run.frames();
    let camera = format!(
        "path {}, frame {mid} of {} (t = {:.2} s)",
        run.path.name,
        run.times.len(),
        run.times[mid]
    );
    let (reference_args, model) = job.reference.context("the reference was asked for")?;
    let reference_settings = reference_args.settings(model, job.ao)?;
    let spp = reference_settings.reported_spp();
    let input = ReportInput {
        scene: &job.scene.name,
        camera: &camera,
        scene_options: &job.scene.options_description(),
        width: job.width,
        height: job.height,
        guard_band: job.guard_band,
        reference_model: model.name(),
        spp,
        reference_radius: Some(reference_settings.vao.radius),
        reference: &reference[mid],
        depth: &run.depths[mid],
        techniques: run
            .techniques
            .iter()
            .zip(&timings)
            .map(|((t, settings, images), ms)| TechniqueImage {
                name: t.name(),
                ao: &images[mid],
                settings: Some(settings),
                gpu_ms: *ms,
            })
            .collect(),
        halo_radius_px: 4,
        halo_relative_jump: 0.1,
        adapter: &gpu.summary.name,
        software_adapter: gpu.summary.device_type == "Cpu",
        diff_scale: None,
        temporal: Some(TemporalInput {
            path: &run.path.name,
            times: &run.times,
            frames: &frames,
            reference,
            techniques: run
                .techniques
                .iter()
                .map(|(t, _, images)| (t.name(), images.as_slice()))
                .collect(),
        }),
    };
    Ok(write_report(out, &input)?)
}
