// G-buffer resolve: depth and normal of every pixel from the visibility buffer (appended to
// gbuffer.wgsl and gbuffer_resolve.wgsl); and, for the next frame's occlusion culling
// (shaders/triangle_cull.wgsl), the frame number at which each shown triangle was last seen.

// The visible triangle + 1 where `z_buffer` holds a depth; elsewhere whatever an earlier frame
// left (never cleared: src/raster/gbuffer.rs, `VISIBILITY_FORMAT`).
@group(0) @binding(6) var visibility: texture_2d<u32>;
@group(0) @binding(7) var depth_out: texture_storage_2d<r32float, write>;
@group(0) @binding(8) var normal_out: texture_storage_2d<rgba16float, write>;
// The visibility pass's reversed-Z depth buffer: 0 where no triangle was drawn.
@group(0) @binding(9) var z_buffer: texture_depth_2d;
// The current frame number ([0]) and per triangle t the frame it was last shown ([1 + t]), as
// triangle_cull.wgsl reads them.
@group(0) @binding(10) var<storage, read_write> seen_frame: array<u32>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(visibility);
    if (any(id.xy >= size)) {
        return;
    }
    if (textureLoad(z_buffer, id.xy, 0) == 0.0) {
        textureStore(depth_out, id.xy, vec4<f32>(0.0));
        textureStore(normal_out, id.xy, vec4<f32>(0.0));
        return;
    }
    let visible = textureLoad(visibility, id.xy, 0).r;
    // Every pixel of a triangle writes the same value: which one lands does not matter.
    seen_frame[visible] = seen_frame[0];
    let tri = triangles[visible - 1u];
    let s = pixel_surface(tri, id.xy, size);
    var shading = vec3<f32>(0.0);
    if (SHADING_NORMALS) {
        shading = resolve_shading_normal(tri, plane_barycentrics(s.view_pos, s.v0, s.v1, s.v2, s.face));
    }
    let out = gbuffer_out(s.view_pos, s.face, shading);
    textureStore(depth_out, id.xy, vec4<f32>(out.depth, 0.0, 0.0, 0.0));
    textureStore(normal_out, id.xy, out.normal);
}
