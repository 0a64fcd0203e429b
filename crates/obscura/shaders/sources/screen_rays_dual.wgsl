// Screen rays over two depth layers (`hemisphere-dual`, ours: seed 000 §2.1's second layer by
// depth peeling, read by the hemisphere march as deep G-buffers read theirs, Mara et al. 2016):
// the second layer is the next surface behind the first at the pixel, so the first surface is no
// thicker than the gap to it: a thin board before a wall no longer occludes all of `thickness`
// behind it (screen_rays.wgsl). Only that: the second layer of a closed object is its back face,
// with air behind it, and a layer's facing is not stored, so no thickness is assumed behind the
// second layer.

@group(GROUP_SOURCE) @binding(SOURCE_SECOND_DEPTH) var second_depth: texture_2d<f32>;

fn screen_rays_inside(q: vec3<f32>, cell: vec2<u32>, z: f32) -> bool {
    // 0 where the pixel has no second layer.
    let z2 = textureLoad(second_depth, cell, 0).r;
    let thickness = select(min(params.thickness, z2 - z), params.thickness, is_background(z2));
    return hemisphere_inside(q, cell, z, thickness);
}

// Depth peeling covers the framebuffer only.
fn screen_rays_band_inside(q: vec3<f32>, pixel: vec2<i32>) -> i32 {
    return -1;
}
