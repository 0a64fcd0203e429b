// Depth peeling's resolve: the linear depth of the peeled layer's triangle at every pixel centre
// (appended to gbuffer.wgsl, gbuffer_resolve.wgsl and the header that reads the peeling pass's
// output, `visible_triangle`: visibility_target_load.wgsl or visibility_words_load.wgsl; the
// raster pass is depth_peel.wgsl).

const VISIBILITY_BINDING: u32 = 6u;
const Z_BUFFER_BINDING: u32 = 8u;
@group(0) @binding(7) var second_depth_out: texture_storage_2d<r32float, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(second_depth_out);
    if (any(id.xy >= size)) {
        return;
    }
    var depth = 0.0;
    let visible = visible_triangle(id.xy, size);
    if (visible != 0u) {
        depth = -pixel_surface(triangles[visible - 1u], id.xy, size).view_pos.z;
    }
    textureStore(second_depth_out, id.xy, vec4<f32>(depth, 0.0, 0.0, 0.0));
}
