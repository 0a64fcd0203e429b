// The G-buffer's visibility pass storing words (appended to gbuffer.wgsl and
// visibility_words_store.wgsl, which says why).

// Never alpha-tested: the depth test runs (and writes) before the shader, so only fragments
// nearer than every one before them store.
@fragment
@early_depth_test(force)
fn fs_visibility_words(in: VisibilityVertex) {
    visibility_store(in.clip, in.id);
}

// Alpha-tested: the texel decides, then the depth test, after the shader (a `discard` must keep
// the depth unwritten). The store comes before that test, so farther fragments store too; the
// maximum still leaves the nearest.
@fragment
fn fs_visibility_words_masked(in: VertexOut) {
    if (!material_passes_alpha(materials[in.material], textures, in.uv)) {
        discard;
    }
    visibility_store(in.clip, in.triangle + 1u);
}
