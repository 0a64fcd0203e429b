// Screen rays over the first depth layer alone (`hemisphere`): no depth is known behind it, so
// every surface is `hemisphere.thickness` thick (screen_rays.wgsl).

fn screen_rays_second_depth(cell: vec2<u32>) -> f32 {
    return 0.0;
}
