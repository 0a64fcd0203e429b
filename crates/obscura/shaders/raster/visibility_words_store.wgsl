// Visibility buffers without a colour target (src/raster/gbuffer.rs `Visibility::Words`; where
// the device has 64-bit atomic min/max): a fragment stores (its depth's bits << 32) |
// ~(triangle + 1) by `atomicMax` into its pixel's word, so the nearest stored fragment's triangle
// is left whatever order the fragments come in; visibility_words_load.wgsl reads it. Why: on the
// H200 a written fragment cost 0.072 ns for its depth and as much again for the `R32Uint` colour
// target (BENCHMARKS.md, "What a written fragment costs"), while an atomic goes to the caches, not
// the few raster units. Reversed-Z depths are positive floats, whose bits order as they do; the
// complement makes the lower triangle win a tie of equal depths, as the first drawn wins a colour
// target's `Greater` depth test (draws go in triangle order).
// `VISIBILITY_WIDTH` (the framebuffer's width) and `VISIBILITY_WORDS_BINDING` are generated in
// front by src/raster/gbuffer.rs, and visibility_words_index.wgsl places the words.

@group(0) @binding(VISIBILITY_WORDS_BINDING) var<storage, read_write> visibility_atomic: array<atomic<u64>>;

fn visibility_store(clip: vec4<f32>, id: u32) {
    let i = visibility_word(vec2<u32>(clip.xy), VISIBILITY_WIDTH);
    atomicMax(&visibility_atomic[i], (u64(bitcast<u32>(clip.z)) << 32u) | u64(~id));
}
