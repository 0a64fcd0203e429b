//! Schedule "single pass" (`shaders/schedules/single.wgsl`): one compute pass, every sample of a
//! pixel in one invocation, the source consulted inline; the source prepares before the pass.

use super::{FrameContext, FrameGroups, SourceGroup, Stage};
use crate::error::Error;
use crate::estimators::EstimatorPass;
use crate::frame::workgroups_32x8;
use crate::gpu::PassProfiler;
use crate::shaders;
use crate::sources::SourcePass;

pub(crate) fn stage() -> Stage {
    Stage {
        label: "single pass",
        parts: vec![shaders::SCHEDULE_SINGLE, shaders::SCHEDULE_SINGLE_MAIN],
        source_group: SourceGroup::Resolve,
        schedule_entries: Vec::new(),
        own_source: false,
        constants: Vec::new(),
        // Every sample count the estimators allow (schedules::writes_out_sample_loops decides by row).
        written_out_up_to: 32,
    }
}

pub(crate) struct Single {
    pipeline: wgpu::ComputePipeline,
    /// The pass's name in timings: the technique's.
    name: &'static str,
}

impl Single {
    /// `stages`: [`stage`]'s one stage.
    pub fn new(
        device: &wgpu::Device,
        name: &'static str,
        stages: &[Stage],
        frame_layout: &wgpu::BindGroupLayout,
        estimator: &EstimatorPass,
        source: &SourcePass,
    ) -> Self {
        Self {
            pipeline: super::pipeline(device, &stages[0], frame_layout, estimator, source, None),
            name,
        }
    }

    pub fn encode(
        &self,
        ctx: &FrameContext,
        encoder: &mut wgpu::CommandEncoder,
        mut profiler: Option<&mut PassProfiler>,
    ) -> Result<(), Error> {
        let source = ctx.source;
        source.begin_frame(ctx.device, encoder, profiler.as_deref_mut());
        source.prepare(
            ctx.device,
            encoder,
            ctx.frame,
            ctx.gbuffer_z,
            profiler.as_deref_mut(),
        );
        let resolve = source.resolve_group(ctx.device, ctx.frame)?;
        let groups = FrameGroups {
            frame: ctx.frame_group,
            estimator: &ctx.estimator.group,
            resolve: resolve.as_ref(),
            request: None,
        };
        let timestamp_writes = profiler.map(|p| p.compute_pass(self.name));
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(self.name),
            timestamp_writes,
        });
        pass.set_pipeline(&self.pipeline);
        groups.set(&mut pass, SourceGroup::Resolve);
        let (x, y, z) = workgroups_32x8(ctx.frame.screen.width, ctx.frame.screen.height);
        pass.dispatch_workgroups(x, y, z);
        Ok(())
    }
}
