//! Schedule "multi-view" (seed 001 §3.4, Algorithm 3; `shaders/schedules/multiview/`): surfaces
//! seen at a grazing angle leave almost no pixels in the camera's depth, so their occlusion goes
//! missing. A second view beside the camera sees them at an angle. The estimator runs twice, per
//! pixel of the camera:
//! 1. the single pass in the camera's view over the row's source (the stochastic depth map);
//! 2. again in the second view, over a second stochastic depth map rasterised from it. That map
//!    keeps every layer, the first visible one included.
//!
//! Each pixel keeps the larger occlusion of the two (the lower AO). Placement of the second view:
//! [`MultiviewSettings`] (the paper gives no numbers).

use super::{single, FrameContext, Stage};
use crate::bindings::{self, entry, GROUP_ESTIMATOR, GROUP_FRAME, GROUP_SCHEDULE, GROUP_SOURCE};
use crate::error::Error;
use crate::estimators::EstimatorPass;
use crate::frame::{workgroups_32x8, FrameInputs};
use crate::gpu::{Gpu, PassProfiler};
use crate::raster::gpu_scene::GpuScene;
use crate::settings::{AoSettings, MultiviewSettings, Resolution};
use crate::shaders;
use crate::sources::stochastic_depth::{bindings_wgsl, read_layout_entries, StochasticDepthMap};
use crate::sources::SourcePass;
use crate::view::{FrameView, ScreenGeometry};
use glam::{Mat4, Quat, Vec3};

/// `MultiviewFrame` of `shaders/schedules/multiview/point.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct MultiviewFrame {
    main: crate::view::ViewUniform,
    to_second: [[f32; 4]; 4],
}

/// The widest field of view the second view takes (degrees).
const MAX_FOV_DEG: f32 = 150.0;

/// The second view of `main` (seed 001 §3.4; [`MultiviewSettings`]): the camera swung by `angle`
/// about its up axis around the point `focus` ahead of it, looking at that point, its field of
/// view widened by twice the angle (at most 150°), at the camera's resolution or half of it.
/// `focus` defaults to the distance along the view axis to the centre of `bounds` (at least the
/// near plane).
pub fn second_view(
    main: &FrameView,
    settings: &MultiviewSettings,
    bounds: (Vec3, Vec3),
) -> FrameView {
    let camera = main.camera;
    let forward = (camera.target - camera.eye).normalize();
    let centre = 0.5 * (bounds.0 + bounds.1);
    let focus = settings
        .focus
        .unwrap_or_else(|| (centre - camera.eye).dot(forward))
        .max(main.near);
    let pivot = camera.eye + forward * focus;
    let turn = Quat::from_axis_angle(camera.up.normalize(), settings.angle.to_radians());
    let second = crate::scene::Camera {
        eye: pivot + turn * (camera.eye - pivot),
        target: pivot,
        up: camera.up,
        fov_y_deg: (camera.fov_y_deg + 2.0 * settings.angle).min(MAX_FOV_DEG),
    };
    let view = FrameView::new(second, main.width, main.height, main.guard_band, main.near);
    match settings.resolution {
        Resolution::Full => view,
        // Even sizes: checked when the schedule was made (ScreenGeometry::half).
        Resolution::Half => view.half(),
    }
}

pub(crate) struct Multiview {
    /// Pass 1: the single pass in the camera's view.
    main: single::Single,
    /// Pass 2: the estimator in the second view (point.wgsl, lookup.wgsl, main.wgsl).
    second: wgpu::ComputePipeline,
    /// The second view's stochastic depth map (every layer kept).
    map: StochasticDepthMap,
    /// Bound as the second map's "first layer": the map keeps every layer and never reads it.
    no_first_layer: wgpu::TextureView,
    second_view: wgpu::Buffer,
    frame: wgpu::Buffer,
    /// The second view's group 2 (the frame uniform and the second map) and group 3 (the
    /// camera's AO), made once.
    source_group: wgpu::BindGroup,
    main_ao_group: wgpu::BindGroup,
    frame_layout: wgpu::BindGroupLayout,
    /// The camera's own AO, before the second view's pass takes the minimum.
    main_ao: wgpu::TextureView,
    settings: MultiviewSettings,
    bounds: (Vec3, Vec3),
    second_screen: ScreenGeometry,
    /// The estimator's debug image (`render --debug-out`): the camera's pass only, as it is.
    estimator_debug: bool,
}

impl Multiview {
    /// `screen`: the camera's geometry (the row's technique runs there); `scene`: the triangles
    /// the second map is rasterised from.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        gpu: &Gpu,
        settings: &AoSettings,
        screen: &ScreenGeometry,
        scene: &GpuScene,
        frame_layout: &wgpu::BindGroupLayout,
        estimator: &EstimatorPass,
        source: &SourcePass,
        stages: &[Stage],
        name: &'static str,
        estimator_debug: bool,
    ) -> Result<Self, Error> {
        let device = &gpu.device;
        if screen.orthographic {
            return Err(Error::Input(
                "the multi-view schedule needs a perspective camera".into(),
            ));
        }
        let second_screen = match settings.multiview.resolution {
            Resolution::Full => *screen,
            Resolution::Half => screen.half()?,
        };
        // The second view's map has no band of its own: its samples are placed in its frame.
        let map = StochasticDepthMap::new(
            &gpu.adapter,
            device,
            &settings.stochastic_depth,
            settings.peel_separation,
            (second_screen.full_width(), second_screen.full_height(), 0),
            scene,
            None,
        )?
        .keeping_every_layer()
        .timed_as(
            "multiview_sd_clear",
            "multiview_sd_reset",
            "multiview_sd_cull",
            "multiview_sd_map",
        );
        let mut source_entries = vec![entry::uniform(bindings::SOURCE_MULTIVIEW)];
        source_entries.extend(read_layout_entries());
        let source_layout = bindings::layout(device, "multiview second view", &source_entries);
        let main_ao_layout = bindings::layout(device, "multiview camera ao", &[entry::texture(0)]);
        let mut parts = super::ESTIMATOR_PRELUDE.to_vec();
        // The second view's shading point in place of the frame's own.
        parts.retain(|p| *p != shaders::FRAME_POINT);
        parts.push(shaders::MULTIVIEW_POINT);
        parts.push(estimator.wgsl);
        let sd_bindings = bindings_wgsl(map.layout(), 0);
        parts.extend([
            sd_bindings.as_str(),
            shaders::STOCHASTIC_DEPTH_SAMPLES,
            shaders::MULTIVIEW_LOOKUP,
            shaders::SCHEDULE_SINGLE,
            shaders::MULTIVIEW_MAIN,
        ]);
        let second = bindings::compute_pipeline(
            device,
            "multiview second view",
            &shaders::compose(&parts),
            &estimator.constants,
            &bindings::by_group(&[
                (GROUP_FRAME, frame_layout),
                (GROUP_ESTIMATOR, &estimator.layout),
                (GROUP_SOURCE, &source_layout),
                (GROUP_SCHEDULE, &main_ao_layout),
            ]),
        );
        let uniform = |label, size: usize| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: size as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        let texture = |label, width, height, usage| {
            crate::gpu::texture_2d(
                device,
                label,
                width,
                height,
                wgpu::TextureFormat::R32Float,
                usage,
            )
        };
        let frame = uniform("multiview frame", std::mem::size_of::<MultiviewFrame>());
        let main_ao = texture(
            "multiview camera ao",
            screen.width,
            screen.height,
            wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING,
        )
        .create_view(&Default::default());
        // What the second view's pass binds besides group 0 is the same every frame.
        let mut resources = vec![(bindings::SOURCE_MULTIVIEW, frame.as_entire_binding())];
        resources.extend(map.read_resources());
        let source_group =
            bindings::group(device, "multiview second view", &source_layout, &resources);
        let main_ao_group = bindings::group(
            device,
            "multiview camera ao",
            &main_ao_layout,
            &[(0, wgpu::BindingResource::TextureView(&main_ao))],
        );
        Ok(Self {
            main: single::Single::new(device, name, stages, frame_layout, estimator, source),
            second,
            map,
            no_first_layer: texture("no first layer", 1, 1, wgpu::TextureUsages::TEXTURE_BINDING)
                .create_view(&Default::default()),
            second_view: uniform(
                "multiview second view",
                std::mem::size_of::<crate::view::ViewUniform>(),
            ),
            frame,
            source_group,
            main_ao_group,
            frame_layout: frame_layout.clone(),
            main_ao,
            settings: settings.multiview,
            bounds: scene.bounds,
            second_screen,
            estimator_debug,
        })
    }

    /// The camera of the coming frame: places the second view and uploads both.
    pub fn set_camera(&self, queue: &wgpu::Queue, view: &FrameView) {
        let second = second_view(view, &self.settings, self.bounds);
        queue.write_buffer(
            &self.second_view,
            0,
            bytemuck::bytes_of(&second.screen().uniform()),
        );
        let to_second: Mat4 = second.view_matrix() * view.view_matrix().inverse();
        let frame = MultiviewFrame {
            main: view.screen().uniform(),
            to_second: to_second.to_cols_array_2d(),
        };
        queue.write_buffer(&self.frame, 0, bytemuck::bytes_of(&frame));
        self.map.set_camera(queue, &second, 0);
    }

    pub fn encode(
        &self,
        ctx: &FrameContext,
        encoder: &mut wgpu::CommandEncoder,
        mut profiler: Option<&mut PassProfiler>,
    ) -> Result<(), Error> {
        let device = ctx.device;
        if self.estimator_debug {
            return self.main.encode(ctx, encoder, profiler);
        }
        // Pass 1 into the camera's own AO image.
        let main_group = ctx.frame.group(
            device,
            &self.frame_layout,
            &self.main_ao,
            ctx.bent,
            ctx.ray_grant,
        );
        let main_ctx = FrameContext {
            frame_group: &main_group,
            ..*ctx
        };
        self.main
            .encode(&main_ctx, encoder, profiler.as_deref_mut())?;
        // The second view's map, every layer.
        self.map.render(
            device,
            encoder,
            &self.no_first_layer,
            None,
            None,
            profiler.as_deref_mut(),
        );
        // Pass 2: group 0 is the camera's depth and normals under the second view's geometry.
        let second_frame = FrameInputs {
            depth: ctx.frame.depth,
            normals: ctx.frame.normals,
            second_layer: None,
            screen: self.second_screen,
            view: &self.second_view,
        };
        let frame_group = second_frame.group(
            device,
            &self.frame_layout,
            ctx.output,
            ctx.bent,
            ctx.ray_grant,
        );
        let label = "multiview_second";
        let timestamp_writes = profiler.map(|p| p.compute_pass(label));
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(label),
            timestamp_writes,
        });
        pass.set_pipeline(&self.second);
        pass.set_bind_group(GROUP_FRAME, &frame_group, &[]);
        pass.set_bind_group(GROUP_ESTIMATOR, &ctx.estimator.group, &[]);
        pass.set_bind_group(GROUP_SOURCE, &self.source_group, &[]);
        pass.set_bind_group(GROUP_SCHEDULE, &self.main_ao_group, &[]);
        let (x, y, z) = workgroups_32x8(ctx.frame.screen.width, ctx.frame.screen.height);
        pass.dispatch_workgroups(x, y, z);
        Ok(())
    }
}
