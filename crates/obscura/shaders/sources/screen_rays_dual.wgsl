// Screen rays over two depth layers (`hemisphere-dual`, ours: seed 000 §2.1's second layer by
// depth peeling, read by the hemisphere march as deep G-buffers read theirs, Mara et al. 2016):
// the second layer is the next surface behind the first at the pixel (for a closed object its
// back face), so the first surface is no thicker than the gap to it (screen_rays.wgsl).

@group(GROUP_SOURCE) @binding(SOURCE_SECOND_DEPTH) var second_depth: texture_2d<f32>;

// The second layer's linear depth at framebuffer pixel `cell`; 0 where it has none.
fn screen_rays_second_depth(cell: vec2<u32>) -> f32 {
    return textureLoad(second_depth, cell, 0).r;
}
