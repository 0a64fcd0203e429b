//! Zero-filling storage buffers in a timed compute pass (`shaders/common/zero_fill.wgsl`): the
//! per-frame clears of the stochastic depth maps and their request buffers, so that a benchmark
//! sees what they cost (an encoder's `clear_buffer` is not inside any timed pass).

// The kernel is included here, not through `crate::shaders`: gpu/ knows nothing of the
// techniques' shaders (tests/it/module_graph.rs).
use super::PassProfiler;

/// The pipeline that fills buffers with zeros. The buffers' sizes must be whole 16-byte words
/// ([`zero_fill_size`]).
pub struct ZeroFill {
    pipeline: wgpu::ComputePipeline,
}

/// `bytes` rounded up to whole 16-byte words, the size a buffer [`ZeroFill`] clears needs.
pub fn zero_fill_size(bytes: u64) -> u64 {
    bytes.div_ceil(16).max(1) * 16
}

impl ZeroFill {
    /// The pipeline, made once per owner.
    pub fn new(device: &wgpu::Device) -> Self {
        Self {
            pipeline: super::compute_pipeline_with(
                device,
                "zero fill",
                include_str!("../../shaders/common/zero_fill.wgsl"),
                &[],
            ),
        }
    }

    /// Fills every buffer of `buffers` with zeros in one compute pass, timed as `name`.
    pub fn encode(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        buffers: &[&wgpu::Buffer],
        name: &'static str,
        profiler: Option<&mut PassProfiler>,
    ) {
        let groups: Vec<_> = buffers
            .iter()
            .map(|buffer| {
                debug_assert_eq!(buffer.size() % 16, 0, "zero fill needs whole 16-byte words");
                super::bind_group(
                    device,
                    "zero fill",
                    &self.pipeline.get_bind_group_layout(0),
                    &[buffer.as_entire_binding()],
                )
            })
            .collect();
        let timestamp_writes = profiler.map(|p| p.compute_pass(name));
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(name),
            timestamp_writes,
        });
        pass.set_pipeline(&self.pipeline);
        for (group, buffer) in groups.iter().zip(buffers) {
            pass.set_bind_group(0, group, &[]);
            // 16-byte words in rows of at most 65,535 workgroups of 256.
            let workgroups = (buffer.size() / 16).div_ceil(256) as u32;
            let x = workgroups.clamp(1, 65_535);
            pass.dispatch_workgroups(x, workgroups.div_ceil(x), 1);
        }
    }
}
