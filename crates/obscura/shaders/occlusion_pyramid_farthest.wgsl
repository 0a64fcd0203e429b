// The occlusion pyramid's values (shaders/occlusion_pyramid.wgsl): the farthest reversed-Z depth
// of the first raster phase per tile. Pixels outside the framebuffer count as the near plane
// (1), which no minimum keeps.

@group(0) @binding(0) var z: texture_depth_2d;

const PYRAMID_OUTSIDE: f32 = 1.0;

fn pyramid_source_size() -> vec2<u32> {
    return textureDimensions(z);
}

fn pyramid_pixel(p: vec2<u32>) -> f32 {
    return textureLoad(z, p, 0);
}

fn pyramid_combine(a: f32, b: f32) -> f32 {
    return min(a, b);
}
