// G-buffer resolve: depth and normal of every pixel from the visibility buffer's triangle
// (Burns and Hunt, JCGT 2(2), 2013; why a visibility buffer: gbuffer.wgsl). Appended to
// gbuffer.wgsl: the same camera, vertices, face normal and `gbuffer_out`.
//
// The surface point is the triangle's point seen through the pixel centre, which is what the
// rasteriser's perspective-correct interpolation computes at that centre: the pixel's line meets
// the triangle's plane. Both are taken in homogeneous view space, so the same lines hold for
// perspective and orthographic cameras and for triangles that cross the eye plane. The line
// joins A and B, the pixel centre unprojected at NDC depths 1 (near) and 0 (far, or the point at
// infinity of an infinite reversed-Z projection); the plane is π = (n, −n·v0). The meeting point
// is (π·B) A − (π·A) B (e.g. Hartley and Zisserman, "Multiple View Geometry", 2nd ed., §3.2).
// Barycentrics, for the vertex normals only, follow from the point by sub-triangle areas.

@group(0) @binding(6) var visibility: texture_2d<u32>;
@group(0) @binding(7) var depth_out: texture_storage_2d<r32float, write>;
@group(0) @binding(8) var normal_out: texture_storage_2d<rgba16float, write>;

// The view-space point of the plane through `v0` with normal `n` seen through NDC point `ndc`.
fn pixel_plane_point(ndc: vec2<f32>, v0: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    let a = camera.inverse_projection * vec4<f32>(ndc, 1.0, 1.0);
    let b = camera.inverse_projection * vec4<f32>(ndc, 0.0, 1.0);
    let plane = vec4<f32>(n, -dot(n, v0));
    let x = dot(plane, b) * a - dot(plane, a) * b;
    return x.xyz / x.w;
}

// Barycentrics of point `p` in the plane of the triangle `v` with normal `n` (= (v1 − v0) ×
// (v2 − v0) up to its length).
fn plane_barycentrics(p: vec3<f32>, v0: vec3<f32>, v1: vec3<f32>, v2: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    let e = vec3<f32>(
        dot(cross(v1 - p, v2 - p), n),
        dot(cross(v2 - p, v0 - p), n),
        dot(cross(v0 - p, v1 - p), n),
    );
    return e / (e.x + e.y + e.z);
}

// The interpolated vertex normal in view space (zero where a corner lacks one).
fn resolve_shading_normal(tri: vec4<u32>, b: vec3<f32>) -> vec3<f32> {
    let n0 = decode_vertex_normal(attributes[tri.x].zw);
    let n1 = decode_vertex_normal(attributes[tri.y].zw);
    let n2 = decode_vertex_normal(attributes[tri.z].zw);
    // A triangle with a corner lacking a normal keeps its face normal (Scene::surface_normal).
    if (!all(vec3<f32>(dot(n0, n0), dot(n1, n1), dot(n2, n2)) > vec3<f32>(0.0))) {
        return vec3<f32>(0.0);
    }
    let n = b.x * n0 + b.y * n1 + b.z * n2;
    return (camera.view * vec4<f32>(n, 0.0)).xyz;
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(visibility);
    if (any(id.xy >= size)) {
        return;
    }
    let visible = textureLoad(visibility, id.xy, 0).r;
    if (visible == 0u) {
        textureStore(depth_out, id.xy, vec4<f32>(0.0));
        textureStore(normal_out, id.xy, vec4<f32>(0.0));
        return;
    }
    let tri = triangles[visible - 1u];
    let v0 = to_view(positions[tri.x].xyz);
    let v1 = to_view(positions[tri.y].xyz);
    let v2 = to_view(positions[tri.z].xyz);
    // The pixel centre in NDC (y up, framebuffer rows down).
    let ndc = (vec2<f32>(id.xy) + 0.5) / vec2<f32>(size) * vec2<f32>(2.0, -2.0) + vec2<f32>(-1.0, 1.0);
    let face = view_face_normal(tri);
    let view_pos = pixel_plane_point(ndc, v0, face);
    var shading = vec3<f32>(0.0);
    if (SHADING_NORMALS) {
        shading = resolve_shading_normal(tri, plane_barycentrics(view_pos, v0, v1, v2, face));
    }
    let out = gbuffer_out(view_pos, face, shading);
    textureStore(depth_out, id.xy, vec4<f32>(out.depth, 0.0, 0.0, 0.0));
    textureStore(normal_out, id.xy, out.normal);
}
