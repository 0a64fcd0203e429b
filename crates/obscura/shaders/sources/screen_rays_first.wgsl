// Screen rays over the first depth layer alone (`hemisphere`): no depth is known behind it, so
// every surface is `hemisphere.thickness` thick (screen_rays.wgsl).

fn screen_rays_inside(q: vec3<f32>, cell: vec2<u32>, z: f32) -> bool {
    return hemisphere_inside(q, cell, z, params.thickness);
}

// Nothing is known off the framebuffer.
fn screen_rays_band_inside(q: vec3<f32>, pixel: vec2<i32>) -> i32 {
    return -1;
}
