// Depth peeling storing words (appended to gbuffer.wgsl, depth_peel.wgsl and
// visibility_words_store.wgsl, which says why). The maximum over the fragments peeling keeps is
// the nearest of them, so the pass needs no depth test: it draws over the G-buffer's depth
// buffer without testing or writing it (no raster work per fragment), and every fragment runs
// the shader, as the colour-target pass's fragments did (their `discard` made its depth test
// late).

@fragment
fn fs_peel_words(in: VisibilityVertex) {
    if (peel_keeps(vec2<u32>(in.clip.xy), 1.0 / in.clip.w)) {
        visibility_store(in.clip, in.id);
    }
}

@fragment
fn fs_peel_words_masked(in: VertexOut) {
    if (material_passes_alpha(materials[in.material], textures, in.uv)
        && peel_keeps(vec2<u32>(in.clip.xy), -in.view_pos.z)) {
        visibility_store(in.clip, in.triangle + 1u);
    }
}
