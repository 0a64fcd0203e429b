//! Stenciled VAO (seed 000 §3.8 RT-SVAO, §3.9 SD-SVAO): phase 1 takes every sample from the depth
//! buffer and flags, per pixel, the samples the hidden-depth source must still resolve; phase 2
//! resolves only those. For SD-SVAO phase 1 also marks each flagged sample's pixel in an SD-request
//! mask, and the stochastic depth map is rasterised between the phases only there (stencil). The
//! paper needed a hardware stencil and a ray-tracing pipeline against the divergence;
//! in compute, phase 2 either walks every pixel and returns at once for unflagged ones (`dense`),
//! or reads a work list of flagged pixels compacted by phase 1 and is dispatched indirectly.
//! Same arithmetic as the single pass, so it gives the same image (`shaders/svao_phase*.wgsl`).

use super::vao::{frame_resources, params_buffer, vao_source, Hidden, HiddenSource};
use super::{workgroups_32x8, AoKernel, FrameInputs};
use crate::gpu::PassProfiler;
use crate::hidden::HiddenDepth;
use crate::raster::stochastic_depth::StochasticDepthMap;
use crate::settings::VaoSettings;
use crate::shaders;
use crate::view::{FrameView, ScreenGeometry};

/// Bytes per visible pixel of phase 1's results (`SvaoPixel` in the WGSL).
const PIXEL_BYTES: u64 = 16;

/// Workgroups (x, y) for `threads` threads of 64 per group, in rows of at most 65535 workgroups
/// (the per-dimension dispatch limit; a 4K image needs 129,600 groups). Phase 2 recovers the
/// thread index as `x + y · 65535 · 64`.
pub fn dispatch_rows(threads: u32) -> (u32, u32) {
    let groups = threads.div_ceil(64);
    (groups.clamp(1, 65535), groups.div_ceil(65535).max(1))
}

pub struct SvaoKernel {
    phase1: wgpu::ComputePipeline,
    phase2: wgpu::ComputePipeline,
    indirect: wgpu::ComputePipeline,
    params: wgpu::Buffer,
    view: wgpu::Buffer,
    hidden: Hidden,
    name: &'static str,
    compact: bool,
    pixels: wgpu::Buffer,
    work_count: wgpu::Buffer,
    work_list: wgpu::Buffer,
    dispatch: wgpu::Buffer,
    /// SD-SVAO: the SD-request mask, one u32 per framebuffer pixel (seed 000 §3.9).
    sd_request: Option<wgpu::Buffer>,
}

impl SvaoKernel {
    /// Two-phase VAO for a visible image of `screen`, resolving flagged samples with column rays
    /// (`rt-svao`) or a stochastic depth map limited to the requested pixels (`sd-svao`, made
    /// with `requested`). `compact`: phase 2 over a work list with an indirect dispatch, else over
    /// every pixel with an early return.
    pub fn new(
        device: &wgpu::Device,
        settings: &VaoSettings,
        view: &wgpu::Buffer,
        hidden: HiddenSource,
        screen: &ScreenGeometry,
        compact: bool,
    ) -> Self {
        let (kind, sd_layout, name) = match &hidden {
            HiddenSource::StochasticDepth(map) => {
                (HiddenDepth::StochasticDepth, Some(map.layout()), "sd-svao")
            }
            _ if compact => (HiddenDepth::ColumnRays, None, "rt-svao"),
            _ => (HiddenDepth::ColumnRays, None, "rt-svao-dense"),
        };
        let constants = [
            ("SAMPLE_COUNT", f64::from(settings.samples)),
            ("COMPACT", f64::from(u8::from(compact))),
        ];
        let pipeline = |label, entry: &str| {
            let source = format!("{}\n{}", shaders::SVAO, entry);
            crate::gpu::compute_pipeline_with(
                device,
                label,
                &vao_source(kind, sd_layout, &source),
                &constants,
            )
        };
        let phase1 = pipeline("svao phase 1", shaders::SVAO_PHASE1);
        let phase2 = pipeline("svao phase 2", shaders::SVAO_PHASE2);
        let indirect =
            crate::gpu::compute_pipeline_with(device, "svao indirect", shaders::SVAO_INDIRECT, &[]);
        let pixels = u64::from(screen.width) * u64::from(screen.height);
        let buffer = |label, size: u64, usage| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: size.max(4),
                usage: wgpu::BufferUsages::STORAGE | usage,
                mapped_at_creation: false,
            })
        };
        let full_pixels = u64::from(screen.full_width()) * u64::from(screen.full_height());
        let sd_request = (kind == HiddenDepth::StochasticDepth).then(|| {
            buffer(
                "sd request",
                full_pixels * 4,
                wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
            )
        });
        Self {
            hidden: Hidden::new(device, hidden, &phase2),
            params: params_buffer(device, settings),
            view: view.clone(),
            name,
            compact,
            pixels: buffer(
                "svao pixels",
                pixels * PIXEL_BYTES,
                wgpu::BufferUsages::COPY_SRC,
            ),
            work_count: buffer(
                "svao work count",
                4,
                wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
            ),
            work_list: buffer("svao work list", pixels * 4, wgpu::BufferUsages::empty()),
            dispatch: buffer("svao dispatch", 12, wgpu::BufferUsages::INDIRECT),
            sd_request,
            phase1,
            phase2,
            indirect,
        }
    }
}

impl AoKernel for SvaoKernel {
    fn set_camera(&self, queue: &wgpu::Queue, view: &FrameView) {
        self.hidden.set_camera(queue, view);
    }

    fn stack_overflows(&self) -> Option<&wgpu::Buffer> {
        self.hidden.stack_overflows()
    }

    fn phase1_records(&self) -> Option<&wgpu::Buffer> {
        Some(&self.pixels)
    }

    fn stochastic_depth(&self) -> Option<&StochasticDepthMap> {
        match &self.hidden {
            Hidden::StochasticDepth(map) => Some(map),
            _ => None,
        }
    }

    fn sd_requests(&self) -> Option<&wgpu::Buffer> {
        self.sd_request.as_ref()
    }

    fn pass_name(&self) -> &'static str {
        self.name
    }

    fn encode(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        inputs: &FrameInputs,
        output: &wgpu::TextureView,
        mut profiler: Option<&mut PassProfiler>,
    ) {
        let work = |pipeline: &wgpu::ComputePipeline, request: Option<&wgpu::Buffer>| {
            let mut resources = vec![
                self.pixels.as_entire_binding(),
                self.work_count.as_entire_binding(),
                self.work_list.as_entire_binding(),
            ];
            resources.extend(request.map(|r| r.as_entire_binding()));
            crate::gpu::bind_group(
                device,
                "svao work",
                &pipeline.get_bind_group_layout(2),
                &resources,
            )
        };
        encoder.clear_buffer(&self.work_count, 0, None);
        if let Some(request) = &self.sd_request {
            encoder.clear_buffer(request, 0, None);
        }
        {
            let group0 = crate::gpu::bind_group(
                device,
                "svao phase 1",
                &self.phase1.get_bind_group_layout(0),
                &frame_resources(&self.view, &self.params, inputs, output),
            );
            let group2 = work(&self.phase1, self.sd_request.as_ref());
            let timestamp_writes = profiler
                .as_deref_mut()
                .map(|p| p.compute_pass("svao_phase1"));
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("svao phase 1"),
                timestamp_writes,
            });
            pass.set_pipeline(&self.phase1);
            pass.set_bind_group(0, &group0, &[]);
            pass.set_bind_group(2, &group2, &[]);
            let (x, y, z) = workgroups_32x8(inputs.screen.width, inputs.screen.height);
            pass.dispatch_workgroups(x, y, z);
        }
        if self.compact {
            let group = crate::gpu::bind_group(
                device,
                "svao indirect",
                &self.indirect.get_bind_group_layout(0),
                &[
                    self.work_count.as_entire_binding(),
                    self.dispatch.as_entire_binding(),
                ],
            );
            let timestamp_writes = profiler
                .as_deref_mut()
                .map(|p| p.compute_pass("svao_indirect"));
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("svao indirect"),
                timestamp_writes,
            });
            pass.set_pipeline(&self.indirect);
            pass.set_bind_group(0, &group, &[]);
            pass.dispatch_workgroups(1, 1, 1);
        }
        if let Hidden::StochasticDepth(map) = &self.hidden {
            map.render(
                device,
                encoder,
                inputs.depth,
                self.sd_request.as_ref(),
                profiler.as_deref_mut(),
            );
        }
        let mut resources = frame_resources(&self.view, &self.params, inputs, output);
        resources.extend(self.hidden.resources(encoder, inputs));
        let group0 = crate::gpu::bind_group(
            device,
            "svao phase 2",
            &self.phase2.get_bind_group_layout(0),
            &resources,
        );
        let group2 = work(&self.phase2, None);
        let timestamp_writes = profiler.map(|p| p.compute_pass("svao_phase2"));
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("svao phase 2"),
            timestamp_writes,
        });
        pass.set_pipeline(&self.phase2);
        pass.set_bind_group(0, &group0, &[]);
        if let Hidden::ColumnRays(rays) = &self.hidden {
            pass.set_bind_group(1, &rays.bvh_group, &[]);
        }
        pass.set_bind_group(2, &group2, &[]);
        if self.compact {
            pass.dispatch_workgroups_indirect(&self.dispatch, 0);
        } else {
            let (x, y) = dispatch_rows(inputs.screen.width * inputs.screen.height);
            pass.dispatch_workgroups(x, y, 1);
        }
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
