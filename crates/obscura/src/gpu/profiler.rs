//! Per-pass GPU timings with timestamp queries, and, where the device has pipeline statistics
//! queries, the fragment-shader invocations of each raster pass (overdraw made visible); passes
//! that rasterise in compute count their fragments themselves ([`PassProfiler::copy_fragments`]).
//!
//! Every pass that wants timing asks for its timestamp writes by name; each frame's queries are
//! resolved into their own slot of one buffer, read back once at the end. Benchmarks take medians
//! over frames; nothing here is ever used for timed asserts in tests.

use super::{Gpu, GpuError};
use std::collections::BTreeMap;

/// Timestamps per frame are resolved into slots this far apart (the resolve-offset alignment).
const SLOT_BYTES: u64 = 2 * wgpu::QUERY_RESOLVE_BUFFER_ALIGNMENT;
const MAX_PASSES: u32 = (SLOT_BYTES / 16) as u32;

/// Milliseconds per named pass for one frame.
pub type FrameTimings = BTreeMap<String, f64>;

/// Fragment-shader invocations per named raster pass for one frame.
pub type FrameFragments = BTreeMap<String, u64>;

/// The fragment counters: one pipeline-statistics query per raster pass, resolved per frame.
struct FragmentQueries {
    queries: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    pass_names: Vec<String>,
    frame_passes: Vec<Vec<String>>,
}

/// Fragment queries per frame slot (8 bytes each).
const MAX_RASTER_PASSES: u32 = (SLOT_BYTES / 8) as u32;

/// Fragments counted by compute passes' shaders: a `u32` per pass, copied per frame into
/// `buffer` (slots of `MAX_COUNTED_PASSES` words).
struct CountedFragments {
    buffer: wgpu::Buffer,
    pass_names: Vec<String>,
    frame_passes: Vec<Vec<String>>,
}

const MAX_COUNTED_PASSES: u64 = 8;

/// GPU times per named pass over up to `max_frames` frames: each pass asks for its timestamp
/// writes by name ([`PassProfiler::compute_pass`], [`PassProfiler::render_pass`]),
/// [`PassProfiler::end_frame`] resolves the frame and [`PassProfiler::read`] returns milliseconds
/// per pass name (summed over passes of one name).
pub struct PassProfiler {
    fragments: Option<FragmentQueries>,
    counted: CountedFragments,
    queries: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    pass_names: Vec<String>,
    frame_passes: Vec<Vec<String>>,
    frame: u32,
    max_frames: u32,
    period_ns: f64,
}

impl PassProfiler {
    /// A profiler for up to `max_frames` frames. Errors when the adapter has no timestamp queries.
    pub fn new(gpu: &Gpu, max_frames: u32) -> Result<Self, GpuError> {
        if !gpu.summary.timestamp_queries {
            return Err(GpuError::Other(format!(
                "adapter '{}' does not support timestamp queries, so per-pass GPU times cannot be measured",
                gpu.summary.name
            )));
        }
        let queries = gpu.device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("pass timestamps"),
            ty: wgpu::QueryType::Timestamp,
            count: 2 * MAX_PASSES,
        });
        let resolve = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("timestamp resolve"),
            size: SLOT_BYTES * u64::from(max_frames.max(1)),
            usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let fragments = gpu
            .device
            .features()
            .contains(wgpu::Features::PIPELINE_STATISTICS_QUERY)
            .then(|| FragmentQueries {
                queries: gpu.device.create_query_set(&wgpu::QuerySetDescriptor {
                    label: Some("raster fragments"),
                    ty: wgpu::QueryType::PipelineStatistics(
                        wgpu::PipelineStatisticsTypes::FRAGMENT_SHADER_INVOCATIONS,
                    ),
                    count: MAX_RASTER_PASSES,
                }),
                resolve: gpu.device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("fragments resolve"),
                    size: SLOT_BYTES * u64::from(max_frames.max(1)),
                    usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
                    mapped_at_creation: false,
                }),
                pass_names: Vec::new(),
                frame_passes: Vec::new(),
            });
        let counted = CountedFragments {
            buffer: gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("counted fragments"),
                size: 4 * MAX_COUNTED_PASSES * u64::from(max_frames.max(1)),
                usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            }),
            pass_names: Vec::new(),
            frame_passes: Vec::new(),
        };
        Ok(Self {
            fragments,
            counted,
            queries,
            resolve,
            pass_names: Vec::new(),
            frame_passes: Vec::new(),
            frame: 0,
            max_frames: max_frames.max(1),
            period_ns: f64::from(gpu.queue.get_timestamp_period()),
        })
    }

    /// Index of the next pass's begin query; panics (a programming error) past `MAX_PASSES`.
    fn next_pass(&mut self, name: &str) -> u32 {
        assert!(
            self.frame < self.max_frames,
            "profiler frame budget exhausted"
        );
        let index = self.pass_names.len() as u32;
        assert!(index < MAX_PASSES, "too many profiled passes in one frame");
        self.pass_names.push(name.to_string());
        2 * index
    }

    /// The timestamp writes for compute pass `name` of the current frame. At most 32 passes a frame
    /// (one 512-byte resolve slot); panics past that or past `max_frames` frames.
    pub fn compute_pass(&mut self, name: &str) -> wgpu::ComputePassTimestampWrites<'_> {
        let begin = self.next_pass(name);
        wgpu::ComputePassTimestampWrites {
            query_set: &self.queries,
            beginning_of_pass_write_index: Some(begin),
            end_of_pass_write_index: Some(begin + 1),
        }
    }

    /// The timestamp writes for render pass `name` of the current frame; limits as
    /// [`PassProfiler::compute_pass`].
    pub fn render_pass(&mut self, name: &str) -> wgpu::RenderPassTimestampWrites<'_> {
        let begin = self.next_pass(name);
        wgpu::RenderPassTimestampWrites {
            query_set: &self.queries,
            beginning_of_pass_write_index: Some(begin),
            end_of_pass_write_index: Some(begin + 1),
        }
    }

    /// Starts counting the fragment-shader invocations of raster pass `name` (no-op without
    /// pipeline statistics queries); [`PassProfiler::end_fragments`] before the pass ends.
    pub fn begin_fragments(&mut self, pass: &mut wgpu::RenderPass, name: &str) {
        if let Some(f) = &mut self.fragments {
            let index = f.pass_names.len() as u32;
            assert!(index < MAX_RASTER_PASSES, "too many counted raster passes");
            f.pass_names.push(name.to_string());
            pass.begin_pipeline_statistics_query(&f.queries, index);
        }
    }

    /// Stops the count [`PassProfiler::begin_fragments`] started (no-op without pipeline statistics
    /// queries); call it before `pass` ends.
    pub fn end_fragments(&self, pass: &mut wgpu::RenderPass) {
        if self.fragments.is_some() {
            pass.end_pipeline_statistics_query();
        }
    }

    /// The fragments compute pass `name` of the current frame made, as its shader counted them:
    /// the `u32` at byte `offset` of `counter`, copied once the pass has run (encode this after
    /// it). At most 8 such passes a frame; panics past that.
    pub fn copy_fragments(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        name: &str,
        counter: &wgpu::Buffer,
        offset: u64,
    ) {
        let index = self.counted.pass_names.len() as u64;
        assert!(
            index < MAX_COUNTED_PASSES,
            "too many counted compute passes"
        );
        assert!(
            self.frame < self.max_frames,
            "profiler frame budget exhausted"
        );
        self.counted.pass_names.push(name.to_string());
        let slot = 4 * (MAX_COUNTED_PASSES * u64::from(self.frame) + index);
        encoder.copy_buffer_to_buffer(counter, offset, &self.counted.buffer, slot, 4);
    }

    /// Resolve this frame's queries into its slot. Call once per frame after its passes.
    pub fn end_frame(&mut self, encoder: &mut wgpu::CommandEncoder) {
        self.counted
            .frame_passes
            .push(std::mem::take(&mut self.counted.pass_names));
        if let Some(f) = &mut self.fragments {
            let count = f.pass_names.len() as u32;
            if count > 0 {
                encoder.resolve_query_set(
                    &f.queries,
                    0..count,
                    &f.resolve,
                    u64::from(self.frame) * SLOT_BYTES,
                );
            }
            f.frame_passes.push(std::mem::take(&mut f.pass_names));
        }
        let count = 2 * self.pass_names.len() as u32;
        if count > 0 {
            encoder.resolve_query_set(
                &self.queries,
                0..count,
                &self.resolve,
                u64::from(self.frame) * SLOT_BYTES,
            );
        }
        self.frame_passes.push(std::mem::take(&mut self.pass_names));
        self.frame += 1;
    }

    /// Every recorded frame's fragment-shader invocations per raster pass (summed over passes of
    /// one name) and the fragments compute passes counted ([`PassProfiler::copy_fragments`]),
    /// or `None` where the device has no pipeline statistics queries and no pass counted.
    pub fn read_fragments(&self, gpu: &Gpu) -> Result<Option<Vec<FrameFragments>>, GpuError> {
        let counted = self.read_counted(gpu)?;
        let Some(f) = &self.fragments else {
            let any = counted.iter().any(|frame| !frame.is_empty());
            return Ok(any.then_some(counted));
        };
        let size = SLOT_BYTES * u64::from(self.frame);
        if size == 0 {
            return Ok(Some(Vec::new()));
        }
        let staging = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("fragments readback"),
            size,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        encoder.copy_buffer_to_buffer(&f.resolve, 0, &staging, 0, size);
        gpu.queue.submit([encoder.finish()]);
        let counts: Vec<u64> = bytemuck::pod_collect_to_vec(&super::read_buffer(gpu, &staging)?);
        let stride = (SLOT_BYTES / 8) as usize;
        Ok(Some(
            f.frame_passes
                .iter()
                .enumerate()
                .zip(counted)
                .map(|((frame, names), mut out)| {
                    add_by_name(&mut out, names, |p| counts[frame * stride + p]);
                    out
                })
                .collect(),
        ))
    }

    /// Every recorded frame's fragments as compute passes counted them.
    fn read_counted(&self, gpu: &Gpu) -> Result<Vec<FrameFragments>, GpuError> {
        let c = &self.counted;
        if c.frame_passes.iter().all(|names| names.is_empty()) {
            return Ok(vec![FrameFragments::new(); c.frame_passes.len()]);
        }
        let words: Vec<u32> =
            bytemuck::pod_collect_to_vec(&super::read_buffer_copy(gpu, &c.buffer)?);
        let stride = MAX_COUNTED_PASSES as usize;
        Ok(c.frame_passes
            .iter()
            .enumerate()
            .map(|(frame, names)| {
                let mut out = FrameFragments::new();
                add_by_name(&mut out, names, |p| u64::from(words[frame * stride + p]));
                out
            })
            .collect())
    }

    /// The recorded frames' timestamp ticks, each frame's from the start of its slot.
    async fn ticks(&self, gpu: &Gpu) -> Result<Vec<u64>, GpuError> {
        let size = SLOT_BYTES * u64::from(self.frame);
        if size == 0 {
            return Ok(Vec::new());
        }
        let staging = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("timestamp readback"),
            size,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        encoder.copy_buffer_to_buffer(&self.resolve, 0, &staging, 0, size);
        gpu.queue.submit([encoder.finish()]);
        Ok(bytemuck::pod_collect_to_vec(
            &super::read_buffer_async(gpu, &staging).await?,
        ))
    }

    /// Read every recorded frame's pass times (milliseconds).
    pub fn read(&self, gpu: &Gpu) -> Result<Vec<FrameTimings>, GpuError> {
        Ok(self.read_with_spans(gpu)?.0)
    }

    /// [`Self::read`] without blocking (the only way in a browser).
    pub async fn read_async(&self, gpu: &Gpu) -> Result<Vec<FrameTimings>, GpuError> {
        Ok(self.read_with_spans_async(gpu).await?.0)
    }

    /// Every recorded frame's pass times and span (milliseconds), from one readback. The span
    /// runs from the start of the frame's first timed pass to the end of its last: unlike the
    /// sum of the passes it includes what the GPU does between them (layout transitions,
    /// copies, waits); measured on the H200, a depth buffer written and then sampled cost about
    /// 0.15 ms there that no pass's time showed (BENCHMARKS.md, issue 16).
    pub fn read_with_spans(&self, gpu: &Gpu) -> Result<(Vec<FrameTimings>, Vec<f64>), GpuError> {
        pollster::block_on(self.read_with_spans_async(gpu))
    }

    async fn read_with_spans_async(
        &self,
        gpu: &Gpu,
    ) -> Result<(Vec<FrameTimings>, Vec<f64>), GpuError> {
        let ticks = self.ticks(gpu).await?;
        let stride = (SLOT_BYTES / 8) as usize;
        let ms = |t: u64| t as f64 * self.period_ns / 1e6;
        Ok(self
            .frame_passes
            .iter()
            .enumerate()
            .map(|(f, names)| {
                // Per pass: begin, end.
                let stamps = &ticks[f * stride..f * stride + 2 * names.len()];
                let mut timings = FrameTimings::new();
                for (name, pass) in names.iter().zip(stamps.chunks_exact(2)) {
                    *timings.entry(name.clone()).or_insert(0.0) +=
                        ms(pass[1].saturating_sub(pass[0]));
                }
                let first = stamps.iter().step_by(2).copied().min().unwrap_or(0);
                let last = stamps.iter().skip(1).step_by(2).copied().max().unwrap_or(0);
                (timings, ms(last.saturating_sub(first)))
            })
            .unzip())
    }
}

/// Adds `value(p)` to `out` under the name of pass `p` of `names` (passes of one name summed).
fn add_by_name(out: &mut FrameFragments, names: &[String], value: impl Fn(usize) -> u64) {
    for (p, name) in names.iter().enumerate() {
        *out.entry(name.clone()).or_insert(0) += value(p);
    }
}
