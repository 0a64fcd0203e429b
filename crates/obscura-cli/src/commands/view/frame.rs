//! One viewer frame without any window: one or two `Renderer`s (split screen), the display pass,
//! the debug views and the per-pass GPU timings. The window (`app.rs`) and `--offscreen-frames`
//! both drive this, so the render path timed offscreen is the one the window shows.

use super::display::{Display, DisplayInputs, GpuMode};
use anyhow::{anyhow, Result};
use obscura::bvh::BvhCache;
use obscura::scene::{Camera, Scene};
use obscura::{AoSettings, Gpu, PassProfiler, Renderer, Technique};
use std::collections::BTreeMap;
use std::sync::Arc;

/// What the central image shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DebugView {
    Ao,
    Composite,
    Normals,
    Depth,
    /// Sample 0 of the stochastic depth map (read back each frame).
    SdLayer,
    /// Two-phase rows: the share of each pixel's samples phase 1 flagged (read back each frame).
    SampleMasks,
    /// Stenciled stochastic-depth rows: where phase 1 asked for the map (read back each frame).
    RequestedPixels,
    /// The ray-traced ground truth of the view it was computed for.
    Reference,
}

impl DebugView {
    pub const ALL: [DebugView; 8] = [
        DebugView::Ao,
        DebugView::Composite,
        DebugView::Normals,
        DebugView::Depth,
        DebugView::SdLayer,
        DebugView::SampleMasks,
        DebugView::RequestedPixels,
        DebugView::Reference,
    ];

    pub fn name(self) -> &'static str {
        match self {
            DebugView::Ao => "ao",
            DebugView::Composite => "composite",
            DebugView::Normals => "normals",
            DebugView::Depth => "depth",
            DebugView::SdLayer => "sd-layer",
            DebugView::SampleMasks => "sample-masks",
            DebugView::RequestedPixels => "requested-pixels",
            DebugView::Reference => "reference",
        }
    }

    pub fn parse(s: &str) -> Result<DebugView, String> {
        DebugView::ALL
            .into_iter()
            .find(|v| v.name() == s)
            .ok_or_else(|| {
                let names: Vec<&str> = DebugView::ALL.iter().map(|v| v.name()).collect();
                format!("unknown view '{s}': use one of {}", names.join(", "))
            })
    }

    /// Whether `technique` has this view (the reference always: it does not depend on it).
    pub fn available(self, technique: Technique) -> bool {
        let row = technique.row();
        let sd = row.source.maps_hidden_depth();
        match self {
            DebugView::SdLayer => sd,
            DebugView::SampleMasks => row.schedule.two_phase(),
            DebugView::RequestedPixels => sd && row.schedule.two_phase(),
            _ => true,
        }
    }

    fn gpu_mode(self) -> Option<GpuMode> {
        match self {
            DebugView::Ao => Some(GpuMode::Ao),
            DebugView::Composite => Some(GpuMode::Composite),
            DebugView::Normals => Some(GpuMode::Normals),
            DebugView::Depth => Some(GpuMode::Depth),
            _ => None,
        }
    }
}

/// One technique's renderer, or why there is none.
pub struct Pane {
    pub settings: AoSettings,
    pub renderer: Option<Renderer>,
    pub error: Option<String>,
}

/// GPU milliseconds per pass of the last profiled frame, per pane (A, then B).
pub type PaneTimings = Vec<BTreeMap<String, f64>>;

pub struct Frame {
    pub gpu: Gpu,
    pub scene: Arc<Scene>,
    /// The scene's BVH, built once for every pane, every settings change and the reference.
    pub bvh: BvhCache,
    pub width: u32,
    pub height: u32,
    pub guard_band: u32,
    pub a: Pane,
    pub b: Option<Pane>,
    pub display: Display,
    /// Last frame's camera.
    pub camera: Camera,
    /// `None`: the adapter has no timestamp queries.
    pub timings: Option<PaneTimings>,
    /// Per pane (A, then B), under a ray budget: what a recent frame granted (refreshed one frame
    /// in 30).
    pub budgets: Vec<Option<obscura::RayBudgetReport>>,
    /// Why the last debug view could not be shown (it shows the AO instead).
    pub view_note: Option<String>,
}

/// Make the renderer of `settings`; an error is kept for the UI, not fatal.
fn make_pane(
    gpu: &Gpu,
    scene: &Scene,
    bvh: &BvhCache,
    settings: AoSettings,
    (width, height, guard_band): (u32, u32, u32),
) -> Pane {
    match Renderer::with_bvh_cache(gpu, scene, &settings, width, height, guard_band, bvh) {
        Ok(r) => Pane {
            settings,
            renderer: Some(r),
            error: None,
        },
        Err(e) => Pane {
            settings,
            renderer: None,
            error: Some(format!("{:#}", crate::args::for_user(e.into()))),
        },
    }
}

impl Frame {
    pub fn new(
        gpu: Gpu,
        scene: Arc<Scene>,
        settings: AoSettings,
        split: Option<Technique>,
        (width, height, guard_band): (u32, u32, u32),
        camera: Camera,
    ) -> Self {
        let size = (width, height, guard_band);
        let bvh = BvhCache::new();
        let a = make_pane(&gpu, &scene, &bvh, settings, size);
        let b = split.map(|t| make_pane(&gpu, &scene, &bvh, with_technique(&settings, t), size));
        let display = Display::new(&gpu, width, height);
        let timings = gpu.summary.timestamp_queries.then(Vec::new);
        Self {
            gpu,
            scene,
            bvh,
            width,
            height,
            guard_band,
            a,
            b,
            display,
            camera,
            timings,
            budgets: Vec::new(),
            view_note: None,
        }
    }

    /// Rebuild what changed: the size and guard band (both panes), the settings of A, or the split
    /// (B takes A's settings with its own technique). Returns true if the display texture was
    /// reallocated.
    pub fn configure(
        &mut self,
        settings: AoSettings,
        split: Option<Technique>,
        (width, height, guard_band): (u32, u32, u32),
    ) -> bool {
        let size_changed =
            (width, height, guard_band) != (self.width, self.height, self.guard_band);
        let size = (width, height, guard_band);
        if size_changed || settings != self.a.settings {
            self.a = make_pane(&self.gpu, &self.scene, &self.bvh, settings, size);
        }
        let b_settings = split.map(|t| with_technique(&settings, t));
        match (b_settings, &self.b) {
            (None, _) => self.b = None,
            (Some(s), Some(b)) if !size_changed && b.settings == s => {}
            (Some(s), _) => {
                self.b = Some(make_pane(&self.gpu, &self.scene, &self.bvh, s, size));
            }
        }
        (self.width, self.height, self.guard_band) = size;
        self.display.resize(&self.gpu, width, height)
    }

    /// Render one frame from `camera` and draw `view` into the display image. `profile`: time
    /// every pass of this frame (waits for the GPU to read the timestamps back).
    pub fn render(
        &mut self,
        camera: &Camera,
        view: DebugView,
        split_x: Option<u32>,
        reference: Option<&[f32]>,
        profile: bool,
    ) -> Result<()> {
        self.camera = *camera;
        // The ray budget's panel refreshes on the frames asked to be timed, timestamps or not.
        let refresh = profile;
        let profile = profile && self.timings.is_some();
        let mut timings = Vec::new();
        let mut budgets = Vec::new();
        for pane in std::iter::once(&mut self.a).chain(self.b.as_mut()) {
            let Some(renderer) = pane.renderer.as_mut() else {
                continue;
            };
            // A time budget follows every frame's timings.
            let follow = renderer.settings().hemisphere.time_budget > 0.0
                && renderer.settings().ray_budget_active();
            let rendered = if profile && !follow {
                let mut profiler = PassProfiler::new(&self.gpu, 1)?;
                renderer
                    .render(camera, Some(&mut profiler))
                    .map_err(anyhow::Error::from)
                    .and_then(|()| Ok(Some(profiler.read(&self.gpu)?.pop().unwrap_or_default())))
            } else {
                renderer.render_frame(camera).map_err(anyhow::Error::from)
            };
            match rendered {
                Ok(frame_timings) => {
                    if profile {
                        timings.push(frame_timings.unwrap_or_default());
                    }
                }
                Err(e) => {
                    // Keep the window alive: say why in the panel, show nothing for this pane.
                    pane.error = Some(format!("{:#}", crate::args::for_user(e)));
                    pane.renderer = None;
                    continue;
                }
            }
            // Read back (a wait for the GPU) only one frame in 30, as the timings are.
            if refresh {
                let ao = renderer.ambient_occlusion();
                budgets.push(ao.and_then(|ao| ao.read_ray_budget().ok()));
            }
        }
        if refresh {
            self.budgets = budgets;
        }
        if profile {
            self.timings = Some(timings);
        }
        self.view_note = None;
        let split = self.b.is_some().then_some(split_x).flatten();
        let mut view = view;
        if view != DebugView::Reference && view.gpu_mode().is_none() {
            match self.cpu_view(view, split) {
                Ok(Some(grey)) => {
                    self.display.write_grey(&self.gpu, &grey);
                    return Ok(());
                }
                Ok(None) => {
                    self.view_note = Some(format!(
                        "{} has no {} view: showing the AO",
                        self.a.settings.technique,
                        view.name()
                    ));
                    view = DebugView::Ao;
                }
                Err(e) => return Err(e),
            }
        }
        if view == DebugView::Reference {
            match reference {
                Some(image) if image.len() == (self.width * self.height) as usize => {
                    self.display.write_grey(&self.gpu, image);
                    return Ok(());
                }
                _ => {
                    self.view_note =
                        Some("no reference for this view yet: press R (or the button)".into());
                    view = DebugView::Ao;
                }
            }
        }
        self.encode_gpu_view(view.gpu_mode().unwrap_or(GpuMode::Ao), split)
    }

    /// The display pass over the renderers' textures.
    fn encode_gpu_view(&mut self, mode: GpuMode, split: Option<u32>) -> Result<()> {
        let Some(a) = self.a.renderer.as_ref() else {
            self.display.write_grey(
                &self.gpu,
                &vec![f32::NAN; (self.width * self.height) as usize],
            );
            return Ok(());
        };
        let ao_a = a
            .ambient_occlusion()
            .ok_or_else(|| anyhow!("nothing rendered"))?
            .output();
        let ao_b = self
            .b
            .as_ref()
            .and_then(|b| b.renderer.as_ref())
            .and_then(|r| r.ambient_occlusion())
            .map_or(ao_a, |ao| ao.output());
        let (depth, normals) = a.gbuffer_textures();
        let mut encoder = self.gpu.device.create_command_encoder(&Default::default());
        let albedo = if mode == GpuMode::Composite {
            a.encode_albedo(&mut encoder)
        } else {
            depth
        };
        let depth_max = depth_range(&self.scene, &self.camera);
        self.display.encode(
            &self.gpu,
            &mut encoder,
            &DisplayInputs {
                mode,
                ao_a,
                ao_b,
                split_x: split,
                depth,
                normals,
                albedo,
                guard_band: a.guard_band(),
                depth_max,
            },
        );
        self.gpu.queue.submit([encoder.finish()]);
        Ok(())
    }

    /// The CPU debug views as a visible-size grey image (NaN = background), left of the split
    /// from A, right of it from B; None when the technique has no such image.
    fn cpu_view(&self, view: DebugView, split: Option<u32>) -> Result<Option<Vec<f32>>> {
        let Some(a) = self.a.renderer.as_ref() else {
            return Ok(None);
        };
        let Some(left) = cpu_image(a, view, self.width, self.height)? else {
            return Ok(None);
        };
        // B without this image: its half shows the background.
        let right = match (split, self.b.as_ref().and_then(|b| b.renderer.as_ref())) {
            (Some(x), Some(b)) => Some((
                x,
                cpu_image(b, view, self.width, self.height)?
                    .unwrap_or_else(|| vec![f32::NAN; left.len()]),
            )),
            _ => None,
        };
        Ok(Some(match right {
            Some((x, right)) => left
                .iter()
                .zip(&right)
                .enumerate()
                .map(|(i, (&l, &r))| {
                    let col = (i as u32) % self.width;
                    if col == x || col + 1 == x {
                        1.0
                    } else if col < x {
                        l
                    } else {
                        r
                    }
                })
                .collect(),
            None => left,
        }))
    }

    /// The display image as RGBA8 (waits for the GPU).
    pub fn read_rgba(&self) -> Result<Vec<u8>> {
        self.display.read_rgba(&self.gpu)
    }
}

/// A's settings with B's technique, for the split screen.
pub fn with_technique(settings: &AoSettings, technique: Technique) -> AoSettings {
    AoSettings {
        technique,
        ..*settings
    }
}

/// The linear depth the depth view maps to black: the farthest corner of the scene's bounds.
fn depth_range(scene: &Scene, camera: &Camera) -> f32 {
    let b = scene.bounds();
    let mut far: f32 = 0.0;
    for i in 0..8 {
        let corner = glam::Vec3::new(
            if i & 1 == 0 { b.min.x } else { b.max.x },
            if i & 2 == 0 { b.min.y } else { b.max.y },
            if i & 4 == 0 { b.min.z } else { b.max.z },
        );
        far = far.max((corner - camera.eye).dot(camera.forward()));
    }
    far.max(1e-3)
}

/// One renderer's CPU debug image at the visible size (nearest-neighbour from the size the
/// technique ran at, guard band cropped).
fn cpu_image(r: &Renderer, view: DebugView, width: u32, height: u32) -> Result<Option<Vec<f32>>> {
    let ao = r
        .ambient_occlusion()
        .ok_or_else(|| anyhow!("nothing rendered"))?;
    let work = ao.work_screen();
    let (ww, wh, wg) = (work.width, work.height, work.guard_band);
    let fw = ww + 2 * wg;
    // (source image, its width, its guard band) on the work screen.
    let (image, src_w, guard): (Vec<f32>, u32, u32) = match view {
        DebugView::SdLayer => {
            let Some(layers) = r.read_stochastic_depth()? else {
                return Ok(None);
            };
            if layers.is_empty() {
                return Ok(None);
            }
            // As `render --debug-out`'s sd_layer.png.
            let (grey, _, _) = crate::commands::render::sd_layer_grey(&layers);
            (grey, fw, wg)
        }
        DebugView::SampleMasks => {
            let Some(masks) = r.read_sample_masks()? else {
                return Ok(None);
            };
            let settings = r.settings();
            let per_pixel = settings.samples_per_pixel().max(1) as f32;
            let grey = masks
                .iter()
                .map(|m| m.count_ones() as f32 / per_pixel)
                .collect();
            (grey, ww, 0)
        }
        DebugView::RequestedPixels => {
            let Some(requests) = r.read_sd_requests()? else {
                return Ok(None);
            };
            let grey = requests
                .iter()
                .map(|&q| f32::from(u8::from(q != 0)))
                .collect();
            (grey, fw, wg)
        }
        _ => return Ok(None),
    };
    let src_h = (image.len() as u32) / src_w.max(1);
    if src_w == 0 || src_h == 0 {
        return Ok(None);
    }
    let mut out = Vec::with_capacity((width * height) as usize);
    for y in 0..height {
        let sy = (y as u64 * wh as u64 / height as u64) as u32 + guard;
        for x in 0..width {
            let sx = (x as u64 * ww as u64 / width as u64) as u32 + guard;
            let i = (sy.min(src_h - 1) * src_w + sx.min(src_w - 1)) as usize;
            out.push(image[i]);
        }
    }
    Ok(Some(out))
}
