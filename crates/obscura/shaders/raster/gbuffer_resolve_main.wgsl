// G-buffer resolve: depth and normal of every pixel from the visibility buffer (appended to
// gbuffer.wgsl, gbuffer_resolve.wgsl and the header that reads the visibility pass's output,
// `visible_triangle`: visibility_target_load.wgsl or visibility_words_load.wgsl); and, for
// the next frame's occlusion culling (shaders/raster/triangle_cull.wgsl), the frame number at which
// each shown triangle was last seen.

const VISIBILITY_BINDING: u32 = 6u;
const Z_BUFFER_BINDING: u32 = 9u;
@group(0) @binding(7) var depth_out: texture_storage_2d<r32float, write>;
@group(0) @binding(8) var normal_out: texture_storage_2d<rgba16float, write>;
// The current frame number ([0]) and per triangle t the frame it was last shown ([1 + t]), as
// triangle_cull.wgsl reads them.
@group(0) @binding(10) var<storage, read_write> seen_frame: array<u32>;
// The visible triangle + 1 per pixel (0: none), where the G-buffer keeps it (two-phase BVH rays'
// blocked proof, sources/bvh_rays_proof.wgsl); a 1×1 texture left alone otherwise.
@group(0) @binding(11) var triangle_out: texture_storage_2d<r32uint, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(depth_out);
    if (any(id.xy >= size)) {
        return;
    }
    let visible = visible_triangle(id.xy, size);
    if (all(textureDimensions(triangle_out) == size)) {
        textureStore(triangle_out, id.xy, vec4<u32>(visible));
    }
    if (visible == 0u) {
        textureStore(depth_out, id.xy, vec4<f32>(0.0));
        textureStore(normal_out, id.xy, vec4<f32>(0.0));
        return;
    }
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
