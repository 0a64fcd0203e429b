//! Schedule "two-phase" (seed 000 §3.8 RT-SVAO, §3.9 SD-SVAO): phase 1 takes every sample from the
//! source's first look (the depth buffer) and flags, per pixel, the samples the source must still
//! resolve; phase 2 resolves only those. Between the phases the source prepares what phase 2 reads
//! (SD-SVAO: the stochastic depth map, rasterised only at the pixels phase 1 requested). The paper
//! needed a hardware stencil and a ray-tracing pipeline against the divergence; in compute, phase 2
//! either walks every pixel and returns at once for unflagged ones (dense), or reads a work list of
//! flagged pixels compacted by phase 1 and is dispatched indirectly. Same arithmetic as the single
//! pass, so it gives the same image (`shaders/schedules/two_phase*.wgsl`). Any estimator with at
//! most 32 samples (one mask bit each) runs in it.

use super::{FrameContext, FrameGroups, SourceGroup, Stage};
use crate::bindings::{
    self, entry, GROUP_SCHEDULE, INDIRECT_DISPATCH, INDIRECT_WORK_LIST, SCHEDULE_PIXELS,
    SCHEDULE_WORK_LIST,
};
use crate::error::Error;
use crate::estimators::EstimatorPass;
use crate::frame::workgroups_32x8;
use crate::gpu::PassProfiler;
use crate::shaders;
use crate::sources::SourcePass;
use crate::view::ScreenGeometry;

/// Bytes per visible pixel of phase 1's results (`TwoPhasePixel` in the WGSL: the mask and the
/// estimator's three-word partial state).
const PIXEL_BYTES: u64 = 16;

/// Where the work list's pixel indices start in its buffer, after their count (`WorkList` in
/// schedules/work_list.wgsl: `@align(128)`).
const WORK_ITEMS_OFFSET: u64 = 128;

/// Workgroups (x, y) for `threads` threads of 64 per group, in rows of at most 65535 workgroups
/// (the per-dimension dispatch limit; a 4K image needs 129,600 groups). Phase 2 recovers the
/// thread index as `x + y · 65535 · 64`.
pub fn dispatch_rows(threads: u32) -> (u32, u32) {
    let groups = threads.div_ceil(64);
    (groups.clamp(1, 65535), groups.div_ceil(65535).max(1))
}

fn schedule_entries(read_only: bool) -> Vec<wgpu::BindGroupLayoutEntry> {
    vec![
        entry::storage(SCHEDULE_PIXELS, read_only),
        entry::storage(SCHEDULE_WORK_LIST, read_only),
    ]
}

/// Phase 1 and phase 2; `compact`: phase 2 over a work list with an indirect dispatch.
pub(crate) fn stages(compact: bool) -> Vec<Stage> {
    let constants = vec![("COMPACT", f64::from(u8::from(compact)))];
    vec![
        Stage {
            label: "two-phase phase 1",
            parts: vec![
                shaders::SCHEDULE_WORK_LIST,
                shaders::SCHEDULE_TWO_PHASE,
                shaders::SCHEDULE_TWO_PHASE_1,
            ],
            source_group: SourceGroup::Request,
            schedule_entries: schedule_entries(false),
            own_source: false,
            constants: constants.clone(),
            // Phase 1 written out (lookups only; H100, BENCHMARKS.md): GTAO-VB's 8 samples 13 %
            // faster, VAO's 1–7 %; HBAO+'s and SSAO's 32, 45 KB of code, 1 % and 6 % slower.
            written_out_up_to: 16,
        },
        Stage {
            label: "two-phase phase 2",
            parts: vec![
                shaders::SCHEDULE_WORK_LIST,
                shaders::SCHEDULE_TWO_PHASE,
                shaders::SCHEDULE_TWO_PHASE_2,
            ],
            source_group: SourceGroup::Resolve,
            schedule_entries: schedule_entries(true),
            own_source: false,
            constants,
            written_out_up_to: 0,
        },
    ]
}

/// The indirect-arguments pass's WGSL and group-0 layout entries.
pub(crate) fn indirect_stage() -> (String, Vec<wgpu::BindGroupLayoutEntry>) {
    (
        shaders::compose(&[
            shaders::SCHEDULE_WORK_LIST,
            shaders::SCHEDULE_TWO_PHASE_INDIRECT,
        ]),
        vec![
            entry::storage(INDIRECT_WORK_LIST, true),
            entry::storage(INDIRECT_DISPATCH, false),
        ],
    )
}

pub(crate) struct TwoPhase {
    compact: bool,
    phase1: wgpu::ComputePipeline,
    phase2: wgpu::ComputePipeline,
    indirect: wgpu::ComputePipeline,
    pixels: wgpu::Buffer,
    /// The count of flagged pixels, then their indices (`WorkList` in work_list.wgsl).
    work_list: wgpu::Buffer,
    dispatch: wgpu::Buffer,
    phase1_group: wgpu::BindGroup,
    phase2_group: wgpu::BindGroup,
    indirect_group: wgpu::BindGroup,
}

impl TwoPhase {
    /// `stages`: [`stages`]`(compact)`, phase 1 then phase 2.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        device: &wgpu::Device,
        compact: bool,
        stages: &[Stage],
        frame_layout: &wgpu::BindGroupLayout,
        estimator: &EstimatorPass,
        source: &SourcePass,
        screen: &ScreenGeometry,
    ) -> Result<Self, crate::gpu::GpuError> {
        let layouts: Vec<_> = stages
            .iter()
            .map(|s| bindings::layout(device, s.label, &s.schedule_entries))
            .collect();
        let [phase1, phase2] = [0, 1].map(|i| {
            let layout = Some(&layouts[i]);
            super::pipeline(device, &stages[i], frame_layout, estimator, source, layout)
        });
        let (indirect_source, indirect_entries) = indirect_stage();
        let indirect_layout = bindings::layout(device, "two-phase indirect", &indirect_entries);
        let indirect = bindings::compute_pipeline(
            device,
            "two-phase indirect",
            &indirect_source,
            &[],
            &[Some(&indirect_layout)],
        );
        let pixels = u64::from(screen.width) * u64::from(screen.height);
        let limits = device.limits();
        crate::gpu::check_storage_size(&limits, "two-phase pixels", pixels * PIXEL_BYTES)?;
        crate::gpu::check_storage_size(
            &limits,
            "two-phase work list",
            WORK_ITEMS_OFFSET + (pixels.max(1) * 4).next_multiple_of(WORK_ITEMS_OFFSET),
        )?;
        let buffer = |label, size: u64, usage| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: size.max(4),
                usage: wgpu::BufferUsages::STORAGE | usage,
                mapped_at_creation: false,
            })
        };
        let records = buffer(
            "two-phase pixels",
            pixels * PIXEL_BYTES,
            wgpu::BufferUsages::COPY_SRC,
        );
        // The count and the list in one buffer: one storage binding fewer, so that phase 2 of
        // the ray-traced rows (the BVH's five buffers and the source's own) stays within
        // WebGPU's default of 8 storage buffers per stage (tests/it/webgpu_limits.rs).
        // WGSL sizes the struct in whole multiples of its 128-byte alignment, and a binding must
        // hold at least one: 256 bytes for one pixel.
        let work_list = buffer(
            "two-phase work list",
            WORK_ITEMS_OFFSET + (pixels.max(1) * 4).next_multiple_of(WORK_ITEMS_OFFSET),
            wgpu::BufferUsages::COPY_DST,
        );
        let dispatch = buffer("two-phase dispatch", 12, wgpu::BufferUsages::INDIRECT);
        let work = |layout| {
            bindings::group(
                device,
                "two-phase work",
                layout,
                &[
                    (SCHEDULE_PIXELS, records.as_entire_binding()),
                    (SCHEDULE_WORK_LIST, work_list.as_entire_binding()),
                ],
            )
        };
        let indirect_group = bindings::group(
            device,
            "two-phase indirect",
            &indirect_layout,
            &[
                (INDIRECT_WORK_LIST, work_list.as_entire_binding()),
                (INDIRECT_DISPATCH, dispatch.as_entire_binding()),
            ],
        );
        Ok(Self {
            compact,
            phase1_group: work(&layouts[0]),
            phase2_group: work(&layouts[1]),
            indirect_group,
            phase1,
            phase2,
            indirect,
            pixels: records,
            work_list,
            dispatch,
        })
    }

    /// Phase 1's per-pixel records (16 bytes each, the sample bit mask first).
    pub fn records(&self) -> &wgpu::Buffer {
        &self.pixels
    }

    pub fn encode(
        &self,
        ctx: &FrameContext,
        encoder: &mut wgpu::CommandEncoder,
        mut profiler: Option<&mut PassProfiler>,
    ) -> Result<(), Error> {
        let FrameContext {
            device,
            frame,
            frame_group,
            estimator,
            source,
            ..
        } = *ctx;
        encoder.clear_buffer(&self.work_list, 0, Some(4));
        source.begin_frame(device, encoder, profiler.as_deref_mut());
        let request = source.request_group(device, ctx.visible_triangles);
        let mut groups = FrameGroups {
            frame: frame_group,
            estimator: &estimator.group,
            resolve: None,
            request: request.as_ref(),
        };
        {
            let timestamp_writes = profiler
                .as_deref_mut()
                .map(|p| p.compute_pass("svao_phase1"));
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("two-phase phase 1"),
                timestamp_writes,
            });
            pass.set_pipeline(&self.phase1);
            groups.set(&mut pass, SourceGroup::Request);
            pass.set_bind_group(GROUP_SCHEDULE, &self.phase1_group, &[]);
            let (x, y, z) = workgroups_32x8(frame.screen.width, frame.screen.height);
            pass.dispatch_workgroups(x, y, z);
        }
        if self.compact {
            let timestamp_writes = profiler
                .as_deref_mut()
                .map(|p| p.compute_pass("svao_indirect"));
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("two-phase indirect"),
                timestamp_writes,
            });
            pass.set_pipeline(&self.indirect);
            pass.set_bind_group(0, &self.indirect_group, &[]);
            pass.dispatch_workgroups(1, 1, 1);
        }
        source.prepare(
            device,
            encoder,
            frame,
            ctx.gbuffer_z,
            profiler.as_deref_mut(),
        );
        let resolve = source.resolve_group(device, frame)?;
        groups.resolve = resolve.as_ref();
        let timestamp_writes = profiler.map(|p| p.compute_pass("svao_phase2"));
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("two-phase phase 2"),
            timestamp_writes,
        });
        pass.set_pipeline(&self.phase2);
        groups.set(&mut pass, SourceGroup::Resolve);
        pass.set_bind_group(GROUP_SCHEDULE, &self.phase2_group, &[]);
        if self.compact {
            pass.dispatch_workgroups_indirect(&self.dispatch, 0);
        } else {
            let (x, y) = dispatch_rows(frame.screen.width * frame.screen.height);
            pass.dispatch_workgroups(x, y, 1);
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::dispatch_rows;

    #[test]
    fn dispatch_rows_cover_every_thread_within_the_limit() {
        for threads in [
            1,
            64,
            65,
            65535 * 64,
            65535 * 64 + 1,
            3840 * 2160,
            7680 * 4320,
        ] {
            let (x, y) = dispatch_rows(threads);
            assert!(x <= 65535 && y <= 65535);
            // Thread (gx, gy) is index gx + gy·65535·64: with more than one row every row is full,
            // so the indices reach x·64 + (y − 1)·65535·64 − 1 ≥ threads − 1.
            assert!(y == 1 || x == 65535);
            let reachable = u64::from(x) * 64 + u64::from(y - 1) * 65535 * 64;
            assert!(reachable >= u64::from(threads), "{threads}: ({x}, {y})");
        }
    }
}
