//! How passes chain. [`AmbientOcclusion`] is the part an engine embeds: its depth and normals in,
//! an AO texture out. [`renderer::Renderer`] adds our own G-buffer for scenes we load ourselves.
//!
//! A frame is a list of passes (docs/ARCHITECTURE.md, "Data flow"): the technique row's source
//! prepares what it reads (e.g. the stochastic depth map), the row's schedule runs the estimator
//! over it into the raw AO, and then each filter of [`AmbientOcclusion`]'s filter list reads the
//! previous image and writes its own. The schedule decides when the source prepares (before the
//! single pass; between the phases of a two-phase schedule). New sources, schedules and filters
//! (a depth pyramid, half resolution with upsampling, temporal accumulation) slot into this list
//! without touching the estimators.

pub mod renderer;
#[cfg(test)]
mod shader_check;

use crate::bindings;
use crate::error::Error;
use crate::estimators::EstimatorPass;
use crate::filter::{
    atrous::Atrous,
    bilateral::BilateralBlur,
    half_resolution::HalfResolution,
    ray_budget::{RayBudget, RayBudgetReport, TimeBudget},
    temporal::{BudgetRequest, HistoryTexel, TemporalAccumulation},
    AoFilter, FilterImages,
};
use crate::frame::{check_float_texture, check_texture, FrameInputs};
use crate::gpu::{Gpu, PassProfiler};
use crate::schedules::{FrameContext, SchedulePass};
use crate::settings::AoSettings;
use crate::sources::ray_stochastic_depth::RaySdMapSize;
use crate::sources::stochastic_depth::{SdLayout, StochasticDepthMap};
use crate::sources::{SceneResources, SourcePass};
use crate::view::{FrameView, ScreenGeometry};
use wgpu::util::DeviceExt;

/// What a caller's own rasterisation of the frame leaves beside depth and normals
/// ([`crate::Renderer`]'s G-buffer; an engine's frame has none of it).
#[derive(Clone, Copy, Default)]
pub(crate) struct OwnGBuffer<'a> {
    /// The depth buffer (reversed-Z `Depth32Float`, the framebuffer's size): the stochastic depth
    /// map may test its fragments against it instead of writing its own
    /// (`StochasticDepthMap::render`).
    pub z: Option<&'a wgpu::Texture>,
    /// The triangle each framebuffer pixel shows + 1 (`R32Uint`): two-phase BVH rays prove rays
    /// blocked with it (`shaders/sources/bvh_rays_proof.wgsl`).
    pub visible_triangles: Option<&'a wgpu::Texture>,
}

/// The textures of one frame, as the engine has them. All cover the guard-banded framebuffer:
/// `(width + 2g) × (height + 2g)` of the [`ScreenGeometry`], are single-sampled and have the
/// `TEXTURE_BINDING` usage. An engine with a hardware depth buffer and a projection matrix gets
/// them from [`crate::EngineInput`].
#[derive(Clone, Copy)]
pub struct FrameTextures<'a> {
    /// Linear view depth, `R32Float`, world units, 0 = background.
    pub depth: &'a wgpu::Texture,
    /// View-space unit normals facing the camera (a float format; xyz used).
    pub normals: &'a wgpu::Texture,
    /// The second depth layer (linear `R32Float`, 0 = none, e.g. from depth peeling), for
    /// techniques whose row needs it ([`crate::technique::Needs::second_layer`]).
    pub second_layer: Option<&'a wgpu::Texture>,
}

/// One filter of the list and the image it writes.
struct FilterStage {
    filter: Box<dyn AoFilter>,
    output: wgpu::Texture,
}

/// AO for one screen configuration: the technique row's source, schedule and estimator, then
/// the filters (today the bilateral blur, when enabled). With `resolution = "half"` these run on
/// a half-resolution copy of the frame between a downsample and a depth-aware upsample
/// ([`HalfResolution`]).
///
/// The output is an `R32Float` texture of the *visible* size (no guard band), 1 = unoccluded.
pub struct AmbientOcclusion {
    gpu: Gpu,
    settings: AoSettings,
    screen: ScreenGeometry,
    view: wgpu::Buffer,
    frame_layout: wgpu::BindGroupLayout,
    estimator: EstimatorPass,
    source: SourcePass,
    schedule: SchedulePass,
    raw: wgpu::Texture,
    /// `bent_normals`: the bent normals (visible size, `Rgba16Float`); 1×1 and unwritten otherwise.
    bent: wgpu::Texture,
    /// The frame group's ray grant without a ray budget: 1×1, never read.
    no_ray_grant: wgpu::Texture,
    filters: Vec<FilterStage>,
    /// `resolution = "half"`: the half frame and the passes around the technique.
    half: Option<HalfResolution>,
    /// [`AmbientOcclusion::set_camera`] was called (rows that trace or rasterise need it).
    camera_set: std::sync::atomic::AtomicBool,
}

impl AmbientOcclusion {
    /// Build pipelines and images for `screen`. `settings` are validated first. `scene` holds
    /// what the technique's row needs ([`crate::technique::Needs`]): the triangles for the
    /// stochastic depth map and column rays, a BVH for column rays; a missing one is an error
    /// naming it. The adapter says which stochastic depth sample counts the map can have; an
    /// unsupported one is an error naming the supported ones.
    pub fn new(
        gpu: &Gpu,
        settings: &AoSettings,
        screen: ScreenGeometry,
        scene: SceneResources,
    ) -> Result<Self, Error> {
        Self::build(gpu, settings, screen, scene, false)
    }

    /// [`AmbientOcclusion::new`]; `estimator_debug`: the AO pass writes the estimator's debug
    /// image ([`crate::technique::Estimator::debug_image`]) instead of its AO, unblurred.
    pub(crate) fn build(
        gpu: &Gpu,
        settings: &AoSettings,
        screen: ScreenGeometry,
        scene: SceneResources,
        estimator_debug: bool,
    ) -> Result<Self, Error> {
        // Pipelines an earlier constructor on this Gpu made are reused (gpu::memo).
        let _kept = gpu.keeping();
        settings.validate()?;
        gpu.check_backend()?;
        let device = &gpu.device;
        let row = settings.technique.row();
        let needs = settings.technique.needs();
        if settings.bent_normals {
            check_bent_normals(settings)?;
        }
        if screen.orthographic && (needs.triangles || needs.bvh) {
            return Err(Error::Input(format!(
                "technique '{}' traces or rasterises hidden depth from a perspective camera; with \
                 an orthographic projection use a screen-space technique ({})",
                settings.technique,
                crate::technique::names_where(|t| !t.needs().triangles && !t.needs().bvh)
            )));
        }
        let view = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("view"),
            contents: bytemuck::bytes_of(&screen.uniform()),
            // COPY_DST: set_camera writes the near plane and, with temporal accumulation, the
            // pattern offset and the frame number.
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        });
        let half = match settings.resolution {
            crate::settings::Resolution::Full => None,
            crate::settings::Resolution::Half => Some(HalfResolution::new(device, &screen, &view)?),
        };
        // The geometry the technique runs at, and its View uniform.
        let (work, work_view) = match &half {
            Some(h) => (h.screen(), h.view()),
            None => (screen, &view),
        };
        let frame_layout = bindings::frame_layout(device, true);
        let (section, mut inputs) = settings.estimator_inputs();
        // The debug image runs no temporal accumulation, so no budget either: every ray.
        inputs.ray_budget &= !estimator_debug;
        let estimator = EstimatorPass::new(
            device,
            &gpu.queue,
            (row.estimator.name(), row.estimator.caps().module),
            (&section, &inputs),
            // Output pixels: at half resolution, half as many of the working image's.
            settings.max_radius_px * work.height as f32 / screen.height as f32,
        );
        let source = SourcePass::new(gpu, row.source, row.schedule, settings, &work, scene)?;
        let schedule = SchedulePass::new(
            row,
            &frame_layout,
            &estimator,
            &source,
            &work,
            crate::schedules::PixelOutputs {
                estimator_debug,
                bent_normals: settings.bent_normals,
            },
            &crate::schedules::ScheduleInputs {
                gpu,
                settings,
                scene: scene.scene,
            },
        )?;
        let ao_texture = |label| {
            crate::gpu::texture_2d(
                device,
                label,
                work.width,
                work.height,
                wgpu::TextureFormat::R32Float,
                wgpu::TextureUsages::STORAGE_BINDING
                    | wgpu::TextureUsages::TEXTURE_BINDING
                    | wgpu::TextureUsages::COPY_SRC,
            )
        };
        // Unwritten without `bent_normals`: a 1×1 stand-in for the frame group.
        let (bent_width, bent_height) = match settings.bent_normals {
            true => (work.width, work.height),
            false => (1, 1),
        };
        let mut filters = Vec::new();
        // Temporal accumulation first: it averages the raw AO's rotation noise over frames and
        // clips its history to the raw neighbourhood's spread; the blur smooths what is left.
        if settings.temporal.enabled && !estimator_debug {
            filters.push(FilterStage {
                filter: Box::new(TemporalAccumulation::new(
                    device,
                    &settings.temporal,
                    work_view,
                    &work,
                    inputs.ray_budget.then(|| BudgetRequest {
                        rays: settings.hemisphere.rays,
                        budget: initial_ray_budget(settings, &work),
                    }),
                    match settings.technique.estimator() {
                        crate::technique::Estimator::Hemisphere => settings.hemisphere.rays,
                        _ => 0,
                    },
                )),
                output: ao_texture("ao accumulated"),
            });
        }
        // The à-trous denoiser takes the blur's place when enabled.
        if settings.denoise.enabled && !estimator_debug {
            filters.push(FilterStage {
                filter: Box::new(Atrous::new(
                    device,
                    &settings.denoise,
                    work_view,
                    &work,
                    settings.radius(),
                    match row.estimator {
                        crate::technique::Estimator::Hemisphere => settings.hemisphere.rays,
                        _ => 0,
                    },
                    settings.temporal.enabled,
                )),
                output: ao_texture("ao denoised"),
            });
        } else if settings.blur.enabled && !estimator_debug {
            filters.push(FilterStage {
                filter: Box::new(BilateralBlur::new(
                    device,
                    &settings.blur,
                    work_view,
                    work.width,
                    work.height,
                )),
                output: ao_texture("ao blurred"),
            });
        }
        Ok(Self {
            gpu: gpu.clone(),
            settings: *settings,
            screen,
            view,
            frame_layout,
            estimator,
            source,
            schedule,
            raw: ao_texture("ao raw"),
            bent: crate::gpu::texture_2d(
                device,
                "bent normals",
                bent_width,
                bent_height,
                wgpu::TextureFormat::Rgba16Float,
                wgpu::TextureUsages::STORAGE_BINDING
                    | wgpu::TextureUsages::TEXTURE_BINDING
                    | wgpu::TextureUsages::COPY_SRC,
            ),
            no_ray_grant: crate::gpu::texture_2d(
                device,
                "no ray grant",
                1,
                1,
                wgpu::TextureFormat::R32Uint,
                wgpu::TextureUsages::TEXTURE_BINDING,
            ),
            filters,
            half,
            camera_set: std::sync::atomic::AtomicBool::new(false),
        })
    }

    /// The camera of the coming frame; sources that trace rays or rasterise use it, and so does
    /// temporal accumulation (`temporal.enabled`), which takes each call as a new frame: call it
    /// once per frame, before [`encode`](Self::encode). Those rows (and temporal accumulation)
    /// refuse to encode until it was set once; its screen geometry must be the one this was
    /// built for.
    pub fn set_camera(&self, queue: &wgpu::Queue, view: &FrameView) {
        let work = match &self.half {
            Some(_) => view.half(),
            None => *view,
        };
        // Filters first: temporal accumulation counts the frame the sources then turn by.
        for stage in &self.filters {
            stage.filter.set_camera(queue, &work);
        }
        let frame = self.temporal().map_or(0, TemporalAccumulation::frame);
        self.source.set_camera(queue, &work, frame);
        self.schedule.set_camera(queue, &work);
        // The camera's near plane, and with temporal accumulation the estimators' pattern turned
        // by one entry per frame (View pattern_offset) and the frame number.
        let mut uniform = work.screen().uniform();
        uniform.near = work.near;
        if let Some(temporal) = self.temporal() {
            uniform.pattern_offset = temporal.pattern_offset();
            uniform.frame = temporal.frame();
        }
        let buffer = self.half.as_ref().map_or(&self.view, HalfResolution::view);
        queue.write_buffer(buffer, 0, bytemuck::bytes_of(&uniform));
        self.camera_set
            .store(true, std::sync::atomic::Ordering::Relaxed);
    }

    /// Temporal accumulation, when `temporal.enabled`.
    fn temporal(&self) -> Option<&TemporalAccumulation> {
        self.filters.iter().find_map(|f| f.filter.as_temporal())
    }

    /// `temporal.enabled`: forgets the accumulated history, so the next frame starts afresh (a
    /// camera cut, a changed scene). Does nothing otherwise.
    pub fn reset_temporal(&self) {
        if let Some(temporal) = self.temporal() {
            temporal.reset();
        }
    }

    /// Under a ray budget (`hemisphere.ray_budget` or `time_budget`, with temporal accumulation):
    /// the rays a frame from the next frame on (frame loops with a time budget set it from the
    /// GPU timings, [`TimeBudget`]). An error without a budget.
    pub fn set_ray_budget(&self, rays: u32) -> Result<(), Error> {
        self.ray_budget()?.set_budget(rays);
        Ok(())
    }

    /// Under a ray budget: what the last frame's selection granted (read back from the GPU).
    pub fn read_ray_budget(&self) -> Result<RayBudgetReport, Error> {
        Ok(self.ray_budget()?.read(&self.gpu)?)
    }

    /// Under a ray budget: the rays each visible pixel (of the working resolution) was granted
    /// the last frame, row-major.
    pub fn read_ray_grant(&self) -> Result<Vec<u32>, Error> {
        let bytes = crate::gpu::read_texture_bytes(&self.gpu, self.ray_budget()?.grant_image(), 4)?;
        Ok(bytemuck::cast_slice(&bytes).to_vec())
    }

    /// With a time budget (`hemisphere.time_budget`): sets the next frame's ray budget from the
    /// last frame's GPU `timings` ([`TimeBudget`]) and returns what that frame granted;
    /// `None` without a time budget (nothing to follow). Frame loops call it after each timed
    /// frame.
    pub fn follow_time_budget(
        &self,
        timings: &crate::gpu::FrameTimings,
    ) -> Result<Option<RayBudgetReport>, Error> {
        let target = self.settings.hemisphere.time_budget;
        if target.is_nan() || target <= 0.0 || !self.settings.ray_budget_active() {
            return Ok(None);
        }
        let budget = self.ray_budget()?;
        let report = budget.read(&self.gpu)?;
        let controller = TimeBudget {
            target_ms: f64::from(target),
            max_rays: report.wanted,
        };
        budget.set_budget(controller.next(report.budget, TimeBudget::ao_ms(timings)));
        Ok(Some(report))
    }

    fn ray_budget(&self) -> Result<&RayBudget, Error> {
        self.temporal()
            .and_then(TemporalAccumulation::ray_budget)
            .ok_or_else(|| {
                Error::Input(
                    "no ray budget: set hemisphere.ray_budget (--ray-budget) or \
                     hemisphere.time_budget on a hemisphere row with temporal.enabled"
                        .into(),
                )
            })
    }

    /// `temporal.enabled`: the history the last frame wrote, per visible pixel (at the working
    /// resolution): the accumulated AO, the number of frames in it (1: history rejected, e.g.
    /// disoccluded) and the linear depth. Waits for the GPU; for tests and tools.
    pub fn read_temporal_history(&self) -> Result<Option<Vec<HistoryTexel>>, Error> {
        let Some(temporal) = self.temporal() else {
            return Ok(None);
        };
        let bytes = crate::gpu::read_texture_bytes(&self.gpu, temporal.history().texture(), 8)?;
        let words: &[u32] = bytemuck::cast_slice(&bytes);
        Ok(Some(
            words
                .chunks_exact(2)
                .map(|w| HistoryTexel::unpack([w[0], w[1]]))
                .collect(),
        ))
    }

    /// The settings it was built with (validated).
    pub fn settings(&self) -> &AoSettings {
        &self.settings
    }

    /// The screen geometry it was built for: the inputs' and the output's sizes.
    pub fn screen(&self) -> ScreenGeometry {
        self.screen
    }

    /// The screen geometry the technique runs at: [`Self::screen`], or its half with
    /// `resolution = "half"` (the raw AO, sample masks, maps and requests are that size).
    pub fn work_screen(&self) -> ScreenGeometry {
        self.half
            .as_ref()
            .map_or(self.screen, HalfResolution::screen)
    }

    /// Record the passes of one frame. The textures must cover the guard-banded framebuffer
    /// ([`FrameTextures`]); a wrong size, format, usage or sample count, a missing second layer
    /// where the row needs it, or (rows that trace or rasterise) no [`set_camera`] yet is an
    /// error naming it. Validation errors wgpu reported on this device since the last check are
    /// returned too; what wgpu only sees when the commands run (a texture of another device)
    /// comes from [`Gpu::finish`] or the next `encode`.
    ///
    /// [`set_camera`]: Self::set_camera
    pub fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        textures: FrameTextures,
        profiler: Option<&mut PassProfiler>,
    ) -> Result<(), Error> {
        self.encode_with_gbuffer(encoder, textures, OwnGBuffer::default(), profiler)
    }

    /// [`Self::encode`] for a frame the caller rasterised itself with this camera
    /// ([`crate::Renderer`]'s G-buffer), which may leave more than depth and normals
    /// ([`OwnGBuffer`]). Not at half resolution, whose frame is another size.
    pub(crate) fn encode_with_gbuffer(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        textures: FrameTextures,
        gbuffer: OwnGBuffer,
        mut profiler: Option<&mut PassProfiler>,
    ) -> Result<(), Error> {
        let device = &self.gpu.device;
        let needs = self.settings.technique.needs();
        if (needs.triangles || needs.bvh)
            && !self.camera_set.load(std::sync::atomic::Ordering::Relaxed)
        {
            return Err(Error::Input(format!(
                "technique '{}' traces or rasterises the scene from the camera: call \
                 AmbientOcclusion::set_camera before the first encode",
                self.settings.technique
            )));
        }
        if self.settings.temporal.enabled
            && !self.camera_set.load(std::sync::atomic::Ordering::Relaxed)
        {
            return Err(Error::Input(
                "temporal accumulation reprojects its history by the camera motion: call \
                 AmbientOcclusion::set_camera before every encode"
                    .into(),
            ));
        }
        let needs_second = needs.second_layer;
        if needs_second && textures.second_layer.is_none() {
            return Err(Error::Input(format!(
                "technique '{}' needs the second depth layer: set FrameTextures::second_layer",
                self.settings.technique
            )));
        }
        let second_layer = textures.second_layer.filter(|_| needs_second);
        let r32 = [wgpu::TextureFormat::R32Float];
        check_texture(&self.screen, "AO depth", textures.depth, &r32)?;
        check_float_texture(&self.screen, "AO normals", textures.normals)?;
        if let Some(second) = second_layer {
            check_texture(&self.screen, "AO second depth layer", second, &r32)?;
        }
        let depth = textures.depth.create_view(&Default::default());
        let normals = textures.normals.create_view(&Default::default());
        let second = second_layer.map(|t| t.create_view(&Default::default()));
        let frame = FrameInputs {
            depth: &depth,
            normals: &normals,
            second_layer: second.as_ref(),
            screen: self.screen,
            view: &self.view,
        };
        let half_views = self.half.as_ref().map(|half| {
            half.downsample(device, encoder, &frame, profiler.as_deref_mut());
            let (d, n, s) = half.textures();
            let view = |t: &wgpu::Texture| t.create_view(&Default::default());
            (view(d), view(n), view(s))
        });
        let half_frame = match (&self.half, &half_views) {
            (Some(half), Some((depth, normals, second))) => Some(FrameInputs {
                depth,
                normals,
                second_layer: needs_second.then_some(second),
                screen: half.screen(),
                view: half.view(),
            }),
            _ => None,
        };
        // The frame the technique runs on.
        let work = half_frame.as_ref().unwrap_or(&frame);
        let raw = self.raw.create_view(&Default::default());
        let bent = self.bent.create_view(&Default::default());
        // The ray budget picks this frame's rays from the history before the AO pass casts them.
        let temporal = self.temporal();
        if let Some(temporal) = temporal {
            temporal.encode_budget(device, encoder, work, profiler.as_deref_mut());
        }
        let ray_grant = temporal
            .and_then(TemporalAccumulation::ray_budget)
            .map_or(&self.no_ray_grant, |b| b.grant_image())
            .create_view(&Default::default());
        let frame_group = work.group(device, &self.frame_layout, &raw, &bent, &ray_grant);
        let ctx = FrameContext {
            device,
            frame: work,
            frame_group: &frame_group,
            output: &raw,
            bent: &bent,
            ray_grant: &ray_grant,
            estimator: &self.estimator,
            source: &self.source,
            gbuffer_z: gbuffer.z.filter(|_| self.half.is_none()),
            visible_triangles: gbuffer.visible_triangles.filter(|_| self.half.is_none()),
        };
        self.schedule
            .encode(&ctx, encoder, profiler.as_deref_mut())?;
        let mut input = raw;
        let mut history = None;
        for stage in &self.filters {
            let output = stage.output.create_view(&Default::default());
            let images = FilterImages {
                input: &input,
                output: &output,
                history,
            };
            stage
                .filter
                .encode(device, encoder, work, images, profiler.as_deref_mut());
            // The filters after temporal accumulation read the history it wrote.
            history = history.or(stage
                .filter
                .as_temporal()
                .map(TemporalAccumulation::history));
            input = output;
        }
        if let Some(half) = &self.half {
            half.upsample(device, encoder, &frame, &input, profiler);
        }
        // wgpu reports what the checks above cannot see (e.g. a texture of another device) to
        // the device's error handler: surface it here, as this call's error.
        Ok(self.gpu.check_errors()?)
    }

    /// The final AO (after the last filter, and the upsample at half resolution): visible size.
    pub fn output(&self) -> &wgpu::Texture {
        match &self.half {
            Some(half) => half.output(),
            None => self.work_output(),
        }
    }

    /// The final AO of the last encoded frame, row-major over the visible image (1 =
    /// unoccluded). Waits for the GPU; for tests, tools and examples (an engine samples
    /// [`AmbientOcclusion::output`] instead).
    pub fn read_output(&self) -> Result<Vec<f32>, Error> {
        Ok(crate::gpu::read_texture_f32(&self.gpu, self.output(), 1)?)
    }

    /// `bent_normals`: the bent normals of the last frame, `Rgba16Float` of the visible size:
    /// xyz the view-space unit bent normal (right-handed, camera looking down −Z, as the input
    /// normals), w = 1 on geometry and all zero on background pixels. Unfiltered. None without
    /// `bent_normals`.
    pub fn bent_normals(&self) -> Option<&wgpu::Texture> {
        self.settings.bent_normals.then_some(&self.bent)
    }

    /// [`Self::bent_normals`] read back, row-major `[x, y, z, w]` per visible pixel. Waits for
    /// the GPU.
    pub fn read_bent_normals(&self) -> Result<Option<Vec<[f32; 4]>>, Error> {
        let Some(texture) = self.bent_normals() else {
            return Ok(None);
        };
        let bytes = crate::gpu::read_texture_bytes(&self.gpu, texture, 8)?;
        let halves: &[half::f16] = bytemuck::cast_slice(&bytes);
        Ok(Some(
            halves
                .chunks_exact(4)
                .map(|c| [c[0].to_f32(), c[1].to_f32(), c[2].to_f32(), c[3].to_f32()])
                .collect(),
        ))
    }

    /// The AO after the filters at the resolution the technique ran at ([`Self::work_screen`]):
    /// [`Self::output`] before the upsample at half resolution, the same texture otherwise.
    pub fn work_output(&self) -> &wgpu::Texture {
        self.filters.last().map_or(&self.raw, |f| &f.output)
    }

    /// The schedule's AO before the filters ([`Self::work_screen`]'s visible size).
    pub fn raw_output(&self) -> &wgpu::Texture {
        &self.raw
    }

    /// The stochastic depth map's layout (stochastic-depth rows only; the ray-traced map: one
    /// map of N slots).
    pub fn stochastic_depth_layout(&self) -> Option<SdLayout> {
        self.source
            .stochastic_depth()
            .map(StochasticDepthMap::layout)
            .or_else(|| {
                self.source.ray_stochastic_depth().map(|map| SdLayout {
                    maps: 1,
                    samples_per_map: map.reservoir(),
                })
            })
    }

    /// The stochastic depth map of the last frame (stochastic-depth rows): every sample layer of
    /// the framebuffer as linear depth, 0 = empty (see [`StochasticDepthMap::read_layers`]). A
    /// two-phase row's map is defined only at the pixels phase 1 requested; it reads as empty
    /// elsewhere. Waits for the GPU.
    pub fn read_stochastic_depth(&self) -> Result<Option<Vec<Vec<f32>>>, Error> {
        let Some(mut layers) = self.read_stochastic_depth_as_written()? else {
            return Ok(None);
        };
        if let Some(requests) = self.read_sd_requests()? {
            for layer in &mut layers {
                for (z, &r) in layer.iter_mut().zip(&requests) {
                    if r == 0 {
                        *z = 0.0;
                    }
                }
            }
        }
        Ok(Some(layers))
    }

    /// [`AmbientOcclusion::read_stochastic_depth`] without emptying the pixels phase 1 did not
    /// request: the map as the raster pass left it. A two-phase row's map must be empty there
    /// (the stencil, depth or shader test keeps those pixels from the pass); this shows whether
    /// it is. Waits for the GPU.
    pub fn read_stochastic_depth_as_written(&self) -> Result<Option<Vec<Vec<f32>>>, Error> {
        match (
            self.source.stochastic_depth(),
            self.source.ray_stochastic_depth(),
        ) {
            (Some(map), _) => map.read_layers(&self.gpu).map(Some),
            (None, Some(map)) => map.read_layers(&self.gpu).map(Some),
            (None, None) => Ok(None),
        }
    }

    /// The ray-traced stochastic depth map's size in texels, its guard band included, and that
    /// band's width in texels on each side (seed 002 §3.5); `None` for other sources.
    pub fn ray_sd_map_size(&self) -> Option<RaySdMapSize> {
        self.source.ray_stochastic_depth().map(|map| map.extent())
    }

    /// The size of the SD-request mask [`Self::read_sd_request_texels`] returns and its band
    /// beyond the framebuffer on each side: the ray-traced map's texels
    /// ([`Self::ray_sd_map_size`]), or the raster map's pixels with its own band
    /// (`stochastic_depth.guard_band`); `None` without a stochastic depth map.
    pub fn sd_request_map_size(&self) -> Option<RaySdMapSize> {
        self.ray_sd_map_size().or_else(|| {
            self.source.stochastic_depth().map(|map| {
                let (width, height) = map.map_size();
                RaySdMapSize {
                    width,
                    height,
                    guard_texels: map.band(),
                }
            })
        })
    }

    /// The ray-traced stochastic depth map's hits per ray of the last frame (`ray-sd-vao`,
    /// `ray-sd-vao-full`; framebuffer-sized, 0 where nothing was traced). Waits for the GPU.
    pub fn read_ray_sd_hits(&self) -> Result<Option<Vec<u32>>, Error> {
        match self.source.ray_stochastic_depth() {
            Some(map) => Ok(Some(map.read_hits(&self.gpu)?)),
            None => Ok(None),
        }
    }

    /// The depth pyramid of the last frame (`sao`, `pyramid-hbao`): levels 1 … L − 1, level l
    /// ⌈W/K^l⌉ × ⌈H/K^l⌉ texels of the framebuffer (guard band included), row-major, linear
    /// depth, 0 = background. Waits for the GPU.
    pub fn read_depth_pyramid(&self) -> Result<Option<Vec<Vec<f32>>>, Error> {
        match self.source.depth_pyramid() {
            Some(pyramid) => Ok(Some(pyramid.read_levels(&self.gpu)?)),
            None => Ok(None),
        }
    }

    /// Two-phase stochastic depth: the SD-request mask of the last frame, one value per
    /// framebuffer pixel (guard band included), non-zero where phase 1 asked for the map (for
    /// the ray-traced map: where it asked for the pixel's texel, so a requested texel shows at
    /// each of its pixels). Either map's own guard band is left out, see
    /// [`Self::read_sd_request_texels`]. Waits for the GPU.
    pub fn read_sd_requests(&self) -> Result<Option<Vec<u32>>, Error> {
        let Some(words) = self.read_sd_request_texels()? else {
            return Ok(None);
        };
        Ok(Some(
            match (
                self.source.ray_stochastic_depth(),
                self.source.stochastic_depth(),
            ) {
                (Some(map), _) => map.texel_of_pixels().map(|t| words[t]).collect(),
                (None, Some(map)) => map.cell_of_pixels().map(|t| words[t]).collect(),
                (None, None) => words,
            },
        ))
    }

    /// Two-phase stochastic depth: the SD-request mask of the last frame as phase 1 wrote it:
    /// per pixel of the raster map (its own band included), per texel of the ray-traced map
    /// ([`crate::sources::ray_stochastic_depth::RayStochasticDepthMap::map_size`], its guard band included: seed 002 Fig. 13c's view).
    /// Waits for the GPU.
    pub fn read_sd_request_texels(&self) -> Result<Option<Vec<u32>>, Error> {
        let Some(buffer) = self.source.requests() else {
            return Ok(None);
        };
        let mut words: Vec<u32> =
            bytemuck::pod_collect_to_vec(&crate::gpu::read_buffer_copy(&self.gpu, buffer)?);
        // The buffer is padded to whole 16-byte words.
        words.truncate(self.source.request_cells());
        Ok(Some(words))
    }

    /// Two-phase ray-traced stochastic depth with ray intervals (seed 002 §3.2): per framebuffer
    /// pixel (guard band included), the linear depth interval `[near, far]` phase 1's samples
    /// need from the map's texel there, or `None` where no sample asked. Waits for the GPU.
    pub fn read_sd_intervals(&self) -> Result<Option<Vec<Option<[f32; 2]>>>, Error> {
        let (Some(buffer), Some(map)) =
            (self.source.intervals(), self.source.ray_stochastic_depth())
        else {
            return Ok(None);
        };
        let words: Vec<u32> =
            bytemuck::pod_collect_to_vec(&crate::gpu::read_buffer_copy(&self.gpu, buffer)?);
        Ok(Some(
            map.texel_of_pixels()
                // request.wgsl stores max(~near bits) and max(far bits): 0 where nothing asked.
                .map(|t| {
                    let w = &words[2 * t..2 * t + 2];
                    (w[0] != 0 || w[1] != 0).then(|| [f32::from_bits(!w[0]), f32::from_bits(w[1])])
                })
                .collect(),
        ))
    }

    /// Rays of the last frame whose BVH traversal overflowed its stack (0 for techniques without
    /// rays). Waits for the GPU.
    pub fn read_stack_overflows(&self) -> Result<u32, Error> {
        let Some(counter) = self.source.stack_overflows() else {
            return Ok(0);
        };
        let bytes = crate::gpu::read_buffer_copy(&self.gpu, counter)?;
        Ok(u32::from_le_bytes([bytes[0], bytes[1], bytes[2], bytes[3]]))
    }

    /// Two-phase rows: per visible pixel, the bit mask of the samples phase 1 flagged for the
    /// source in the last frame. Waits for the GPU.
    pub fn read_sample_masks(&self) -> Result<Option<Vec<u32>>, Error> {
        let Some(records) = self.schedule.phase1_records() else {
            return Ok(None);
        };
        let words: Vec<u32> =
            bytemuck::pod_collect_to_vec(&crate::gpu::read_buffer_copy(&self.gpu, records)?);
        let work = self.work_screen();
        let pixels = (work.width * work.height) as usize;
        Ok(Some(
            words.chunks_exact(4).take(pixels).map(|r| r[0]).collect(),
        ))
    }
}

/// The first frame's ray budget: `hemisphere.ray_budget`, or with only a time budget every ray
/// the working image's pixels would cast (the time budget lowers it from the timings).
fn initial_ray_budget(settings: &AoSettings, work: &ScreenGeometry) -> u32 {
    match settings.hemisphere.ray_budget {
        0 => (u64::from(work.width) * u64::from(work.height) * u64::from(settings.hemisphere.rays))
            .min(u64::from(u32::MAX)) as u32,
        n => n,
    }
}

/// `bent_normals` needs an estimator that reports them, on the single-pass schedule (the
/// two-phase ones carry only three words per pixel between their phases), at full resolution:
/// otherwise an error naming the techniques that can.
fn check_bent_normals(settings: &AoSettings) -> Result<(), Error> {
    let can = |row: &crate::technique::TechniqueRow| {
        row.estimator.bent_normals() && row.schedule == crate::technique::Schedule::Single
    };
    if !can(settings.technique.row()) {
        return Err(Error::Input(format!(
            "technique '{}' reports no bent normals: use one of {} or leave out --bent-normals",
            settings.technique,
            crate::technique::names_where(can)
        )));
    }
    if settings.resolution != crate::settings::Resolution::Full {
        return Err(Error::Input(
            "bent normals are written at full resolution only: leave out --resolution half or \
             --bent-normals"
                .into(),
        ));
    }
    Ok(())
}
