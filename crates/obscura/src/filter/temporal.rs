//! Temporal accumulation (issue 13; `shaders/filter/temporal_accumulation.wgsl`): the AO of the last
//! frames, reprojected by depth and camera motion, averaged with this frame's, history rejected
//! where the surface differs (depth or normal). The estimators turn their 4×4 pattern by one
//! entry per frame meanwhile ([`TemporalAccumulation::pattern_offset`]), so a still camera
//! converges to the mean over all 16 rotations.
//!
//! The filter keeps the previous camera itself: [`TemporalAccumulation::set_camera`] is called
//! once per frame (by [`crate::AmbientOcclusion::set_camera`]), before the frame is encoded.

use super::shared_cell::SharedCell;

use super::ray_budget::RayBudget;
use super::FilterImages;
use crate::frame::FrameInputs;
use crate::gpu::PassProfiler;
use crate::settings::TemporalSettings;
use crate::shaders;
use crate::view::{FrameView, ScreenGeometry};
use glam::Mat4;

/// The 16 entries of the estimators' 4×4 pattern (`common/pattern.wgsl`).
pub const PATTERN_PERIOD: u32 = 16;

/// The history's depth keeps f32's exponent less this in 7 bits: depths from 2^-64 to 2^64
/// (`DEPTH_EXPONENT_BIAS` of the shader).
const HISTORY_DEPTH_EXPONENT_BIAS: u32 = 63;

/// One texel of the history ([`crate::AmbientOcclusion::read_temporal_history`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HistoryTexel {
    /// The accumulated AO.
    pub ao: f32,
    /// Frames in it: 1 where the history was rejected (disocclusion, first frame), 0 on
    /// background.
    pub frames: u32,
    /// The linear depth it was accumulated at.
    pub depth: f32,
}

impl HistoryTexel {
    /// One texel as `temporal_accumulation.wgsl` packs it: AO in 24-bit fixed point above the
    /// frame count in the low byte; the depth in the low half of the second word, as the shader's
    /// `pack_history_depth` writes it (7 exponent and 9 mantissa bits, relative error ≤ 2^-10).
    pub fn unpack(words: [u32; 2]) -> Self {
        Self {
            ao: (words[0] >> 8) as f32 / 16_777_215.0,
            frames: words[0] & 255,
            depth: f32::from_bits(((words[1] & 0xffff) + (HISTORY_DEPTH_EXPONENT_BIAS << 9)) << 14),
        }
    }
}

/// `TemporalParams` of the shader.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct TemporalParams {
    current_to_previous: [[f32; 4]; 4],
    current_to_world: [[f32; 4]; 4],
    depth_tolerance: f32,
    normal_cos: f32,
    max_frames: f32,
    clamp: u32,
    history_valid: u32,
    sample_rays: u32,
    _pad: [u32; 2],
}

/// One compute pass per frame, with two history images it alternates between.
pub struct TemporalAccumulation {
    pipeline: wgpu::ComputePipeline,
    params: wgpu::Buffer,
    view: wgpu::Buffer,
    history: [wgpu::TextureView; 2],
    settings: TemporalSettings,
    /// The camera of the last frame (`None`: no history yet).
    previous: SharedCell<Option<FrameView>>,
    /// Frames since creation or the last reset; picks the history image and the pattern offset.
    frame: SharedCell<u32>,
    /// `hemisphere.ray_budget`: which pixels cast rays this frame, from this history.
    budget: Option<RayBudget>,
    /// Rays whose visibilities each pixel's AO averages (the hemisphere rows), else 0.
    sample_rays: u32,
}

/// A ray budget for [`TemporalAccumulation::new`]: pixels cast `rays` rays when granted, at most
/// `budget` a frame.
#[derive(Clone, Copy, Debug)]
pub struct BudgetRequest {
    /// Rays a granted pixel casts (`hemisphere.rays`).
    pub rays: u32,
    /// Rays a frame, at most.
    pub budget: u32,
}

impl TemporalAccumulation {
    /// The pass and its history images for the AO image of `screen` (its visible size); `view`
    /// is its `View` uniform; `budget`: the ray budget that reads this history, if any;
    /// `sample_rays`: for an estimator whose pixel is the mean of that many ray visibilities
    /// (the hemisphere rows), which widens the history clip to that sampling noise; else 0.
    pub fn new(
        device: &wgpu::Device,
        settings: &TemporalSettings,
        view: &wgpu::Buffer,
        screen: &ScreenGeometry,
        budget: Option<BudgetRequest>,
        sample_rays: u32,
    ) -> Self {
        let source = shaders::with_common(
            &[shaders::VIEW, shaders::VERTEX_NORMAL],
            shaders::TEMPORAL_ACCUMULATION,
        );
        // SAFETY: every texel the shader touches is in range by construction: it returns for
        // ids outside the visible size; the 3×3 neighbourhood is clamped into the visible image;
        // the depth and normals are read at id + guard band, inside the framebuffer whose size
        // `AmbientOcclusion::encode` checks before binding them; history taps are bounds-tested
        // before each load; the AO and history images are this filter's own, of the visible size.
        let pipeline = unsafe {
            crate::gpu::compute_pipeline_unchecked(
                device,
                "temporal accumulation",
                &source,
                &screen.view_constants(),
            )
        };
        let (width, height) = (screen.width, screen.height);
        let params = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("temporal params"),
            size: std::mem::size_of::<TemporalParams>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let history = ["temporal history a", "temporal history b"].map(|label| {
            crate::gpu::texture_2d(
                device,
                label,
                width,
                height,
                wgpu::TextureFormat::Rg32Uint,
                wgpu::TextureUsages::STORAGE_BINDING
                    | wgpu::TextureUsages::TEXTURE_BINDING
                    | wgpu::TextureUsages::COPY_SRC,
            )
            .create_view(&Default::default())
        });
        Self {
            pipeline,
            params,
            view: view.clone(),
            history,
            settings: *settings,
            previous: SharedCell::new(None),
            frame: SharedCell::new(0),
            budget: budget.map(|b| RayBudget::new(device, &source, screen, b.rays, b.budget)),
            sample_rays,
        }
    }

    /// Starts a new frame seen from `view`: uploads the motion from the previous frame's camera.
    pub fn set_camera(&self, queue: &wgpu::Queue, view: &FrameView) {
        let current_to_world = view.view_matrix().inverse();
        let (current_to_previous, valid) = match self.previous.get() {
            Some(previous) => (previous.view_matrix() * current_to_world, 1),
            None => (Mat4::IDENTITY, 0),
        };
        let params = TemporalParams {
            current_to_previous: current_to_previous.to_cols_array_2d(),
            current_to_world: current_to_world.to_cols_array_2d(),
            depth_tolerance: self.settings.depth_tolerance,
            normal_cos: self.settings.normal_tolerance_deg.to_radians().cos(),
            max_frames: self.settings.frames as f32,
            clamp: u32::from(self.settings.clamp),
            history_valid: valid,
            sample_rays: self.sample_rays,
            _pad: [0; 2],
        };
        queue.write_buffer(&self.params, 0, bytemuck::bytes_of(&params));
        self.previous.set(Some(*view));
        self.frame.set(self.frame.get().wrapping_add(1));
        if let Some(budget) = &self.budget {
            budget.set_frame(queue, self.frame.get());
        }
    }

    /// The ray budget, if the hemisphere rows run under one.
    pub fn ray_budget(&self) -> Option<&RayBudget> {
        self.budget.as_ref()
    }

    /// Records the ray budget's passes for this frame (before the AO pass, which reads their
    /// grants); nothing without a budget.
    pub fn encode_budget(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        inputs: &FrameInputs,
        profiler: Option<&mut PassProfiler>,
    ) {
        let Some(budget) = &self.budget else {
            return;
        };
        let parity = (self.frame.get() % 2) as usize;
        budget.encode(
            device,
            encoder,
            &[
                (0, self.view.as_entire_binding()),
                (1, self.params.as_entire_binding()),
                (2, wgpu::BindingResource::TextureView(inputs.depth)),
                (3, wgpu::BindingResource::TextureView(inputs.normals)),
                (
                    5,
                    wgpu::BindingResource::TextureView(&self.history[1 - parity]),
                ),
            ],
            (inputs.screen.width, inputs.screen.height),
            profiler,
        );
    }

    /// Forgets the history: the next frame starts the average afresh (a camera cut).
    pub fn reset(&self) {
        self.previous.set(None);
    }

    /// Frames since creation (1 for the first); the stochastic maps turn their random choices
    /// by it.
    pub fn frame(&self) -> u32 {
        self.frame.get()
    }

    /// How far the estimators' 4×4 pattern is turned this frame (0 to 15).
    pub fn pattern_offset(&self) -> u32 {
        self.frame.get() % PATTERN_PERIOD
    }

    /// The history image this frame writes (`Rg32Uint`: see [`HistoryTexel::unpack`]).
    pub fn history(&self) -> &wgpu::TextureView {
        &self.history[(self.frame.get() % 2) as usize]
    }
}

impl super::AoFilter for TemporalAccumulation {
    /// Accumulate `input` into `output` (both R32Float, visible size). Timing: `temporal`.
    fn encode(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        inputs: &FrameInputs,
        images: FilterImages,
        profiler: Option<&mut PassProfiler>,
    ) {
        let FilterImages {
            input,
            output,
            history: _,
        } = images;
        let parity = (self.frame.get() % 2) as usize;
        let bind_group = crate::gpu::bind_group(
            device,
            "temporal",
            &self.pipeline.get_bind_group_layout(0),
            &[
                self.view.as_entire_binding(),
                self.params.as_entire_binding(),
                wgpu::BindingResource::TextureView(inputs.depth),
                wgpu::BindingResource::TextureView(inputs.normals),
                wgpu::BindingResource::TextureView(input),
                wgpu::BindingResource::TextureView(&self.history[1 - parity]),
                wgpu::BindingResource::TextureView(output),
                wgpu::BindingResource::TextureView(&self.history[parity]),
            ],
        );
        let timestamp_writes = profiler.map(|p| p.compute_pass("temporal"));
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("temporal"),
            timestamp_writes,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &bind_group, &[]);
        let (w, h) = (inputs.screen.width, inputs.screen.height);
        pass.dispatch_workgroups(w.div_ceil(8), h.div_ceil(8), 1);
    }

    fn set_camera(&self, queue: &wgpu::Queue, view: &FrameView) {
        TemporalAccumulation::set_camera(self, queue, view);
    }

    fn as_temporal(&self) -> Option<&TemporalAccumulation> {
        Some(self)
    }
}
