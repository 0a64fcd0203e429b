// Visibility-buffer resolve: the surface a pixel's visible triangle shows at the pixel centre
// (Burns and Hunt, JCGT 2(2), 2013; why a visibility buffer: gbuffer.wgsl). Appended to
// gbuffer.wgsl (camera, vertices, face normal); the entry points are gbuffer_resolve_main.wgsl
// (depth and normals) and depth_peel_resolve.wgsl (the peeled layer's depth).
//
// The surface point is the triangle's point seen through the pixel centre, which is what the
// rasteriser's perspective-correct interpolation computes at that centre: the pixel's line meets
// the triangle's plane. Both are taken in homogeneous view space, so the same lines hold for
// perspective and orthographic cameras and for triangles that cross the eye plane. The line
// joins A and B, the pixel centre unprojected at NDC depths 1 (near) and 0 (far, or the point at
// infinity of an infinite reversed-Z projection); the plane is π = (n, −n·v0). The meeting point
// is (π·B) A − (π·A) B (e.g. Hartley and Zisserman, "Multiple View Geometry", 2nd ed., §3.2).
// Barycentrics, for the vertex normals only, follow from the point by sub-triangle areas.

// The view-space point of the plane through `v0` with normal `n` seen through NDC point `ndc`.
fn pixel_plane_point(ndc: vec2<f32>, v0: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    let a = camera.inverse_projection * vec4<f32>(ndc, 1.0, 1.0);
    let b = camera.inverse_projection * vec4<f32>(ndc, 0.0, 1.0);
    let plane = vec4<f32>(n, -dot(n, v0));
    let x = dot(plane, b) * a - dot(plane, a) * b;
    return x.xyz / x.w;
}

// `pixel_plane_point` for triangle corners `v0..v2` with face normal `n`, or their centroid where
// the line and the plane give no finite point (a triangle too thin for its normal to be
// computed, or seen exactly edge-on: the rasteriser covers such a pixel only by rounding).
fn pixel_triangle_point(ndc: vec2<f32>, v0: vec3<f32>, v1: vec3<f32>, v2: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    let p = pixel_plane_point(ndc, v0, n);
    // Finite: NaN fails every comparison; infinities fail the bound.
    let finite = all(abs(p) <= vec3<f32>(3.0e38));
    return select((v0 + v1 + v2) / 3.0, p, finite);
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

// The pixel centre of framebuffer pixel `pixel` (of `size`) in NDC (y up, rows down).
fn pixel_ndc(pixel: vec2<u32>, size: vec2<u32>) -> vec2<f32> {
    return (vec2<f32>(pixel) + 0.5) / vec2<f32>(size) * vec2<f32>(2.0, -2.0) + vec2<f32>(-1.0, 1.0);
}

// Where the pixel centre's line meets triangle `tri`: the view-space point, its corners and the
// (unnormalised) face normal.
struct PixelSurface {
    view_pos: vec3<f32>,
    v0: vec3<f32>,
    v1: vec3<f32>,
    v2: vec3<f32>,
    face: vec3<f32>,
}

fn pixel_surface(tri: vec4<u32>, pixel: vec2<u32>, size: vec2<u32>) -> PixelSurface {
    var s: PixelSurface;
    s.v0 = to_view(positions[tri.x].xyz);
    s.v1 = to_view(positions[tri.y].xyz);
    s.v2 = to_view(positions[tri.z].xyz);
    s.face = view_face_normal(tri);
    s.view_pos = pixel_triangle_point(pixel_ndc(pixel, size), s.v0, s.v1, s.v2, s.face);
    return s;
}
