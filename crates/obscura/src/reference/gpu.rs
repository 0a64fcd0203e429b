//! The ground truth on the GPU (`shaders/reference/reference.wgsl`): the same two models as
//! [`super::ground_truth`] through the compute BVH traversal, held to the CPU oracle by tests.

use super::ground_truth::{ReferenceModel, ReferenceSettings};
use crate::bindings::{
    self, entry, FRAME_VIEW, GROUP_ESTIMATOR, GROUP_FRAME, GROUP_SCHEDULE, GROUP_SOURCE,
    REFERENCE_OUT, REFERENCE_PARAMS,
};
use crate::bvh::gpu::GpuBvh;
use crate::bvh::Bvh;
use crate::error::Error;
use crate::estimators::vao::VaoSettings;
use crate::gpu::Gpu;
use crate::raster::gpu_scene::GpuScene;
use crate::scene::Scene;
use crate::shaders;
use crate::sources::column_rays::{self, ColumnRays};
use crate::view::FrameView;
use wgpu::util::DeviceExt;

/// Hemisphere rays per pixel in one dispatch (progress is reported between batches, and no
/// single dispatch runs long enough to trip a driver watchdog).
const BATCH_SPP: u32 = 64;

/// The reference image of the visible `view.width × view.height` (row-major), and the number of
/// rays traced (primary rays plus hemisphere rays or traced VAO sample columns, as counted on the
/// CPU: an upper bound for the `vao` model, whose samples snapping to their own pixel trace none).
/// `progress(done, total)` is called after each batch. One image: for many views of one scene,
/// make a [`GpuReferenceTracer`] once and trace each view with it.
pub fn render_reference_gpu(
    gpu: &Gpu,
    scene: &Scene,
    bvh: &Bvh,
    view: FrameView,
    settings: &ReferenceSettings,
    progress: &dyn Fn(u32, u32),
) -> Result<(Vec<f32>, u64), Error> {
    GpuReferenceTracer::new(gpu, scene, bvh, settings.vao)?.trace(view, settings, progress)
}

/// The reference tracer of one scene on one device: the scene and its BVH uploaded and the
/// pipeline compiled once, then any number of views traced ([`Self::trace`]). A dataset's views
/// of one scene share it, so each view costs its rays alone, not an upload and a shader
/// compilation as well.
pub struct GpuReferenceTracer<'a> {
    gpu: &'a Gpu,
    /// The VAO parameters the pipeline was built with (its constants).
    vao: VaoSettings,
    estimator: crate::estimators::EstimatorPass,
    frame_layout: wgpu::BindGroupLayout,
    output_layout: wgpu::BindGroupLayout,
    pipeline: wgpu::ComputePipeline,
    rays: ColumnRays,
}

impl<'a> GpuReferenceTracer<'a> {
    /// Uploads `scene` and `bvh` to `gpu` and builds the pipeline for the VAO parameters `vao`
    /// (the `vao` models' kernel; the hemisphere model reads only its radius, per trace).
    pub fn new(
        gpu: &'a Gpu,
        scene: &Scene,
        bvh: &Bvh,
        vao: VaoSettings,
    ) -> Result<GpuReferenceTracer<'a>, Error> {
        // Pipelines an earlier constructor on this Gpu made are reused (gpu::memo).
        let _kept = gpu.keeping();
        let device = &gpu.device;
        let gpu_scene = GpuScene::new(device, &gpu.queue, scene, &device.limits())?;
        let gpu_bvh = GpuBvh::new(device, bvh, scene)?;
        // The VAO estimator through the single-pass loop over the all-layers source
        // (reference.wgsl).
        let (section, inputs) = crate::settings::AoSettings {
            vao,
            ..Default::default()
        }
        .estimator_inputs();
        let estimator = crate::estimators::EstimatorPass::new(
            device,
            &gpu.queue,
            ("vao", &crate::estimators::vao::MODULE),
            (&section, &inputs),
            0.0, // the ground truth's R is never capped
        );
        let mut parts = crate::schedules::ESTIMATOR_PRELUDE.to_vec();
        parts.push(estimator.wgsl);
        parts.extend(column_rays::trace_wgsl());
        parts.extend([
            shaders::SOURCE_ALL_LAYERS,
            shaders::SCHEDULE_SINGLE,
            shaders::HASH,
            shaders::HEMISPHERE,
            shaders::VERTEX_NORMAL,
            shaders::REFERENCE,
        ]);
        let frame_layout =
            bindings::layout(device, "reference view", &[entry::uniform(FRAME_VIEW)]);
        let source_layout = bindings::layout(device, "column rays", &column_rays::layout_entries());
        let output_layout = bindings::layout(
            device,
            "reference output",
            &[
                entry::uniform(REFERENCE_PARAMS),
                entry::storage(REFERENCE_OUT, false),
            ],
        );
        let pipeline = bindings::compute_pipeline(
            device,
            "reference",
            &shaders::compose(&parts),
            &estimator.constants,
            &bindings::by_group(&[
                (GROUP_FRAME, &frame_layout),
                (GROUP_ESTIMATOR, &estimator.layout),
                (GROUP_SOURCE, &source_layout),
                (GROUP_SCHEDULE, &output_layout),
            ]),
        );
        let rays = ColumnRays::new(device, &source_layout, &gpu_scene, &gpu_bvh);
        Ok(GpuReferenceTracer {
            gpu,
            vao,
            estimator,
            frame_layout,
            output_layout,
            pipeline,
            rays,
        })
    }

    /// Traces `view` with `settings` (whose `vao` must be the one this tracer was made with):
    /// the image and the rays counted, as [`render_reference_gpu`] returns them.
    pub fn trace(
        &self,
        view: FrameView,
        settings: &ReferenceSettings,
        progress: &dyn Fn(u32, u32),
    ) -> Result<(Vec<f32>, u64), Error> {
        if settings.vao != self.vao {
            return Err(Error::Input(
                "the reference tracer was built for other VAO parameters: make a \
                 GpuReferenceTracer for these settings"
                    .into(),
            ));
        }
        let (gpu, device) = (self.gpu, &self.gpu.device);
        let (estimator, rays) = (&self.estimator, &self.rays);
        let (frame_layout, output_layout) = (&self.frame_layout, &self.output_layout);
        rays.set_camera(&gpu.queue, view.view_matrix().inverse(), view.near);
        // `vao-mean`: one dispatch per turn of the 4×4 pattern (View pattern_offset), each
        // adding a sixteenth of its AO.
        let view_buffer = |pattern_offset: u32| {
            let mut uniform = view.screen().uniform();
            uniform.pattern_offset = pattern_offset;
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("view"),
                contents: bytemuck::bytes_of(&uniform),
                usage: wgpu::BufferUsages::UNIFORM,
            })
        };
        let pixels = u64::from(view.width) * u64::from(view.height);
        let output = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("reference"),
            size: pixels * 4,
            usage: wgpu::BufferUsages::STORAGE
                | wgpu::BufferUsages::COPY_SRC
                | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        // Batches: (first ray, rays) of the hemisphere, or (pattern offset, 0) of the vao models.
        let (model, batches) = match settings.model {
            ReferenceModel::Vao => (0u32, vec![(0, 0)]),
            ReferenceModel::VaoMean => (0u32, (0..16).map(|offset| (offset, 0)).collect()),
            ReferenceModel::Hemisphere => (
                1,
                (0..settings.spp)
                    .step_by(BATCH_SPP as usize)
                    .map(|start| (start, BATCH_SPP.min(settings.spp - start)))
                    .collect(),
            ),
        };
        let weight = 1.0 / batches.len() as f32;
        for (done, &(spp_start, spp_count)) in batches.iter().enumerate() {
            let offset = if model == 0 { spp_start } else { 0 };
            let view_buffer = view_buffer(offset);
            let frame_group = bindings::group(
                device,
                "reference view",
                frame_layout,
                &[(FRAME_VIEW, view_buffer.as_entire_binding())],
            );
            let reference = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("reference params"),
                contents: bytemuck::cast_slice(&[
                    model,
                    spp_start,
                    spp_count,
                    settings.spp,
                    u32::from(settings.falloff),
                    settings.seed as u32,
                    // The vao models' share of each dispatch (1, or 1/16 for vao-mean).
                    weight.to_bits(),
                    0,
                ]),
                usage: wgpu::BufferUsages::UNIFORM,
            });
            let output_group = bindings::group(
                device,
                "reference output",
                output_layout,
                &[
                    (REFERENCE_PARAMS, reference.as_entire_binding()),
                    (REFERENCE_OUT, output.as_entire_binding()),
                ],
            );
            let rays_group = rays.group(device);
            let mut encoder = device.create_command_encoder(&Default::default());
            if done == 0 {
                encoder.clear_buffer(&output, 0, None);
                encoder.clear_buffer(&rays.stack_overflows, 0, None);
            }
            {
                let mut pass = encoder.begin_compute_pass(&Default::default());
                pass.set_pipeline(&self.pipeline);
                pass.set_bind_group(GROUP_FRAME, &frame_group, &[]);
                pass.set_bind_group(GROUP_ESTIMATOR, &estimator.group, &[]);
                pass.set_bind_group(GROUP_SOURCE, &rays_group, &[]);
                pass.set_bind_group(GROUP_SCHEDULE, &output_group, &[]);
                pass.dispatch_workgroups(view.width.div_ceil(8), view.height.div_ceil(8), 1);
            }
            gpu.queue.submit([encoder.finish()]);
            gpu.finish()?;
            progress(done as u32 + 1, batches.len() as u32);
        }
        let staging = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("reference readback"),
            size: pixels * 4 + 4,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        let mut encoder = device.create_command_encoder(&Default::default());
        encoder.copy_buffer_to_buffer(&output, 0, &staging, 0, pixels * 4);
        encoder.copy_buffer_to_buffer(&rays.stack_overflows, 0, &staging, pixels * 4, 4);
        gpu.queue.submit([encoder.finish()]);
        let bytes = crate::gpu::read_buffer(gpu, &staging)?;
        let values: Vec<f32> = bytemuck::pod_collect_to_vec(&bytes[..pixels as usize * 4]);
        let overflows =
            u32::from_le_bytes(bytes[pixels as usize * 4..].try_into().expect("4 bytes"));
        if overflows > 0 {
            log::warn!("{overflows} reference rays overflowed the GPU BVH stack; their results may be incomplete");
        }
        let image = match settings.model {
            ReferenceModel::Vao | ReferenceModel::VaoMean => values,
            ReferenceModel::Hemisphere => values
                .iter()
                .map(|&occlusion| 1.0 - occlusion / settings.spp as f32)
                .collect(),
        };
        Ok((image, pixels * settings.rays_per_pixel()))
    }
}
