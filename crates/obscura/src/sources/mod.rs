//! Hidden-depth sources: what answers "what lies behind the first surface here" (the second axis
//! of the technique table). In WGSL a source is one file of `shaders/sources/` implementing the
//! source contract (`source_lookup`, `source_resolve`, `source_request`; docs/ARCHITECTURE.md) for
//! any estimator, except column rays, which reads VAO's columns. Here a source makes what it binds
//! in group 2 and whatever it renders before the AO pass reads it (the stochastic depth map), and
//! owns the data its debug read-backs return.
//!
//! Bound in group 2 twice over: the *resolve* layout (single pass, two-phase phase 2: what
//! `source_resolve` reads) and the *request* layout (two-phase phase 1: what `source_request`
//! writes; only the stochastic depth map's request mask so far).

pub mod column_rays;
pub mod depth_pyramid;
pub mod ray_stochastic_depth;
pub mod stochastic_depth;

use crate::bindings::{self, entry, SOURCE_SD_INTERVAL, SOURCE_SD_REQUEST, SOURCE_SECOND_DEPTH};
use crate::bvh::gpu::GpuBvh;
use crate::error::Error;
use crate::frame::FrameInputs;
use crate::gpu::zero_fill::{zero_fill_size, ZeroFill};
use crate::gpu::{Gpu, PassProfiler};
use crate::raster::gpu_scene::GpuScene;
use crate::settings::AoSettings;
use crate::shaders;
use crate::technique::{Schedule, Source};
use crate::view::{FrameView, ScreenGeometry};
use column_rays::ColumnRays;
use depth_pyramid::DepthPyramid;
use ray_stochastic_depth::{RayMapLayout, RayStochasticDepthMap};
use stochastic_depth::{SdLayout, StochasticDepthMap};

/// Which of the source's two group-2 layouts a pipeline binds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum SourceGroup {
    /// What `source_resolve` reads (single pass, phase 2).
    Resolve,
    /// What `source_request` writes (phase 1).
    Request,
}

/// The scene data the scene-dependent sources need (the technique row's [`crate::technique::Needs`]).
#[derive(Clone, Copy, Default)]
pub struct SceneResources<'a> {
    /// The scene's triangles on the GPU (column rays, stochastic depth map).
    pub scene: Option<&'a GpuScene>,
    /// A BVH over them (column rays).
    pub bvh: Option<&'a GpuBvh>,
}

/// The source's WGSL: its helpers and its contract functions. `sd_layout`: how the stochastic
/// depth maps are laid out (the ray-traced map: one map of N samples); `ray_layout`: the
/// ray-traced map's resolution divisor and guard band, and the raster map's own guard band (its
/// divisor is 1; both ignored by the other sources); `group`: the layout the pass binds (BVH
/// rays prove rays in phase 1 only).
pub(crate) fn wgsl(
    source: Source,
    sd_layout: SdLayout,
    ray_layout: RayMapLayout,
    group: SourceGroup,
) -> String {
    match source {
        Source::FirstLayer => shaders::SOURCE_FIRST_LAYER.to_string(),
        Source::DualDepth => shaders::SOURCE_DUAL_DEPTH.to_string(),
        Source::ColumnRays => {
            let mut parts = column_rays::trace_wgsl().to_vec();
            parts.push(shaders::SOURCE_COLUMN_RAYS);
            parts.join("\n")
        }
        Source::ScreenRays => [shaders::SCREEN_RAYS_FIRST, shaders::SOURCE_SCREEN_RAYS].join("\n"),
        Source::ScreenRaysDual => {
            [shaders::SCREEN_RAYS_DUAL, shaders::SOURCE_SCREEN_RAYS].join("\n")
        }
        Source::BvhRays => column_rays::bvh_rays_wgsl(group == SourceGroup::Request).join("\n"),
        Source::StochasticDepth => [
            &stochastic_depth::bindings_wgsl(sd_layout, ray_layout.guard),
            shaders::STOCHASTIC_DEPTH_SAMPLES,
            shaders::SOURCE_STOCHASTIC_DEPTH,
            shaders::STOCHASTIC_DEPTH_REQUEST,
        ]
        .join("\n"),
        Source::RayStochasticDepth => [
            &ray_stochastic_depth::bindings_wgsl(sd_layout.samples_per_map, ray_layout),
            shaders::STOCHASTIC_DEPTH_SAMPLES,
            shaders::SOURCE_STOCHASTIC_DEPTH,
            shaders::RAY_SD_REQUEST,
        ]
        .join("\n"),
        Source::ScreenRaysStochastic => [
            &stochastic_depth::bindings_wgsl(sd_layout, ray_layout.guard),
            shaders::STOCHASTIC_DEPTH_SAMPLES,
            shaders::SCREEN_RAYS_STOCHASTIC,
            shaders::SOURCE_SCREEN_RAYS,
        ]
        .join("\n"),
        Source::ScreenRaysRayStochastic => [
            &ray_stochastic_depth::bindings_wgsl(sd_layout.samples_per_map, ray_layout),
            shaders::STOCHASTIC_DEPTH_SAMPLES,
            shaders::SCREEN_RAYS_STOCHASTIC,
            shaders::SOURCE_SCREEN_RAYS,
        ]
        .join("\n"),
        Source::DepthPyramid => shaders::SOURCE_DEPTH_PYRAMID.to_string(),
    }
}

/// Group-2 layout entries of the resolving passes.
pub(crate) fn resolve_entries(source: Source) -> Vec<wgpu::BindGroupLayoutEntry> {
    match source {
        Source::FirstLayer | Source::ScreenRays => Vec::new(),
        Source::DualDepth | Source::ScreenRaysDual => vec![entry::texture(SOURCE_SECOND_DEPTH)],
        Source::ColumnRays | Source::BvhRays => column_rays::layout_entries(),
        Source::StochasticDepth | Source::ScreenRaysStochastic => {
            stochastic_depth::read_layout_entries()
        }
        Source::RayStochasticDepth | Source::ScreenRaysRayStochastic => {
            ray_stochastic_depth::read_layout_entries()
        }
        Source::DepthPyramid => depth_pyramid::layout_entries(),
    }
}

/// Group-2 layout entries of phase 1 of a two-phase schedule.
pub(crate) fn request_entries(source: Source) -> Vec<wgpu::BindGroupLayoutEntry> {
    match source {
        Source::StochasticDepth => vec![entry::storage(SOURCE_SD_REQUEST, false)],
        Source::RayStochasticDepth => vec![
            entry::storage(SOURCE_SD_REQUEST, false),
            entry::storage(SOURCE_SD_INTERVAL, false),
        ],
        // Phase 1's proofs (bvh_rays_proof.wgsl).
        Source::BvhRays => column_rays::proof_layout_entries(),
        Source::FirstLayer
        | Source::DualDepth
        | Source::ColumnRays
        | Source::DepthPyramid
        | Source::ScreenRays
        | Source::ScreenRaysDual
        | Source::ScreenRaysStochastic
        | Source::ScreenRaysRayStochastic => Vec::new(),
    }
}

enum Held {
    FirstLayer,
    DualDepth,
    /// Column rays and BVH rays: both bind the camera, the overflow counter and the BVH.
    ColumnRays(Box<ColumnRays>),
    StochasticDepth(Box<StochasticDepthMap>),
    RayStochasticDepth(Box<RayStochasticDepthMap>),
    DepthPyramid(Box<DepthPyramid>),
}

/// A hidden-depth source as an [`crate::AmbientOcclusion`] holds it.
pub(crate) struct SourcePass {
    kind: Source,
    held: Held,
    sd_layout: SdLayout,
    /// The ray-traced map's resolution divisor and guard band (1 and 0 for the other sources).
    ray_layout: RayMapLayout,
    resolve_layout: Option<wgpu::BindGroupLayout>,
    request_layout: Option<wgpu::BindGroupLayout>,
    /// Two-phase stochastic depth: the SD-request mask (seed 000 §3.9), written by phase 1, read
    /// by the map's passes: one u32 per framebuffer pixel for the raster map, per texel for the
    /// ray-traced map.
    request: Option<wgpu::Buffer>,
    /// Two-phase ray-traced stochastic depth: the depth interval phase 1's samples need per map
    /// texel (two u32, `ray_stochastic_depth/request.wgsl`).
    interval: Option<wgpu::Buffer>,
    request_group: Option<wgpu::BindGroup>,
    /// Cells of the request mask (pixels or texels): the buffers are padded to 16-byte words.
    request_cells: u64,
    /// Empties the request mask and intervals each frame (timed `sd_request_clear`).
    zero_fill: Option<ZeroFill>,
    /// The source's pipeline constants (the stochastic depth map's query switch).
    constants: Vec<(&'static str, f64)>,
}

fn missing(what: &str, source: Source) -> Error {
    Error::Input(format!(
        "the {} source needs the scene's {what}: pass it in SceneResources (Renderer does this for its own scenes)",
        source.name()
    ))
}

impl SourcePass {
    pub fn new(
        gpu: &Gpu,
        kind: Source,
        schedule: Schedule,
        settings: &AoSettings,
        screen: &ScreenGeometry,
        scene: SceneResources,
    ) -> Result<Self, Error> {
        let device = &gpu.device;
        let full = (screen.full_width(), screen.full_height());
        let mut sd_layout = SdLayout {
            maps: 1,
            samples_per_map: 1,
        };
        let mut ray_layout = RayMapLayout {
            divisor: 1,
            guard: 0,
        };
        let layout_of = |entries: Vec<wgpu::BindGroupLayoutEntry>, label| {
            (!entries.is_empty()).then(|| bindings::layout(device, label, &entries))
        };
        let held = match kind {
            // The march reads only the frame's depth and normals.
            Source::FirstLayer | Source::ScreenRays => Held::FirstLayer,
            Source::DualDepth | Source::ScreenRaysDual => Held::DualDepth,
            Source::ColumnRays | Source::BvhRays => {
                let scene_gpu = scene.scene.ok_or_else(|| missing("triangles", kind))?;
                let bvh = scene.bvh.ok_or_else(|| missing("BVH", kind))?;
                let layout =
                    layout_of(resolve_entries(kind), kind.name()).expect("rays bind their camera");
                let rays = ColumnRays::new(device, &layout, scene_gpu, bvh);
                return Ok(Self {
                    kind,
                    held: Held::ColumnRays(Box::new(rays)),
                    sd_layout,
                    ray_layout,
                    resolve_layout: Some(layout),
                    request_layout: schedule
                        .two_phase()
                        .then(|| layout_of(request_entries(kind), "bvh ray proofs"))
                        .flatten(),
                    request: None,
                    interval: None,
                    request_group: None,
                    request_cells: 0,
                    zero_fill: None,
                    constants: Vec::new(),
                });
            }
            Source::StochasticDepth | Source::ScreenRaysStochastic => {
                let scene_gpu = scene.scene.ok_or_else(|| missing("triangles", kind))?;
                let map = StochasticDepthMap::new(
                    &gpu.adapter,
                    device,
                    &settings.stochastic_depth,
                    settings.peel_separation,
                    (
                        full.0,
                        full.1,
                        settings.stochastic_depth.guard_band_for(screen.height),
                    ),
                    scene_gpu,
                    schedule
                        .two_phase()
                        .then_some(settings.stochastic_depth.mask),
                )?;
                sd_layout = map.layout();
                ray_layout.guard = map.band();
                Held::StochasticDepth(Box::new(map))
            }
            Source::RayStochasticDepth | Source::ScreenRaysRayStochastic => {
                let scene_gpu = scene.scene.ok_or_else(|| missing("triangles", kind))?;
                let bvh = scene.bvh.ok_or_else(|| missing("BVH", kind))?;
                let map = RayStochasticDepthMap::new(
                    device,
                    &settings.ray_sd,
                    settings.peel_separation,
                    full,
                    settings
                        .ray_sd
                        .guard_band_for(screen.height, schedule.two_phase()),
                    scene_gpu,
                    bvh,
                )?;
                sd_layout.samples_per_map = map.reservoir();
                ray_layout = map.layout();
                Held::RayStochasticDepth(Box::new(map))
            }
            Source::DepthPyramid => {
                Held::DepthPyramid(Box::new(DepthPyramid::new(device, &settings.pyramid, full)))
            }
        };
        let request_layout = schedule
            .two_phase()
            .then(|| layout_of(request_entries(kind), "source request"))
            .flatten();
        let maps_hidden_depth = kind.maps_hidden_depth();
        let ray_map_requests = kind == Source::RayStochasticDepth && schedule.two_phase();
        // The raster map's requests are per pixel, the ray-traced map's per texel, each map's
        // own guard band included (what it rasterises or traces).
        let request_cells = match &held {
            Held::RayStochasticDepth(map) => {
                let (w, h) = map.map_size();
                u64::from(w) * u64::from(h)
            }
            Held::StochasticDepth(map) => {
                let (w, h) = map.map_size();
                u64::from(w) * u64::from(h)
            }
            _ => u64::from(full.0) * u64::from(full.1),
        };
        if maps_hidden_depth && schedule.two_phase() {
            let limits = device.limits();
            crate::gpu::check_storage_size(
                &limits,
                "sd request",
                zero_fill_size(request_cells * 4),
            )?;
            if ray_map_requests {
                let bytes = zero_fill_size(request_cells * 8);
                crate::gpu::check_storage_size(&limits, "ray sd intervals", bytes)?;
            }
        }
        let request = (maps_hidden_depth && schedule.two_phase()).then(|| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("sd request"),
                size: zero_fill_size(request_cells * 4),
                usage: wgpu::BufferUsages::STORAGE
                    | wgpu::BufferUsages::COPY_DST
                    | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            })
        });
        let interval = ray_map_requests.then(|| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("ray sd intervals"),
                size: zero_fill_size(request_cells * 8),
                // COPY_SRC: `render --debug-out` reads it (sd_intervals.png).
                usage: wgpu::BufferUsages::STORAGE
                    | wgpu::BufferUsages::COPY_DST
                    | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            })
        });
        let request_group = match (&request_layout, &request) {
            (Some(layout), Some(buffer)) => {
                let mut resources = vec![(SOURCE_SD_REQUEST, buffer.as_entire_binding())];
                resources.extend(
                    interval
                        .as_ref()
                        .map(|b| (SOURCE_SD_INTERVAL, b.as_entire_binding())),
                );
                Some(bindings::group(device, "sd request", layout, &resources))
            }
            _ => None,
        };
        let sd = &settings.stochastic_depth;
        let mut constants = Vec::new();
        let ray_map = kind.map() == Some(Source::RayStochasticDepth);
        // The map's layout, for every reader of it (samples.wgsl declares both).
        if ray_map {
            constants.push(("SD_COMPACT", 1.0));
        } else if kind.map().is_some() && sd.selection == crate::settings::SdSelection::Nearest {
            constants.push(("SD_SORTED", 1.0));
        }
        // What the per-sample reader (read.wgsl) adds; the screen marches over a map read it
        // at every step themselves (screen_rays_stochastic.wgsl).
        if maps_hidden_depth && !kind.marches_layers() {
            if sd.query == crate::settings::SdQuery::Always {
                constants.push(("SD_QUERY_ALWAYS", 1.0));
            }
            // Left at the shader's default when off, so the default pipeline is unchanged.
            if sd.compensation != 1.0 {
                constants.push(("SD_COMPENSATION", f64::from(sd.compensation)));
            }
            let cutoff = settings.ray_sd.radius_cutoff;
            if ray_map && cutoff > 0.0 {
                constants.push(("SD_RADIUS_CUTOFF", f64::from(cutoff)));
            }
            if interval.is_some() && settings.ray_sd.intervals {
                constants.push(("SD_INTERVALS", 1.0));
            }
        }
        let zero_fill = request.is_some().then(|| ZeroFill::new(device));
        Ok(Self {
            kind,
            held,
            sd_layout,
            ray_layout,
            resolve_layout: layout_of(resolve_entries(kind), "source"),
            request_layout,
            request,
            interval: interval.filter(|_| settings.ray_sd.intervals),
            request_group,
            request_cells,
            zero_fill,
            constants,
        })
    }

    /// Pipeline constants every pass composed with this source sets.
    pub fn constants(&self) -> &[(&'static str, f64)] {
        &self.constants
    }

    /// Its WGSL for a pass binding `group` ([`wgsl`]).
    pub fn wgsl(&self, group: SourceGroup) -> String {
        wgsl(self.kind, self.sd_layout, self.ray_layout, group)
    }

    pub fn resolve_layout(&self) -> Option<&wgpu::BindGroupLayout> {
        self.resolve_layout.as_ref()
    }

    pub fn request_layout(&self) -> Option<&wgpu::BindGroupLayout> {
        self.request_layout.as_ref()
    }

    /// The camera of the coming frame (rays and the map's rasterisation use it). `frame` turns
    /// the stochastic maps' random choices (0 without temporal accumulation, which counts frames
    /// so that their noise averages out over time as the estimators' pattern does).
    pub fn set_camera(&self, queue: &wgpu::Queue, view: &FrameView, frame: u32) {
        match &self.held {
            Held::ColumnRays(rays) => {
                rays.set_camera(queue, view.view_matrix().inverse(), view.near)
            }
            Held::StochasticDepth(map) => map.set_camera(queue, view, frame),
            Held::RayStochasticDepth(map) => {
                map.set_camera(queue, view, self.request.is_some(), frame)
            }
            Held::FirstLayer | Held::DualDepth | Held::DepthPyramid(_) => {}
        }
    }

    /// Clears the per-frame counters and request marks before the schedule's first pass (the
    /// marks in a compute pass timed `sd_request_clear`).
    pub fn begin_frame(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        profiler: Option<&mut PassProfiler>,
    ) {
        if let Held::ColumnRays(rays) = &self.held {
            encoder.clear_buffer(&rays.stack_overflows, 0, None);
        }
        if let (Some(zero_fill), Some(request)) = (&self.zero_fill, &self.request) {
            let mut buffers = vec![request];
            buffers.extend(&self.interval);
            zero_fill.encode(device, encoder, &buffers, "sd_request_clear", profiler);
        }
    }

    /// Cells of the request mask: framebuffer pixels (raster map) or map texels (ray-traced).
    pub fn request_cells(&self) -> usize {
        self.request_cells as usize
    }

    /// Renders what the resolving pass reads (the stochastic depth map; for a two-phase schedule
    /// only where phase 1 requested it). Called by the schedule right before that pass.
    /// `gbuffer_z`: the frame's depth buffer where the caller rasterised the frame itself
    /// ([`StochasticDepthMap::render`]).
    pub fn prepare(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameInputs,
        gbuffer_z: Option<&wgpu::Texture>,
        profiler: Option<&mut PassProfiler>,
    ) {
        match &self.held {
            Held::StochasticDepth(map) => map.render(
                device,
                encoder,
                frame.depth,
                gbuffer_z,
                self.request.as_ref(),
                profiler,
            ),
            Held::RayStochasticDepth(map) => map.render(
                device,
                encoder,
                frame.depth,
                self.request.as_ref().map(|r| (r, self.interval.as_ref())),
                profiler,
            ),
            Held::DepthPyramid(pyramid) => pyramid.build(device, encoder, frame.depth, profiler),
            Held::FirstLayer | Held::DualDepth | Held::ColumnRays(_) => {}
        }
    }

    /// Group 2 of the resolving passes for this frame.
    pub fn resolve_group(
        &self,
        device: &wgpu::Device,
        frame: &FrameInputs,
    ) -> Result<Option<wgpu::BindGroup>, Error> {
        let Some(layout) = &self.resolve_layout else {
            return Ok(None);
        };
        Ok(Some(match &self.held {
            Held::FirstLayer => unreachable!("the first layer binds nothing"),
            Held::DualDepth => {
                let second = frame.second_layer.ok_or_else(|| {
                    Error::Input(
                        "the dual depth source needs the second depth layer: pass it to encode (FrameTextures::second_layer)"
                            .into(),
                    )
                })?;
                bindings::group(
                    device,
                    "dual depth",
                    layout,
                    &[(
                        SOURCE_SECOND_DEPTH,
                        wgpu::BindingResource::TextureView(second),
                    )],
                )
            }
            Held::ColumnRays(rays) => rays.group(device),
            Held::StochasticDepth(map) => {
                bindings::group(device, "stochastic depth", layout, &map.read_resources())
            }
            Held::RayStochasticDepth(map) => bindings::group(
                device,
                "ray stochastic depth",
                layout,
                &map.read_resources(),
            ),
            Held::DepthPyramid(pyramid) => {
                bindings::group(device, "depth pyramid", layout, &pyramid.read_resources())
            }
        }))
    }

    /// Group 2 of phase 1 of a two-phase schedule. `visible_triangles`: the triangle each
    /// framebuffer pixel shows, where the caller rasterised the frame itself
    /// ([`crate::raster::gbuffer::GBuffer::visible_triangles`]; BVH rays' blocked proof).
    pub fn request_group(
        &self,
        device: &wgpu::Device,
        visible_triangles: Option<&wgpu::Texture>,
    ) -> Option<wgpu::BindGroup> {
        match (&self.held, &self.request_layout) {
            (Held::ColumnRays(rays), Some(layout)) => {
                let view = visible_triangles.map(|t| t.create_view(&Default::default()));
                Some(rays.proof_group(device, layout, view.as_ref()))
            }
            _ => self.request_group.clone(),
        }
    }

    /// Column rays: the counter of last frame's rays whose BVH traversal overflowed its stack.
    pub fn stack_overflows(&self) -> Option<&wgpu::Buffer> {
        match &self.held {
            Held::ColumnRays(rays) => Some(&rays.stack_overflows),
            _ => None,
        }
    }

    /// The stochastic depth map, for read-backs.
    pub fn stochastic_depth(&self) -> Option<&StochasticDepthMap> {
        match &self.held {
            Held::StochasticDepth(map) => Some(map),
            _ => None,
        }
    }

    /// The ray-traced stochastic depth map, for read-backs and its layout.
    pub fn ray_stochastic_depth(&self) -> Option<&RayStochasticDepthMap> {
        match &self.held {
            Held::RayStochasticDepth(map) => Some(map),
            _ => None,
        }
    }

    /// The depth pyramid, for read-backs.
    pub fn depth_pyramid(&self) -> Option<&DepthPyramid> {
        match &self.held {
            Held::DepthPyramid(pyramid) => Some(pyramid),
            _ => None,
        }
    }

    /// Two-phase stochastic depth: the SD-request mask of the last frame (per framebuffer pixel
    /// for the raster map, per texel of [`RayStochasticDepthMap::map_size`] for the ray-traced).
    pub fn requests(&self) -> Option<&wgpu::Buffer> {
        self.request.as_ref()
    }

    /// Two-phase ray-traced stochastic depth with ray intervals: the interval buffer (two u32
    /// per map texel: the nearest depth's bits inverted, the farthest depth's bits).
    pub fn intervals(&self) -> Option<&wgpu::Buffer> {
        self.interval.as_ref()
    }
}
