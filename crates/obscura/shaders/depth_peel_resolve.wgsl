// Depth peeling's resolve: the linear depth of the peeled layer's triangle at every pixel centre
// (appended to gbuffer.wgsl and gbuffer_resolve.wgsl; the raster pass is depth_peel.wgsl).

// The peeled triangle + 1, 0 = none; set back to 0 once read, for the next frame (its raster
// pass does not clear it: src/raster/gbuffer.rs, `VISIBILITY_FORMAT`).
@group(0) @binding(6) var second_visibility: texture_storage_2d<r32uint, read_write>;
@group(0) @binding(7) var second_depth_out: texture_storage_2d<r32float, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(second_visibility);
    if (any(id.xy >= size)) {
        return;
    }
    let visible = textureLoad(second_visibility, id.xy).r;
    var depth = 0.0;
    if (visible != 0u) {
        depth = -pixel_surface(triangles[visible - 1u], id.xy, size).view_pos.z;
        textureStore(second_visibility, id.xy, vec4<u32>(0u));
    }
    textureStore(second_depth_out, id.xy, vec4<f32>(depth, 0.0, 0.0, 0.0));
}
