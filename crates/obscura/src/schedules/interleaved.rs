//! Schedule "interleaved" (`shaders/schedules/interleaved*.wgsl`; docs/AUTHORS_CODE.md §1.7, the
//! seed authors' HBAO+): the depth split into 16 quarter-resolution layers, then the AO of each
//! layer's pixels from that layer alone, written back to the full-resolution image. Any estimator
//! that does not read pyramid levels; the first depth layer is its only source.

use super::{FrameContext, FrameGroups, SourceGroup, Stage};
use crate::bindings::{self, entry, SCHEDULE_DEPTH_LAYERS};
use crate::error::Error;
use crate::estimators::EstimatorPass;
use crate::gpu::PassProfiler;
use crate::shaders;
use crate::sources::SourcePass;
use crate::view::ScreenGeometry;

pub(crate) fn stage() -> Stage {
    Stage {
        label: "interleaved",
        parts: vec![shaders::SCHEDULE_SINGLE, shaders::SCHEDULE_INTERLEAVED],
        source_group: SourceGroup::Resolve,
        schedule_entries: vec![entry::texture_array(SCHEDULE_DEPTH_LAYERS)],
        own_source: true,
        constants: Vec::new(),
        // Written out, `hbao+-interleaved` was 18 % slower on an H100, the others within 1.4 %
        // (BENCHMARKS.md): the loop stays.
        written_out_up_to: 0,
    }
}

pub(crate) struct Interleaved {
    split: wgpu::ComputePipeline,
    split_layout: wgpu::BindGroupLayout,
    pipeline: wgpu::ComputePipeline,
    layers: wgpu::Texture,
    /// All 16 layers, as the split pass writes them and the AO pass reads them.
    layers_view: wgpu::TextureView,
    layers_group: wgpu::BindGroup,
    name: &'static str,
}

impl Interleaved {
    /// `stages`: [`stage`]'s one stage.
    pub fn new(
        device: &wgpu::Device,
        name: &'static str,
        stages: &[Stage],
        frame_layout: &wgpu::BindGroupLayout,
        estimator: &EstimatorPass,
        source: &SourcePass,
        screen: &ScreenGeometry,
    ) -> Self {
        let layers = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("interleaved depth layers"),
            size: wgpu::Extent3d {
                width: screen.full_width().div_ceil(4),
                height: screen.full_height().div_ceil(4),
                depth_or_array_layers: 16,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::R32Float,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::STORAGE_BINDING,
            view_formats: &[],
        });
        let view = layers.create_view(&wgpu::TextureViewDescriptor {
            dimension: Some(wgpu::TextureViewDimension::D2Array),
            ..Default::default()
        });
        let layers_layout =
            bindings::layout(device, "interleaved layers", &stages[0].schedule_entries);
        let layers_group = bindings::group(
            device,
            "interleaved layers",
            &layers_layout,
            &[(
                SCHEDULE_DEPTH_LAYERS,
                wgpu::BindingResource::TextureView(&view),
            )],
        );
        let split_layout = bindings::layout(
            device,
            "interleaved split",
            &[entry::texture(0), entry::storage_texture_r32f_array(1)],
        );
        let split = bindings::compute_pipeline(
            device,
            "interleaved split",
            shaders::SCHEDULE_INTERLEAVED_SPLIT,
            &[],
            &[Some(&split_layout)],
        );
        let pipeline = super::pipeline(
            device,
            &stages[0],
            frame_layout,
            estimator,
            source,
            Some(&layers_layout),
        );
        Self {
            split,
            split_layout,
            pipeline,
            layers,
            layers_view: view,
            layers_group,
            name,
        }
    }

    pub fn encode(
        &self,
        ctx: &FrameContext,
        encoder: &mut wgpu::CommandEncoder,
        mut profiler: Option<&mut PassProfiler>,
    ) -> Result<(), Error> {
        let split_group = bindings::group(
            ctx.device,
            "interleaved split",
            &self.split_layout,
            &[
                (0, wgpu::BindingResource::TextureView(ctx.frame.depth)),
                (1, wgpu::BindingResource::TextureView(&self.layers_view)),
            ],
        );
        let (w, h) = (self.layers.width(), self.layers.height());
        {
            let timestamp_writes = profiler
                .as_deref_mut()
                .map(|p| p.compute_pass("interleave_split"));
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("interleaved split"),
                timestamp_writes,
            });
            pass.set_pipeline(&self.split);
            pass.set_bind_group(0, &split_group, &[]);
            pass.dispatch_workgroups(w.div_ceil(32), h.div_ceil(4), 1);
        }
        let groups = FrameGroups {
            frame: ctx.frame_group,
            estimator: &ctx.estimator.group,
            resolve: None,
            request: None,
        };
        let timestamp_writes = profiler.map(|p| p.compute_pass(self.name));
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(self.name),
            timestamp_writes,
        });
        pass.set_pipeline(&self.pipeline);
        groups.set(&mut pass, SourceGroup::Resolve);
        pass.set_bind_group(bindings::GROUP_SCHEDULE, &self.layers_group, &[]);
        pass.dispatch_workgroups(w.div_ceil(8), h.div_ceil(8), 16);
        Ok(())
    }
}
