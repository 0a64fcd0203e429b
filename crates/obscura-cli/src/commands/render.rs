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
    #[arg(long, value_parser = parse_technique, default_value = "vao", help = crate::args::technique_help())]
    technique: Technique,
    #[command(flatten)]
    ao: AoArgs,
    /// Output image: .png (8-bit) or .exr (float).
    #[arg(long)]
    out: PathBuf,
    /// Also write AO × base colour next to it (NAME.composite.png/.exr).
    #[arg(long)]
    composite: bool,
    /// Also write a lit composite next to it (NAME.lit.png/.exr): base colour × (sky light × AO +
    /// sun), background transparent, so AO reads on any model.
    #[arg(long)]
    lit: bool,
    /// Keep the background of a PNG output opaque (AO 1, white); by default it is transparent
    /// (alpha 0), so an unoccluded surface and empty space look different.
    #[arg(long)]
    opaque_background: bool,
    /// Write the technique's intermediate images and statistics into this folder. Two-phase
    /// techniques: the per-pixel count of flagged samples (samples.png). Stochastic-depth
    /// techniques: one stochastic depth layer (sd_layer.png), the stored samples per pixel
    /// (sd_counts.png) and, two-phase, the SD-request mask (sd_request.png); the ray-traced map
    /// also its hits per ray (sd_hits.png). Always stats.json.
    #[arg(long, help = debug_out_help())]
    debug_out: Option<PathBuf>,
    /// Frames rendered from the same camera, the last one written: with --temporal the image
    /// after that many frames of accumulation (each frame turns the estimators' pattern; the
    /// hemisphere rows draw new rays), with --ray-budget / --time-budget the budget's frames.
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=MAX_FRAMES))]
    frames: u32,
}

/// `--frames` at most: still frames converge long before (temporal accumulation keeps 255).
const MAX_FRAMES: i64 = 4096;

pub fn run(options: &obscura::GpuOptions, args: &RenderArgs) -> Result<()> {
    // Everything the user typed is checked before the (slow) scene load and GPU work.
    output::check_writable(&args.out)?;
    let settings = args.ao.settings(args.technique)?;
    if let Some(dir) = &args.debug_out {
        if !args.technique.row().has_debug_output() && !settings.temporal.enabled {
            anyhow::bail!(
                "--technique {} has no --debug-out images: use it with --technique {} (or \
                 with --temporal, for the history's images)",
                args.technique,
                technique_list(&debug_techniques())
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
    for _ in 0..args.frames {
        renderer.render_frame(&camera)?;
    }
    let ao = renderer.read_ao()?;
    crate::args::warn_stack_overflows(&renderer)?;
    let gbuffer = renderer.read_gbuffer()?;
    let covered: Vec<bool> = gbuffer
        .visible_depth(guard_band)
        .iter()
        .map(|&d| d > 0.0)
        .collect();
    if args.opaque_background {
        output::write_ao(&args.out, width, height, &ao)?;
    } else {
        output::write_ao_covered(&args.out, width, height, &ao, &covered)?;
    }
    let mut written = vec![args.out.clone()];
    if let Some(bent) = renderer.read_bent_normals()? {
        let path = output::bent_normals_path(&args.out);
        output::write_bent_normals(&path, width, height, &bent)?;
        written.push(path);
    }
    if let Some(dir) = &args.debug_out {
        let row = args.technique.row();
        // The maps and masks are at the resolution the technique ran at (half with
        // `--resolution half`).
        let work = renderer
            .ambient_occlusion()
            .map(|ao| ao.work_screen())
            .ok_or_else(|| anyhow::anyhow!("nothing rendered"))?;
        let (w, h, g) = (work.width, work.height, work.guard_band);
        if row.source.maps_hidden_depth() {
            write_sd_debug(dir, &renderer, &settings, (w, h), g)?
        } else if row.schedule.two_phase() {
            let samples = settings.samples_per_pixel();
            write_debug(dir, &renderer, w, h, samples)?
        }
        if settings.temporal.enabled {
            write_history_debug(dir, &renderer, &settings, (w, h), args.frames)?;
        }
        if let Some((name, what)) = row.estimator_debug_image() {
            let image = renderer
                .read_estimator_debug()?
                .ok_or_else(|| anyhow::anyhow!("{} has no debug image", args.technique))?;
            let path = dir.join(name);
            output::write_ao(&path, width, height, &image)?;
            eprintln!("debug: {}: {what}", path.display());
        }
    }
    if args.composite || args.lit {
        let albedo = renderer.read_albedo()?;
        if args.composite {
            let path = output::composite_path(&args.out);
            output::write_composite(&path, width, height, &ao, &albedo)?;
            written.push(path);
        }
        if args.lit {
            // View-space G-buffer normals of the visible pixels, to world space.
            let to_world = renderer
                .view()
                .map(|v| v.view_matrix().inverse())
                .unwrap_or_default();
            let fw = gbuffer.width as usize;
            let normals: Vec<glam::Vec3> = (0..height as usize)
                .flat_map(|y| (0..width as usize).map(move |x| (x, y)))
                .map(|(x, y)| {
                    let i = (y + guard_band as usize) * fw + x + guard_band as usize;
                    if gbuffer.depth[i] > 0.0 {
                        to_world
                            .transform_vector3(gbuffer.normals[i])
                            .normalize_or_zero()
                    } else {
                        glam::Vec3::ZERO
                    }
                })
                .collect();
            let path = output::lit_path(&args.out);
            output::write_lit_composite(&path, width, height, &ao, &albedo, &normals)?;
            written.push(path);
        }
    }
    let names: Vec<String> = written.iter().map(|p| p.display().to_string()).collect();
    eprintln!("wrote {}", names.join(", "));
    Ok(())
}

/// The techniques `--debug-out` has images for (from the technique table).
fn debug_techniques() -> Vec<Technique> {
    Technique::all()
        .filter(|t| t.row().has_debug_output())
        .collect()
}

fn debug_out_help() -> String {
    format!(
        "Write the technique's intermediate images and statistics into this folder ({}).",
        technique_list(&debug_techniques())
    )
}

/// "a, b, c or d".
fn technique_list(techniques: &[Technique]) -> String {
    let names: Vec<&str> = techniques.iter().map(|t| t.name()).collect();
    match names.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{} or {last}", rest.join(", ")),
        _ => names.join(""),
    }
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
    let (flagged_pixels, rays) = flagged(&masks);
    let stats = serde_json::json!({
        "pixels": masks.len(),
        "flagged_pixels": flagged_pixels,
        "flagged_fraction": flagged_pixels as f64 / masks.len().max(1) as f64,
        "rays_traced": rays,
        "stack_overflows": renderer.read_stack_overflows()?,
    });
    write_json(&dir.join("stats.json"), &stats)?;
    eprintln!(
        "debug: {flagged_pixels} of {} pixels ({:.1} %) flagged, {rays} rays traced; wrote {}",
        masks.len(),
        100.0 * flagged_pixels as f64 / masks.len().max(1) as f64,
        dir.display()
    );
    Ok(())
}

/// Temporal accumulation's state after the last frame, at the working resolution:
/// - `history.png`: frames in each pixel's history / `temporal.frames` (black: none);
/// - hemisphere rows: `variance.png`, the standard error of each pixel's accumulated AO as the
///   ray budget and the denoiser estimate it (√(a'(1 − a')/(m + 2)) for m = frames × rays,
///   a' = (a m + 1)/(m + 2)), × 2 so that one ray's largest (0.5) is white;
/// - under a ray budget: `rays.png`, the rays each pixel cast the last frame / `hemisphere.rays`;
/// - `history.json`: the frames rendered, the mean history, and the budget's rays granted and
///   wanted.
fn write_history_debug(
    dir: &std::path::Path,
    renderer: &Renderer,
    settings: &obscura::AoSettings,
    (width, height): (u32, u32),
    frames_rendered: u32,
) -> Result<()> {
    let ao = renderer
        .ambient_occlusion()
        .ok_or_else(|| anyhow::anyhow!("nothing rendered"))?;
    let history = ao
        .read_temporal_history()?
        .ok_or_else(|| anyhow::anyhow!("no temporal history"))?;
    let most = settings.temporal.frames.max(1) as f32;
    let frames: Vec<f32> = history.iter().map(|t| t.frames as f32 / most).collect();
    output::write_ao(&dir.join("history.png"), width, height, &frames)?;
    let surface = history.iter().filter(|t| t.depth > 1e-6).count().max(1);
    let mean_frames = history.iter().map(|t| f64::from(t.frames)).sum::<f64>() / surface as f64;
    let mut stats = serde_json::json!({
        "frames_rendered": frames_rendered,
        "mean_history_frames": mean_frames,
    });
    let hemisphere = settings.technique.estimator() == obscura::technique::Estimator::Hemisphere;
    if hemisphere {
        let rays = f64::from(settings.hemisphere.rays);
        let error: Vec<f32> = history
            .iter()
            .map(|t| match t.frames {
                0 => 0.0,
                n => 2.0 * visibility_std(f64::from(t.ao), f64::from(n) * rays) as f32,
            })
            .collect();
        output::write_ao(&dir.join("variance.png"), width, height, &error)?;
    }
    if let Ok(report) = ao.read_ray_budget() {
        let grant = ao.read_ray_grant()?;
        let n = settings.hemisphere.rays.max(1) as f32;
        let image: Vec<f32> = grant.iter().map(|&g| g as f32 / n).collect();
        output::write_ao(&dir.join("rays.png"), width, height, &image)?;
        stats["ray_budget"] = serde_json::json!(report.budget);
        stats["rays_granted"] = serde_json::json!(report.granted);
        stats["rays_wanted"] = serde_json::json!(report.wanted);
        eprintln!(
            "debug: ray budget {}: {} rays granted of {} wanted",
            report.budget, report.granted, report.wanted
        );
    }
    write_json(&dir.join("history.json"), &stats)?;
    eprintln!(
        "debug: mean history {mean_frames:.1} frames; wrote history.png{} in {}",
        if hemisphere { ", variance.png" } else { "" },
        dir.display()
    );
    Ok(())
}

/// The standard error of a mean of `rays` rays of visibility with mean `a`, with one free and
/// one blocked ray of prior (shaders/common/visibility_variance.wgsl, mirrored here).
fn visibility_std(a: f64, rays: f64) -> f64 {
    let prior = (a * rays + 1.0) / (rays + 2.0);
    (prior * (1.0 - prior) / (rays + 2.0)).sqrt()
}

/// Counts of a phase-1 sample bitmask image: (pixels with any flagged sample, flagged samples).
fn flagged(masks: &[u32]) -> (usize, u64) {
    (
        masks.iter().filter(|&&m| m != 0).count(),
        masks.iter().map(|m| u64::from(m.count_ones())).sum(),
    )
}

fn write_json(path: &std::path::Path, value: &serde_json::Value) -> Result<()> {
    let text = serde_json::to_string_pretty(value)?;
    output::write_atomically(path, |tmp| {
        std::fs::write(tmp, &text).map_err(|e| e.to_string())
    })?;
    Ok(())
}

/// An SD-request mask as a grey image: white where requested.
fn request_mask(requests: &[u32]) -> Vec<f32> {
    requests
        .iter()
        .map(|&q| f32::from(u8::from(q != 0)))
        .collect()
}

/// `sd-vao`, `sd-svao`: the stochastic depth map of the frame, over the whole framebuffer (guard
/// band included, so these images are `width + 2·guard_band` wide):
/// - `sd_layer.png`: sample 0 of map 0 as a depth image (seed 000 Fig. 2). Empty samples are black;
///   stored depths d map linearly to grey 1 − 0.75·(d − d_min)/(d_max − d_min), d_min/d_max the
///   nearest/farthest stored depth over all samples of the map, so near is white and the farthest
///   stored depth (grey 0.25) stays distinct from empty;
/// - `sd_counts.png`: stored samples per pixel / S (black: none, white: all S);
/// - two-phase only: `sd_request.png` (white = phase 1 requested the map there) and the phase-1
///   flagged samples per visible pixel `samples.png` (count / VAO samples, as for rt-svao);
/// - `stats.json`: settings, layout and the fractions;
/// - the ray-traced map with ray intervals (two-phase `ray-sd-*`): `sd_intervals.png`, each
///   framebuffer pixel's interval length over the frame's longest (seed 002 Fig. 12), and in
///   `stats.json` `interval_pixels`, `interval_mean_length`, `interval_longest`;
/// - the ray-traced map (`ray-sd-*`, one layer per reservoir slot): also `sd_hits.png`, the hits
///   each texel's ray handled / MAX_COUNT at the map's resolution (seed 002's "hits per ray"),
///   and their mean over the traced texels in `stats.json`;
/// - two-phase, the ray-traced map or the raster map with its own band
///   (`--sd-map-guard-band`): `sd_request_map.png`, the requested texels over the whole map, its
///   own guard band included (seed 002 Fig. 13c), and `guard_band_texels_requested` in
///   `stats.json` (`requested_pixels` counts framebuffer pixels only).
fn write_sd_debug(
    dir: &std::path::Path,
    renderer: &Renderer,
    settings: &obscura::AoSettings,
    (width, height): (u32, u32),
    guard_band: u32,
) -> Result<()> {
    let sd = settings.stochastic_depth;
    let layers = renderer
        .read_stochastic_depth()?
        .ok_or_else(|| anyhow::anyhow!("this technique has no stochastic depth map"))?;
    let layout = renderer
        .ambient_occlusion()
        .and_then(|ao| ao.stochastic_depth_layout())
        .ok_or_else(|| anyhow::anyhow!("this technique has no stochastic depth map"))?;
    let (fw, fh) = (width + 2 * guard_band, height + 2 * guard_band);
    let texels = (fw * fh) as usize;
    if layers.len() != layout.samples() as usize || layers.iter().any(|l| l.len() != texels) {
        anyhow::bail!(
            "stochastic depth map read back as {} layers, expected {} of {fw}x{fh}",
            layers.len(),
            layout.samples()
        );
    }
    let stored = |d: f32| d > 0.0 && d.is_finite();
    let (layer, near, far) = sd_layer_grey(&layers);
    output::write_ao(&dir.join("sd_layer.png"), fw, fh, &layer)?;
    let mut counts = vec![0u32; texels];
    for l in &layers {
        for (c, &d) in counts.iter_mut().zip(l) {
            *c += u32::from(stored(d));
        }
    }
    let s = layers.len() as f32;
    let count_image: Vec<f32> = counts.iter().map(|&c| c as f32 / s).collect();
    output::write_ao(&dir.join("sd_counts.png"), fw, fh, &count_image)?;
    let stored_samples: u64 = counts.iter().map(|&c| u64::from(c)).sum();
    let all_samples = texels as u64 * layers.len() as u64;
    let stored_fraction = stored_samples as f64 / all_samples.max(1) as f64;
    // The ray-traced map (its own statistics), not the raster one.
    let ray = settings.technique.source().maps_hidden_depth()
        && !settings.technique.needs().stochastic_depth_map;
    let mut stats = if ray {
        let r = settings.ray_sd;
        serde_json::json!({
            "technique": settings.technique.name(),
            "ray_sd": serde_json::to_value(r)?,
        })
    } else {
        serde_json::json!({
            "technique": settings.technique.name(),
            "sd_samples": sd.samples,
            // Through its shortest decimal form: 0.2, not 0.20000000298023224.
            "sd_alpha": sd.alpha().to_string().parse::<f64>().ok(),
            "sd_seed": sd.seed,
        })
    };
    let common = serde_json::json!({
        "layout": { "maps": layout.maps, "samples_per_map": layout.samples_per_map },
        "framebuffer_width": fw,
        "framebuffer_height": fh,
        "guard_band": guard_band,
        "stored_samples": stored_samples,
        "stored_fraction": stored_fraction,
        "stored_pixels": counts.iter().filter(|&&c| c > 0).count(),
        "stored_depth_range": [
            if stored_samples > 0 { near } else { 0.0 },
            far,
        ],
    });
    if let (Some(stats), serde_json::Value::Object(common)) = (stats.as_object_mut(), common) {
        stats.extend(common);
    }
    let maps = match layout.maps {
        1 => "one map".to_string(),
        n => format!("{n} maps of {}", layout.samples_per_map),
    };
    let mut summary = if ray {
        format!(
            "debug: N = {} slots per texel, {:.2} % of all slots filled",
            layout.samples(),
            100.0 * stored_fraction
        )
    } else {
        format!(
            "debug: S = {} ({maps}), {:.2} % of all samples stored",
            layout.samples(),
            100.0 * stored_fraction
        )
    };
    if let Some(hits) = renderer.read_ray_sd_hits()? {
        let r = settings.ray_sd;
        let extent = renderer
            .ray_sd_map_size()?
            .ok_or_else(|| anyhow::anyhow!("a ray-traced map without a size"))?;
        let (mw, mh, g) = (extent.width, extent.height, extent.guard_texels);
        let image: Vec<f32> = hits
            .iter()
            .map(|&h| h as f32 / r.max_count as f32)
            .collect();
        output::write_ao(&dir.join("sd_hits.png"), mw, mh, &image)?;
        let traced: Vec<u32> = hits.iter().copied().filter(|&h| h > 0).collect();
        let mean = traced.iter().map(|&h| f64::from(h)).sum::<f64>() / traced.len().max(1) as f64;
        if let Some(stats) = stats.as_object_mut() {
            stats.insert("map_width".into(), mw.into());
            stats.insert("map_height".into(), mh.into());
            stats.insert("map_guard_band_texels".into(), g.into());
            stats.insert("hits_per_ray_mean".into(), mean.into());
        }
        summary += &format!(", {mean:.2} hits per ray (rays that met one)");
    }
    // The ray-traced map, or the raster map with its own band: the requested texels over the
    // whole map, its band included (seed 002 Fig. 13c; the band's requests come from samples off
    // the framebuffer).
    let ray_map = renderer.ray_sd_map_size()?.is_some();
    let request_map = renderer
        .sd_request_map_size()?
        .filter(|m| ray_map || m.guard_texels > 0);
    if let (Some(map), Some(requests)) = (request_map, renderer.read_sd_request_texels()?) {
        let (mw, mh, g) = (map.width, map.height, map.guard_texels as usize);
        output::write_ao(
            &dir.join("sd_request_map.png"),
            mw,
            mh,
            &request_mask(&requests),
        )?;
        let in_band = requests
            .iter()
            .enumerate()
            .filter(|&(i, &q)| {
                let (x, y) = (i % mw as usize, i / mw as usize);
                let inner = |v: usize, n: u32| v >= g && v < n as usize - g;
                q != 0 && !(inner(x, mw) && inner(y, mh))
            })
            .count();
        if let Some(stats) = stats.as_object_mut() {
            stats.insert("guard_band_texels_requested".into(), in_band.into());
        }
        summary += &format!(", {in_band} texels of the map's own band requested");
    }
    if let Some(intervals) = renderer.read_sd_intervals()? {
        // Seed 002 Fig. 12: how long a stretch of each pixel's ray the map must trace, as a
        // fraction of the longest in the frame (black: no sample asked).
        let lengths: Vec<f32> = intervals
            .iter()
            .map(|i| i.map_or(0.0, |[near, far]| (far - near).max(0.0)))
            .collect();
        let longest = lengths.iter().copied().fold(0.0f32, f32::max);
        let image: Vec<f32> = lengths
            .iter()
            .map(|&l| if longest > 0.0 { l / longest } else { 0.0 })
            .collect();
        output::write_ao(&dir.join("sd_intervals.png"), fw, fh, &image)?;
        let asked: Vec<f32> = intervals
            .iter()
            .zip(&lengths)
            .filter_map(|(i, &l)| i.map(|_| l))
            .collect();
        let mean = asked.iter().map(|&l| f64::from(l)).sum::<f64>() / asked.len().max(1) as f64;
        if let Some(stats) = stats.as_object_mut() {
            stats.insert("interval_pixels".into(), asked.len().into());
            stats.insert("interval_mean_length".into(), mean.into());
            stats.insert("interval_longest".into(), f64::from(longest).into());
        }
        summary += &format!(
            ", ray intervals at {} pixels, {mean:.3} world units long on average",
            asked.len()
        );
    }
    if let Some(requests) = renderer.read_sd_requests()? {
        output::write_ao(
            &dir.join("sd_request.png"),
            fw,
            fh,
            &request_mask(&requests),
        )?;
        let requested = requests.iter().filter(|&&r| r != 0).count();
        let requested_fraction = requested as f64 / requests.len().max(1) as f64;
        let masks = renderer
            .read_sample_masks()?
            .ok_or_else(|| anyhow::anyhow!("the two-phase schedule returned no sample masks"))?;
        let per_pixel = settings.samples_per_pixel() as f32;
        let flagged_image: Vec<f32> = masks
            .iter()
            .map(|m| m.count_ones() as f32 / per_pixel)
            .collect();
        output::write_ao(&dir.join("samples.png"), width, height, &flagged_image)?;
        let (flagged_pixels, samples_flagged) = flagged(&masks);
        let extra = serde_json::json!({
            "requested_pixels": requested,
            "requested_fraction": requested_fraction,
            "pixels": masks.len(),
            "flagged_pixels": flagged_pixels,
            "flagged_fraction": flagged_pixels as f64 / masks.len().max(1) as f64,
            "samples_flagged": samples_flagged,
        });
        if let (Some(stats), serde_json::Value::Object(extra)) = (stats.as_object_mut(), extra) {
            stats.extend(extra);
        }
        summary += &format!(
            ", {requested} of {} framebuffer pixels ({:.1} %) requested the map, \
             {flagged_pixels} visible pixels flagged",
            requests.len(),
            100.0 * requested_fraction
        );
    }
    write_json(&dir.join("stats.json"), &stats)?;
    eprintln!("{summary}; wrote {}", dir.display());
    Ok(())
}

/// `sd_layer.png` (and the viewer's sd-layer view): sample 0 of map 0 as grey, the nearest depth
/// stored in any layer white, the farthest 0.25, linear in between, empty texels black; with that
/// nearest and farthest depth (∞ and 0 when nothing is stored).
pub(crate) fn sd_layer_grey(layers: &[Vec<f32>]) -> (Vec<f32>, f32, f32) {
    let stored = |d: f32| d > 0.0 && d.is_finite();
    let (near, far) = layers
        .iter()
        .flatten()
        .copied()
        .filter(|&d| stored(d))
        .fold((f32::INFINITY, 0.0f32), |(lo, hi), d| {
            (lo.min(d), hi.max(d))
        });
    let span = (far - near).max(f32::MIN_POSITIVE);
    let grey = layers.first().map_or_else(Vec::new, |layer| {
        layer
            .iter()
            .map(|&d| {
                if stored(d) {
                    1.0 - 0.75 * (d - near) / span
                } else {
                    0.0
                }
            })
            .collect()
    });
    (grey, near, far)
}
