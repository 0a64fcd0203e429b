// Where a pixel's word lies in the visibility words (visibility_words_store.wgsl,
// visibility_words_load.wgsl): in 2×2 quads, the quad's four words together (one 32-byte sector;
// its upper row first), quads row-major, ⌈width / 2⌉ of them to a row. Why: the rasteriser hands
// fragments to the shaders in 2×2 quads, and row-major words put a quad in two 32-byte sectors.
// Measured, not derived (BENCHMARKS.md, issue 16): quad order made the visibility pass 2.4–3.8 %
// and its resolve 5–6.5 % faster on an H200, while the same reasoning applied to the stochastic
// map's layout made it slower.
fn visibility_word(pixel: vec2<u32>, width: u32) -> u32 {
    let quads_per_row = (width + 1u) >> 1u;
    let quad = (pixel.y >> 1u) * quads_per_row + (pixel.x >> 1u);
    return quad * 4u + (pixel.y & 1u) * 2u + (pixel.x & 1u);
}
