//! `obscura reference`: the ray-traced ground truth of one view, on the GPU (or the CPU oracle).

use crate::args::{parse_size, AoArgs, SceneArgs};
use crate::progress::bar;
use anyhow::{bail, Result};
use clap::Args;
use obscura::bvh::BvhCache;
use obscura::reference::cache;
use obscura::reference::gpu::render_reference_gpu;
use obscura::reference::ground_truth::{
    render_reference_counted, ReferenceModel, ReferenceSettings,
};
use obscura::scene::Scene;
use obscura::{output, FrameView, Technique};
use std::path::PathBuf;
use std::time::Instant;

/// Options shared by `reference` and `compare` for the reference model.
#[derive(Args, Clone, Debug)]
pub struct ReferenceArgs {
    /// Hemisphere model: rays per pixel [default: 1024].
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=crate::args::MAX_SPP))]
    pub spp: Option<u32>,
    /// Hemisphere model: weight hits by max(0, 1 - t/R) instead of counting them fully.
    #[arg(long)]
    pub falloff: bool,
    /// Hemisphere model: seed of the per-pixel sample rotations [default: 0].
    #[arg(long)]
    pub seed: Option<u64>,
    /// Recompute the reference even if the cache has it.
    #[arg(long)]
    pub no_cache: bool,
    /// Trace on the CPU (the oracle) instead of the GPU.
    #[arg(long, conflicts_with = "gpu")]
    pub cpu: bool,
    /// Trace on the GPU even when the adapter is a software (CPU) device, where the CPU tracer is
    /// several times faster and used by default.
    #[arg(long)]
    pub gpu: bool,
}

impl ReferenceArgs {
    /// Where to trace: `gpu` unless `--cpu`, or unless the library prefers the CPU on this
    /// adapter ([`obscura::reference::cpu_tracer_by_default`]: a software one) and `--gpu` was
    /// not given. Says so when it falls back.
    pub fn tracer<'g>(&self, gpu: Option<&'g obscura::Gpu>) -> Option<&'g obscura::Gpu> {
        let gpu = gpu.filter(|_| !self.cpu)?;
        if obscura::reference::cpu_tracer_by_default(gpu) && !self.gpu {
            eprintln!(
                "note: tracing the reference on the CPU: adapter '{}' is a software device, where \
                 the CPU tracer is faster (--gpu to trace on it anyway)",
                gpu.summary.name
            );
            return None;
        }
        Some(gpu)
    }

    pub fn settings(&self, model: ReferenceModel, ao: &AoArgs) -> Result<ReferenceSettings> {
        if model != ReferenceModel::Hemisphere
            && (self.spp.is_some() || self.falloff || self.seed.is_some())
        {
            bail!(
                "--spp, --falloff and --seed apply to the hemisphere reference model only (the vao \
                 models trace every sample column exactly): leave them out, or use the hemisphere \
                 model"
            );
        }
        let defaults = ReferenceSettings::default();
        let settings = ReferenceSettings {
            model,
            vao: ao.settings(Technique::Vao)?.vao,
            spp: self.spp.unwrap_or(defaults.spp),
            falloff: self.falloff,
            seed: self.seed.unwrap_or(defaults.seed),
        };
        if let Err(e) = settings.validate() {
            bail!(e);
        }
        Ok(settings)
    }
}

#[derive(Args)]
pub struct ReferenceCmdArgs {
    #[command(flatten)]
    scene: SceneArgs,
    /// Visible image size WIDTHxHEIGHT.
    #[arg(long, value_parser = parse_size, default_value = "640x360")]
    size: (u32, u32),
    /// Ground-truth model: vao (the quantity VAO estimates, nothing hidden), vao-mean (that,
    /// averaged over the 16 turns of VAO's pattern) or hemisphere.
    #[arg(long, value_parser = |s: &str| s.parse::<ReferenceModel>(), default_value = "vao")]
    model: ReferenceModel,
    #[command(flatten)]
    reference: ReferenceArgs,
    #[command(flatten)]
    ao: AoArgs,
    /// Output image: .exr (float, linear) or .png (8-bit).
    #[arg(long)]
    out: PathBuf,
}

/// The reference for `view`, from the cache when it has it; traced on `gpu` when given, else on
/// the CPU, over the scene's BVH from `bvh` (built there on first use); reports rays/s when
/// computed.
pub fn compute_or_load(
    gpu: Option<&obscura::Gpu>,
    scene: &Scene,
    bvh: &BvhCache,
    view: FrameView,
    settings: &ReferenceSettings,
    use_cache: bool,
) -> Result<Vec<f32>> {
    let dir = cache::cache_dir();
    let key = cache::key(scene, &view, settings);
    let pixels = (view.width * view.height) as usize;
    if use_cache {
        if let Some(image) = cache::load(&dir, &key, pixels) {
            eprintln!("reference: reused from the cache ({})", dir.display());
            return Ok(image);
        }
    }
    let start = Instant::now();
    let builds = bvh.builds();
    let tree = bvh.get(scene);
    let build = if bvh.builds() > builds {
        format!("BVH build {:.2} s", start.elapsed().as_secs_f64())
    } else {
        "BVH reused".to_string()
    };
    let trace_start = Instant::now();
    let (image, rays, device) = match gpu {
        Some(gpu) => {
            let progress = bar(1, &format!("{} reference", settings.model));
            let (image, rays) =
                render_reference_gpu(gpu, scene, &tree, view, settings, &|done, total| {
                    progress.set_length(u64::from(total));
                    progress.set_position(u64::from(done));
                })?;
            progress.finish_and_clear();
            // Counted as if every pixel had geometry: an upper bound.
            (
                image,
                rays,
                format!("the GPU ({}), at most", gpu.summary.name),
            )
        }
        None => {
            let progress = bar(
                u64::from(view.height),
                &format!("{} reference", settings.model),
            );
            let (image, rays) =
                render_reference_counted(scene, &tree, view, settings, &|_| progress.inc(1));
            progress.finish_and_clear();
            (
                image,
                rays,
                format!("the CPU ({} threads)", rayon_threads()),
            )
        }
    };
    let seconds = trace_start.elapsed().as_secs_f64();
    eprintln!(
        "reference: {} model on {device} {rays} rays in {seconds:.2} s = {:.2} M rays/s ({build})",
        settings.model,
        rays as f64 / seconds / 1e6,
    );
    if use_cache {
        if let Err(e) = cache::store(&dir, &key, &image) {
            eprintln!("warning: could not cache the reference: {e}");
        }
    }
    Ok(image)
}

fn rayon_threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

pub fn run(gpu_options: &obscura::GpuOptions, args: &ReferenceCmdArgs) -> Result<()> {
    output::check_writable(&args.out)?;
    let settings = args.reference.settings(args.model, &args.ao)?;
    let (width, height) = args.size;
    let scene = args.scene.load()?;
    let camera = args.scene.camera(&scene, width as f32 / height as f32)?;
    let view = FrameView::new(
        camera,
        width,
        height,
        args.ao.guard_band(height),
        obscura::near_plane(&scene),
    );
    let gpu = if args.reference.cpu {
        None
    } else {
        match obscura::Gpu::new(gpu_options) {
            Ok(gpu) => Some(gpu),
            Err(e) => {
                eprintln!("note: tracing on the CPU ({e})");
                None
            }
        }
    };
    let image = compute_or_load(
        args.reference.tracer(gpu.as_ref()),
        &scene,
        &BvhCache::new(),
        view,
        &settings,
        !args.reference.no_cache,
    )?;
    output::write_ao(&args.out, width, height, &image)?;
    eprintln!("wrote {}", args.out.display());
    Ok(())
}
