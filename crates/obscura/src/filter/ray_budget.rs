//! The ray budget (issue 58; `shaders/filter/ray_budget.wgsl`): at most `hemisphere.ray_budget`
//! hemisphere rays a frame, given first to the pixels whose accumulated AO is least certain
//! (no history, then the largest variance of the running mean). It runs before the AO pass and
//! reads temporal accumulation's history through the same reprojection, so it lives beside it
//! ([`super::temporal::TemporalAccumulation`] holds it); the AO pass reads the rays it grants
//! per pixel from the frame group (`FRAME_RAY_GRANT`).

use crate::gpu::{Gpu, PassProfiler};
use crate::shaders;
use crate::view::ScreenGeometry;

/// `BudgetParams` of the shader.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct BudgetParams {
    budget: u32,
    rays: u32,
    frame: u32,
    _pad: u32,
}

/// What the budget's selection found for the last frame ([`crate::AmbientOcclusion::read_ray_budget`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RayBudgetReport {
    /// The budget the frame ran under: rays, at most.
    pub budget: u32,
    /// Rays granted ( ≤ `budget`).
    pub granted: u32,
    /// Rays every visible surface pixel casting its full `hemisphere.rays` would take.
    pub wanted: u32,
}

/// The four passes and their buffers.
pub struct RayBudget {
    priority: wgpu::ComputePipeline,
    block_sums: wgpu::ComputePipeline,
    threshold: wgpu::ComputePipeline,
    grant: wgpu::ComputePipeline,
    params: wgpu::Buffer,
    keys: wgpu::Buffer,
    histogram: wgpu::Buffer,
    /// Pixels per block of 256 keys.
    block_counts: wgpu::Buffer,
    result: wgpu::Buffer,
    grant_image: wgpu::Texture,
    rays: u32,
    budget: super::shared_cell::SharedCell<u32>,
}

/// Keys of the selection's histogram (16 bits: 10 of priority, 6 of hash).
const KEY_COUNT: u64 = 1 << 16;
/// Keys a block of the threshold search holds (`BLOCK` in ray_budget.wgsl).
const BLOCK: u64 = 256;

impl RayBudget {
    /// The passes for the visible image of `screen`, whose pixels cast `rays` rays when
    /// granted, at most `budget` a frame. `temporal_source` is temporal accumulation's WGSL
    /// (with its common helpers), whose bindings and history reads the passes share.
    pub fn new(
        device: &wgpu::Device,
        temporal_source: &str,
        screen: &ScreenGeometry,
        rays: u32,
        budget: u32,
    ) -> Self {
        let source = [
            shaders::HASH,
            shaders::VISIBILITY_VARIANCE,
            temporal_source,
            shaders::RAY_BUDGET,
        ]
        .join("\n");
        let module = crate::gpu::shader_module(device, "ray budget", &source);
        let constants = screen.view_constants();
        let pipeline = |entry: &str| {
            crate::gpu::entry_pipeline(device, "ray budget", &module, entry, &constants, None)
        };
        let (width, height) = (screen.width, screen.height);
        let storage = |label, size: u64| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage: wgpu::BufferUsages::STORAGE
                    | wgpu::BufferUsages::COPY_SRC
                    | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        let pixels = u64::from(width) * u64::from(height);
        Self {
            priority: pipeline("priority"),
            block_sums: pipeline("block_sums"),
            threshold: pipeline("threshold"),
            grant: pipeline("grant"),
            params: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("ray budget params"),
                size: std::mem::size_of::<BudgetParams>() as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            keys: storage("ray budget keys", pixels.max(1) * 4),
            // Cleared before each frame's priority pass.
            histogram: storage("ray budget histogram", KEY_COUNT * 4),
            block_counts: storage("ray budget block counts", KEY_COUNT / BLOCK * 4),
            result: storage("ray budget result", 32),
            grant_image: crate::gpu::texture_2d(
                device,
                "ray grant",
                width,
                height,
                wgpu::TextureFormat::R32Uint,
                wgpu::TextureUsages::STORAGE_BINDING
                    | wgpu::TextureUsages::TEXTURE_BINDING
                    | wgpu::TextureUsages::COPY_SRC,
            ),
            rays,
            budget: super::shared_cell::SharedCell::new(budget),
        }
    }

    /// Rays a frame from the next frame on.
    pub fn set_budget(&self, budget: u32) {
        self.budget.set(budget);
    }

    /// Rays a frame.
    pub fn budget(&self) -> u32 {
        self.budget.get()
    }

    /// The rays each visible pixel may cast this frame (`R32Uint`).
    pub fn grant_image(&self) -> &wgpu::Texture {
        &self.grant_image
    }

    /// Uploads this frame's budget and seed (before the frame is encoded).
    pub fn set_frame(&self, queue: &wgpu::Queue, frame: u32) {
        let params = BudgetParams {
            budget: self.budget.get(),
            rays: self.rays,
            frame,
            _pad: 0,
        };
        queue.write_buffer(&self.params, 0, bytemuck::bytes_of(&params));
    }

    /// Records the histogram's clearing and the four passes. `temporal` holds temporal
    /// accumulation's group-0 resources by binding (view 0, params 1, depth 2, normals 3, the
    /// history read 5). Timing: `ray_budget` (the passes).
    pub fn encode(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        temporal: &[(u32, wgpu::BindingResource)],
        size: (u32, u32),
        profiler: Option<&mut PassProfiler>,
    ) {
        let grant = self.grant_image.create_view(&Default::default());
        let own = [
            (0, self.params.as_entire_binding()),
            (1, self.keys.as_entire_binding()),
            (2, self.histogram.as_entire_binding()),
            (3, self.result.as_entire_binding()),
            (4, wgpu::BindingResource::TextureView(&grant)),
            (5, self.block_counts.as_entire_binding()),
        ];
        // Each entry point's layout holds only what it uses (layouts made from the shader).
        fn pick<'a>(
            all: &[(u32, wgpu::BindingResource<'a>)],
            used: &[u32],
        ) -> Vec<(u32, wgpu::BindingResource<'a>)> {
            all.iter()
                .filter(|(b, _)| used.contains(b))
                .cloned()
                .collect()
        }
        let group = |pipeline: &wgpu::ComputePipeline, index, resources: Vec<_>| {
            crate::gpu::bind_group_at(
                device,
                "ray budget",
                &pipeline.get_bind_group_layout(index),
                &resources,
            )
        };
        let priority = [
            group(&self.priority, 0, pick(temporal, &[0, 1, 2, 3, 5])),
            group(&self.priority, 1, pick(&own, &[0, 1, 2])),
        ];
        // The block and threshold passes read nothing of group 0: their layouts there are empty.
        let block_sums = [
            group(&self.block_sums, 0, Vec::new()),
            group(&self.block_sums, 1, pick(&own, &[2, 5])),
        ];
        let threshold = [
            group(&self.threshold, 0, Vec::new()),
            group(&self.threshold, 1, pick(&own, &[0, 2, 3, 5])),
        ];
        let grant_groups = [
            group(&self.grant, 0, pick(temporal, &[0])),
            group(&self.grant, 1, pick(&own, &[0, 1, 3, 4])),
        ];
        let (w, h) = size;
        let tiles = (w.div_ceil(8), h.div_ceil(8), 1);
        encoder.clear_buffer(&self.histogram, 0, None);
        let timestamp_writes = profiler.map(|p| p.compute_pass("ray_budget"));
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("ray budget"),
            timestamp_writes,
        });
        // The priority pass: one workgroup per 32×4 tile (`TILE` in ray_budget.wgsl).
        let priority_tiles = (w.div_ceil(32), h.div_ceil(4), 1);
        for (pipeline, groups, (x, y, z)) in [
            (&self.priority, &priority, priority_tiles),
            (
                &self.block_sums,
                &block_sums,
                ((KEY_COUNT / BLOCK) as u32, 1, 1),
            ),
            (&self.threshold, &threshold, (1, 1, 1)),
            (&self.grant, &grant_groups, tiles),
        ] {
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, &groups[0], &[]);
            pass.set_bind_group(1, &groups[1], &[]);
            pass.dispatch_workgroups(x, y, z);
        }
    }

    /// What the last frame's selection found (the budget it ran under: a time budget may have
    /// set another for the next frame since).
    pub fn read(&self, gpu: &Gpu) -> Result<RayBudgetReport, crate::gpu::GpuError> {
        let bytes = crate::gpu::read_buffer_copy(gpu, &self.result)?;
        let words: &[u32] = bytemuck::cast_slice(&bytes);
        Ok(RayBudgetReport {
            budget: words[4],
            granted: words[2],
            wanted: words[3],
        })
    }
}

/// A time budget (`hemisphere.time_budget`): sets the ray budget each frame so that the AO's
/// GPU time after the G-buffer (every pass but `gbuffer*`: the budget's passes, the sources, the
/// AO pass, the filters) approaches `target_ms`. The frame loops that time their frames call
/// [`TimeBudget::next`] with the last frame's timings.
///
/// The time is a fixed part plus a part that grows with the rays; the budget is multiplied by
/// √(target / measured) each frame (a damped step towards the budget whose proportional step
/// would meet the target, so one noisy timing moves it half as far in log terms), within
/// [1, `max_rays`].
#[derive(Clone, Copy, Debug)]
pub struct TimeBudget {
    /// Milliseconds a frame after the G-buffer.
    pub target_ms: f64,
    /// The most rays a frame (every pixel's `hemisphere.rays`).
    pub max_rays: u32,
}

impl TimeBudget {
    /// The GPU milliseconds of a frame's AO: every timed pass but the G-buffer's.
    pub fn ao_ms(timings: &crate::gpu::FrameTimings) -> f64 {
        timings
            .iter()
            .filter(|(pass, _)| !pass.starts_with("gbuffer"))
            .map(|(_, ms)| ms)
            .sum()
    }

    /// The next frame's ray budget after a frame of `budget` rays whose AO took `ms`.
    pub fn next(&self, budget: u32, ms: f64) -> u32 {
        let positive = |x: f64| x > 0.0 && x.is_finite();
        if !positive(ms) || !positive(self.target_ms) {
            return budget.clamp(1, self.max_rays.max(1));
        }
        let next = f64::from(budget.max(1)) * (self.target_ms / ms).sqrt();
        next.round().clamp(1.0, f64::from(self.max_rays.max(1))) as u32
    }
}

#[cfg(test)]
mod tests {
    use super::TimeBudget;

    /// A frame's time as a fixed part and a part per ray, with the budget capped by the rays the
    /// pixels want: the controller meets the target within 2 % in 20 frames from either side,
    /// and keeps every ray when even all of them fit.
    #[test]
    fn the_time_budget_meets_its_target() {
        let wanted = 2_000_000u32;
        let frame_ms = |budget: u32| 0.15 + 0.4e-6 * f64::from(budget.min(wanted));
        let controller = TimeBudget {
            target_ms: 0.6,
            max_rays: wanted,
        };
        for start in [1_000u32, wanted] {
            let mut budget = start;
            for _ in 0..20 {
                budget = controller.next(budget, frame_ms(budget));
            }
            let ms = frame_ms(budget);
            assert!((ms / 0.6 - 1.0).abs() < 0.02, "from {start}: {ms} ms");
        }
        let generous = TimeBudget {
            target_ms: 5.0,
            max_rays: wanted,
        };
        let mut budget = 1_000;
        for _ in 0..40 {
            budget = generous.next(budget, frame_ms(budget));
        }
        assert_eq!(budget, wanted);
        // A frame without timings leaves the budget as it was.
        assert_eq!(controller.next(123_456, 0.0), 123_456);
        assert_eq!(controller.next(123_456, f64::NAN), 123_456);
    }
}
