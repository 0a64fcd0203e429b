//! `reference` and `compare`: the ray-traced ground truth of a view and the `compare` report's
//! metrics, from the library's tracers (`reference::gpu`, `reference::ground_truth`),
//! `reference::as_compared` and `report::build_report`, as the CLI's commands use them.

use crate::arrays;
use crate::device::{gpu_of, Device};
use crate::errors::{from_lib, input};
use crate::scene::Scene;
use crate::settings::{resolve, Given};
use crate::view::{camera_of, Size};
use numpy::PyArray2;
use obscura::bvh::Bvh;
use obscura::reference::ground_truth::{
    render_reference_counted, ReferenceModel, ReferenceSettings,
};
use obscura::reference::{as_compared, cache, cpu_tracer_by_default, gpu::render_reference_gpu};
use obscura::report::{build_report, ReportInput, TechniqueImage};
use obscura::scene::Scene as LibScene;
use obscura::{FrameView, Gpu, Renderer, Technique};
use pyo3::prelude::*;

/// The reference's own options, checked before any work.
struct ReferenceOptions {
    settings: ReferenceSettings,
    /// Trace on the CPU (else on the device).
    cpu: bool,
}

#[allow(clippy::too_many_arguments)]
fn reference_options(
    model: &str,
    spp: Option<u32>,
    falloff: bool,
    seed: Option<u64>,
    given: Option<&Given>,
    preset: Option<&str>,
    units: Option<&str>,
    tracer: &str,
) -> PyResult<(ReferenceOptions, obscura::AoSettings)> {
    let model: ReferenceModel = model.parse().map_err(|e: String| input(e))?;
    if model != ReferenceModel::Hemisphere && (spp.is_some() || falloff || seed.is_some()) {
        return Err(input(
            "spp, falloff and seed apply to the hemisphere reference model only (the vao models \
             trace every sample column exactly): leave them out, or use model=\"hemisphere\"",
        ));
    }
    if spp == Some(0) {
        return Err(input(
            "spp 0: the hemisphere reference needs at least 1 ray per pixel",
        ));
    }
    // The vao models' kernel and the blur the report compares through: the vao row's settings.
    let vao = resolve(Some("vao"), given, preset, units)?;
    let defaults = ReferenceSettings::default();
    let settings = ReferenceSettings {
        model,
        vao: vao.vao,
        spp: spp.unwrap_or(defaults.spp),
        falloff,
        seed: seed.unwrap_or(defaults.seed),
    };
    let cpu = match tracer {
        "auto" | "gpu" => false,
        "cpu" => true,
        other => {
            return Err(input(format!(
                "tracer '{other}' is not \"auto\" (the CPU on a software adapter, else the \
                 GPU), \"cpu\" or \"gpu\""
            )))
        }
    };
    Ok((ReferenceOptions { settings, cpu }, vao))
}

/// Traces the reference of `view` (on `gpu`, else on the CPU). With `cache`, reads it from the
/// CLI's reference cache ([`obscura::reference::cache`]: the same key, so either side reuses the
/// other's images) when there, and stores it there after tracing. `bvh` is built on demand, so
/// a cached image costs no BVH build.
fn trace(
    gpu: Option<&Gpu>,
    scene: &LibScene,
    bvh: &dyn Fn() -> std::sync::Arc<Bvh>,
    view: FrameView,
    settings: &ReferenceSettings,
    cache: bool,
) -> Result<Vec<f32>, obscura::Error> {
    let dir = cache::cache_dir();
    let key = cache::key(scene, &view, settings);
    if cache {
        if let Some(image) = cache::load(&dir, &key, (view.width * view.height) as usize) {
            return Ok(image);
        }
    }
    let bvh = bvh();
    let image = match gpu {
        Some(gpu) => render_reference_gpu(gpu, scene, &bvh, view, settings, &|_, _| {})?.0,
        None => render_reference_counted(scene, &bvh, view, settings, &|_| {}).0,
    };
    if cache {
        // A cache that cannot be written costs the next call a trace, nothing else.
        let _ = cache::store(&dir, &key, &image);
    }
    Ok(image)
}

/// The GPU to trace on: none with ``tracer="cpu"``, none on a software adapter with
/// ``"auto"`` (the CLI's default there), else the device's.
fn tracer_gpu(tracer: &str, gpu: &Gpu) -> Option<Gpu> {
    match tracer {
        "cpu" => None,
        "auto" if cpu_tracer_by_default(gpu) => None,
        _ => Some(gpu.clone()),
    }
}

/// The ray-traced ground truth of one view, as ``obscura reference`` computes it: ``model``
/// ``"vao"`` (what VAO estimates with nothing hidden), ``"vao-mean"`` or ``"hemisphere"``
/// (cosine-weighted rays within R: ``spp`` rays per pixel, default 1024, ``falloff``,
/// ``seed``); the vao models read the vao row's settings (``settings``, ``preset``, ``units``).
/// ``tracer``: ``"auto"`` (the CPU on a software adapter, as the CLI), ``"cpu"`` or ``"gpu"``.
/// ``cache=True``: reuse and fill the CLI's reference cache (``OBSCURA_CACHE_DIR``, else
/// ``~/.cache/obscura/references``), keyed by the scene's contents, the view and the settings.
/// Returns float32 (height, width), C-contiguous.
#[pyfunction]
#[pyo3(signature = (scene, model="vao", *, camera=None, width=640, height=360, guard_band=None,
    spp=None, falloff=false, seed=None, settings=None, preset=None, units=None, tracer="auto",
    cache=false, device=None))]
#[allow(clippy::too_many_arguments)]
pub fn reference<'py>(
    py: Python<'py>,
    scene: &Bound<'py, Scene>,
    model: &str,
    camera: Option<&Bound<'py, PyAny>>,
    width: u32,
    height: u32,
    guard_band: Option<u32>,
    spp: Option<u32>,
    falloff: bool,
    seed: Option<u64>,
    settings: Option<&Bound<'py, PyAny>>,
    preset: Option<&str>,
    units: Option<&str>,
    tracer: &str,
    cache: bool,
    device: Option<&Bound<'py, Device>>,
) -> PyResult<Bound<'py, PyArray2<f32>>> {
    let size = Size::new(width, height, guard_band)?;
    let given = Given::from_py(settings)?;
    let (options, _) = reference_options(
        model,
        spp,
        falloff,
        seed,
        given.as_ref(),
        preset,
        units,
        tracer,
    )?;
    let camera = camera_of(py, scene, camera, size)?.camera;
    let lib_scene = scene.get().scene.clone();
    let gpu = if options.cpu {
        None
    } else {
        tracer_gpu(tracer, &gpu_of(py, device)?)
    };
    let image = py
        .detach(|| {
            let view = size.frame_view(camera, &lib_scene);
            let bvh = || std::sync::Arc::new(Bvh::build(&lib_scene));
            trace(
                gpu.as_ref(),
                &lib_scene,
                &bvh,
                view,
                &options.settings,
                cache,
            )
        })
        .map_err(from_lib)?;
    arrays::image(py, image, size.width, size.height)
}

/// Compares ``techniques`` (names) with the reference of one view, as ``obscura compare
/// --timing-frames 0`` does, and returns its report (``report.json``'s content) as a dict:
/// ``results`` holds each technique's ``mse``, ``mae``, ``psnr``, ``ssim``, ``halo_bright``,
/// ``halo_dark`` and the settings it ran with. Arguments as ``render`` and ``reference``
/// (``reference_model`` is ``reference``'s ``model``; ``cache`` as ``reference``'s).
#[pyfunction]
#[pyo3(signature = (scene, techniques, *, reference_model="vao", camera=None, width=640,
    height=360, guard_band=None, settings=None, preset=None, units=None, spp=None, falloff=false,
    seed=None, tracer="auto", cache=false, device=None))]
#[allow(clippy::too_many_arguments)]
pub fn compare_json(
    py: Python<'_>,
    scene: &Bound<'_, Scene>,
    techniques: Vec<String>,
    reference_model: &str,
    camera: Option<&Bound<'_, PyAny>>,
    width: u32,
    height: u32,
    guard_band: Option<u32>,
    settings: Option<&Bound<'_, PyAny>>,
    preset: Option<&str>,
    units: Option<&str>,
    spp: Option<u32>,
    falloff: bool,
    seed: Option<u64>,
    tracer: &str,
    cache: bool,
    device: Option<&Bound<'_, Device>>,
) -> PyResult<String> {
    let size = Size::new(width, height, guard_band)?;
    if techniques.is_empty() {
        return Err(input(
            "techniques is empty: name at least one (e.g. [\"vao\"])",
        ));
    }
    let given = Given::from_py(settings)?;
    let (options, vao) = reference_options(
        reference_model,
        spp,
        falloff,
        seed,
        given.as_ref(),
        preset,
        units,
        tracer,
    )?;
    // Every technique's settings checked before any work.
    let rows = techniques
        .iter()
        .map(|t| resolve(Some(t), given.as_ref(), preset, units))
        .collect::<PyResult<Vec<_>>>()?;
    let chosen = camera_of(py, scene, camera, size)?;
    let gpu = gpu_of(py, device)?;
    let trace_gpu = if options.cpu {
        None
    } else {
        tracer_gpu(tracer, &gpu)
    };
    let lib_scene = scene.get().scene.clone();
    let camera = chosen.camera;
    let report = py.detach(|| -> Result<String, obscura::Error> {
        let bvh = obscura::bvh::BvhCache::new();
        let mut images = Vec::new();
        let mut gbuffer = None;
        for s in &rows {
            let mut renderer = Renderer::with_bvh_cache(
                &gpu,
                &lib_scene,
                s,
                size.width,
                size.height,
                size.guard_band,
                &bvh,
            )?;
            renderer.render(&camera, None)?;
            let json = serde_json::to_value(s.resolved())
                .map_err(|e| obscura::Error::Input(e.to_string()))?;
            images.push((s.technique, renderer.read_ao()?, json));
            gbuffer = Some(renderer.read_gbuffer()?);
        }
        let gbuffer = gbuffer.ok_or_else(|| obscura::Error::Input("no technique".into()))?;
        let depth = gbuffer.visible_depth(size.guard_band);
        let view = size.frame_view(camera, &lib_scene);
        let traced = trace(
            trace_gpu.as_ref(),
            &lib_scene,
            &|| bvh.get(&lib_scene),
            view,
            &options.settings,
            cache,
        )?;
        let reference = as_compared(traced, options.settings.model, &vao.blur, &gbuffer, &view);
        let input = ReportInput {
            scene: &lib_scene.name,
            camera: &chosen.name,
            scene_options: &lib_scene.options_description(),
            width: size.width,
            height: size.height,
            guard_band: size.guard_band,
            reference_model: options.settings.model.name(),
            spp: options.settings.reported_spp(),
            reference_radius: Some(options.settings.vao.radius),
            reference: &reference,
            depth: &depth,
            techniques: images
                .iter()
                .map(|(t, ao, settings)| TechniqueImage {
                    name: Technique::name(*t),
                    ao,
                    settings: Some(settings),
                    gpu_ms: None,
                })
                .collect(),
            halo_radius_px: 4,
            halo_relative_jump: 0.1,
            adapter: &gpu.summary.name,
            software_adapter: cpu_tracer_by_default(&gpu),
            diff_scale: None,
            temporal: None,
        };
        let report = build_report(&input).map_err(|e| obscura::Error::Input(e.to_string()))?;
        serde_json::to_string(&report).map_err(|e| obscura::Error::Input(e.to_string()))
    });
    report.map_err(from_lib)
}
