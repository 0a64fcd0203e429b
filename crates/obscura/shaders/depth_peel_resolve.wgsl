// Depth peeling's resolve: the linear depth of the peeled layer's triangle at every pixel centre
// (appended to gbuffer.wgsl and gbuffer_resolve.wgsl; the raster pass is depth_peel.wgsl).

// The peeled triangle + 1 where `z_buffer` holds a depth; elsewhere whatever an earlier frame
// left (never cleared: src/raster/gbuffer.rs, `VISIBILITY_FORMAT`).
@group(0) @binding(6) var second_visibility: texture_2d<u32>;
@group(0) @binding(7) var second_depth_out: texture_storage_2d<r32float, write>;
// The peeling pass's reversed-Z depth buffer: 0 where no triangle was peeled.
@group(0) @binding(8) var z_buffer: texture_depth_2d;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(second_visibility);
    if (any(id.xy >= size)) {
        return;
    }
    var depth = 0.0;
    if (textureLoad(z_buffer, id.xy, 0) != 0.0) {
        let visible = textureLoad(second_visibility, id.xy, 0).r;
        depth = -pixel_surface(triangles[visible - 1u], id.xy, size).view_pos.z;
    }
    textureStore(second_depth_out, id.xy, vec4<f32>(depth, 0.0, 0.0, 0.0));
}
