// A visibility buffer's resolve reading a colour target (gbuffer_resolve_main.wgsl,
// depth_peel_resolve.wgsl; src/raster/gbuffer.rs `Visibility::Target`): the visible triangle + 1
// per pixel where the pass's depth buffer holds a depth; elsewhere whatever an earlier frame left
// (the target is never cleared: `VISIBILITY_FORMAT`). The resolve defines the bindings
// `VISIBILITY_BINDING` and `Z_BUFFER_BINDING`.

@group(0) @binding(VISIBILITY_BINDING) var visibility: texture_2d<u32>;
// The pass's reversed-Z depth buffer: 0 where no triangle was drawn.
@group(0) @binding(Z_BUFFER_BINDING) var z_buffer: texture_depth_2d;

// The visible triangle + 1 of `pixel` (of a framebuffer of `size`), 0 where none was drawn.
fn visible_triangle(pixel: vec2<u32>, size: vec2<u32>) -> u32 {
    if (textureLoad(z_buffer, pixel, 0) == 0.0) {
        return 0u;
    }
    return textureLoad(visibility, pixel, 0).r;
}
