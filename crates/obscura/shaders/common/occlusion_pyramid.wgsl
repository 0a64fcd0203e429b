// The occlusion pyramid's layout (src/raster/occlusion_pyramid.rs), shared by its builder
// (shaders/raster/occlusion_pyramid.wgsl) and its reader (shaders/raster/triangle_cull.wgsl): for each level
// from PYRAMID_FIRST_LEVEL to PYRAMID_LAST_LEVEL, the farthest reversed-Z depth over square tiles
// of 2^level pixels (level 0: the depth itself) of a framebuffer of `size` pixels,
// ceil(size / 2^level) tiles row by row, one level after another in one buffer. The builder
// writes levels 0 to 2 per invocation (4×4 pixels each), so the first level is 0.

const PYRAMID_FIRST_LEVEL: u32 = 0u;
const PYRAMID_LAST_LEVEL: u32 = 6u;

fn pyramid_level_size(size: vec2<u32>, level: u32) -> vec2<u32> {
    return (size + vec2<u32>((1u << level) - 1u)) >> vec2<u32>(level);
}

// Where tile `tile` of `level` is in the pyramid buffer.
fn pyramid_index(size: vec2<u32>, level: u32, tile: vec2<u32>) -> u32 {
    var offset = 0u;
    for (var l = PYRAMID_FIRST_LEVEL; l < level; l++) {
        let s = pyramid_level_size(size, l);
        offset += s.x * s.y;
    }
    return offset + tile.y * pyramid_level_size(size, level).x + tile.x;
}
