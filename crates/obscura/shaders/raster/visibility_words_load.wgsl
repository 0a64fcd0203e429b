// A visibility buffer's resolve reading the words a pass stored by 64-bit atomics
// (visibility_words_store.wgsl; gbuffer_resolve_main.wgsl, depth_peel_resolve.wgsl): per pixel
// (placed by visibility_words_index.wgsl), the nearest fragment's reversed-Z depth bits (high
// word) and the complement of its triangle + 1 (low word), 0 where nothing was stored. The
// resolve reads each word once and empties it for the next frame, so the buffer needs no
// clearing pass. The resolve defines the binding `VISIBILITY_BINDING`.

@group(0) @binding(VISIBILITY_BINDING) var<storage, read_write> visibility_words: array<vec2<u32>>;

// The visible triangle + 1 of `pixel` (of a framebuffer of `size`), 0 where none was stored.
fn visible_triangle(pixel: vec2<u32>, size: vec2<u32>) -> u32 {
    let i = visibility_word(pixel, size.x);
    // Little-endian: x is the low word.
    let word = visibility_words[i];
    if (word.y == 0u) {
        return 0u;
    }
    visibility_words[i] = vec2<u32>(0u);
    return ~word.x;
}
