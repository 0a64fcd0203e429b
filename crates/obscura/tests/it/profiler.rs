//! `PassProfiler`'s fragment counts that compute passes make themselves (the compute rasteriser's
//! `sd_bin` and `sd_tiles`): read back per frame and pass name.

use crate::common::gpu;
use obscura::PassProfiler;

/// What compute passes count comes back per frame and pass name, summed over passes of one
/// name, beside (or without) the pipeline statistics.
#[test]
fn counted_fragments_come_back_per_frame_and_pass() {
    let gpu = gpu();
    let counter = wgpu::util::DeviceExt::create_buffer_init(
        &gpu.device,
        &wgpu::util::BufferInitDescriptor {
            label: Some("counter"),
            contents: bytemuck::cast_slice(&[7u32, 11]),
            usage: wgpu::BufferUsages::COPY_SRC,
        },
    );
    let mut profiler = PassProfiler::new(&gpu, 3).unwrap();
    for frame in 0..3 {
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        profiler.copy_fragments(&mut encoder, "a", &counter, 0);
        if frame == 1 {
            profiler.copy_fragments(&mut encoder, "a", &counter, 4);
        }
        profiler.copy_fragments(&mut encoder, "b", &counter, 4);
        profiler.end_frame(&mut encoder);
        gpu.queue.submit([encoder.finish()]);
    }
    let frames = profiler.read_fragments(&gpu).unwrap().unwrap();
    let got: Vec<Vec<(String, u64)>> = frames
        .into_iter()
        .map(|f| f.into_iter().collect())
        .collect();
    let want = |a: u64| vec![("a".to_string(), a), ("b".to_string(), 11)];
    assert_eq!(got, [want(7), want(18), want(7)]);
}
