// Zero-filling storage buffers in compute (src/gpu/zero_fill.rs), timed like any pass (a
// `clear_buffer` in the encoder has no timestamps): one 16-byte word per invocation,
// consecutive invocations on consecutive words, plain stores. Measured for the stochastic depth
// map (H200, 1080p + 64 px, S = 4): 0.013 ms, where an atomic store per value took 0.047 ms
// looping over a pixel's values and 0.098 ms with one value per invocation (BENCHMARKS.md,
// issue 16).

@group(0) @binding(0) var<storage, read_write> zero_fill_words: array<vec4<u32>>;

@compute @workgroup_size(256)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let index = id.y * groups.x * 256u + id.x;
    if (index < arrayLength(&zero_fill_words)) {
        zero_fill_words[index] = vec4<u32>(0u);
    }
}
