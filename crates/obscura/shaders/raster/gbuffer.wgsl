// G-buffer (raster): linear view depth and camera-facing normals in view space for the
// guard-banded framebuffer, and base colour on request. Vertices are pulled from storage buffers so
// the face normal comes from the triangle itself (the authors' AO uses face normals,
// docs/AUTHORS_CODE.md §1.1) and the same buffers serve ray tracing. With SHADING_NORMALS the
// vertex normals are interpolated instead (common/vertex_normal.wgsl), turned to the face normal's
// side. Alpha test: `material_passes_alpha` (common/material.wgsl), the lookup the ray tracer and
// the CPU use too.
//
// The G-buffer itself is a visibility buffer (Burns and Hunt, "The Visibility Buffer: A
// Cache-Friendly Approach to Deferred Shading", JCGT 2(2), 2013): the raster pass stores only
// the visible triangle of each pixel (`fs_visibility*`), and gbuffer_resolve.wgsl computes depth
// and normal from it in compute. Why: on the H100/H200 we measure on, raster work (fragment
// shading and depth testing alike) is slow and compute is fast (BENCHMARKS.md, issue 16), so
// the raster pass does as little per fragment as it can. `vs_main` and `VertexOut` serve the passes that
// need interpolated values per fragment (alpha test, base colour, depth peeling, the SD map).

struct Camera {
    view: mat4x4<f32>,
    projection: mat4x4<f32>,
    inverse_projection: mat4x4<f32>,
}


@group(0) @binding(0) var<uniform> camera: Camera;
@group(0) @binding(1) var<storage, read> positions: array<vec4<f32>>;
// Per vertex (u, v, octahedral normal).
@group(0) @binding(2) var<storage, read> attributes: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> triangles: array<vec4<u32>>;
@group(0) @binding(4) var<storage, read> materials: array<Material>;
@group(0) @binding(5) var textures: texture_2d_array<f32>;
// The triangles the culling pass kept (shaders/raster/triangle_cull.wgsl), each draw's from its first
// triangle on; a draw's vertex `v` is corner `v % 3` of triangle `drawn_triangles[v / 3]`.
@group(1) @binding(0) var<storage, read> drawn_triangles: array<u32>;

// Interpolate vertex normals (the scene's `Normals::Shading`); off: face normals, and the resolve
// reads no normals.
override SHADING_NORMALS: bool = false;

// What the per-fragment passes interpolate (alpha test, base colour, depth peeling, SD map).
struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) view_pos: vec3<f32>,
    @location(1) uv: vec2<f32>,
    @location(2) @interpolate(flat) material: u32,
    // Index of the triangle in `triangles` (the stochastic depth map hashes it).
    @location(3) @interpolate(flat) triangle: u32,
}

// The triangle (index in `triangles`) a draw's `vertex` belongs to.
fn drawn_triangle(vertex: u32) -> u32 {
    return drawn_triangles[vertex / 3u];
}

// The vertex index in `positions` of corner `vertex % 3` of triangle `tri` (non-indexed draws:
// three vertices per triangle).
fn corner_index(tri: vec4<u32>, vertex: u32) -> u32 {
    let corner = vertex % 3u;
    return select(select(tri.z, tri.y, corner == 1u), tri.x, corner == 0u);
}

fn to_view(world: vec3<f32>) -> vec3<f32> {
    return (camera.view * vec4<f32>(world, 1.0)).xyz;
}

// Every raster pass projects with this one expression, so all of them cover the same pixels
// with the same depths (the depth tests of the passes agree).
fn view_to_clip(view_pos: vec3<f32>) -> vec4<f32> {
    return camera.projection * vec4<f32>(view_pos, 1.0);
}

// The triangle's face normal in view space (unnormalised; the winding's side).
fn view_face_normal(tri: vec4<u32>) -> vec3<f32> {
    let p0 = positions[tri.x].xyz;
    let p1 = positions[tri.y].xyz;
    let p2 = positions[tri.z].xyz;
    return (camera.view * vec4<f32>(cross(p1 - p0, p2 - p0), 0.0)).xyz;
}

@vertex
fn vs_main(@builtin(vertex_index) vertex: u32) -> VertexOut {
    let t = drawn_triangle(vertex);
    let tri = triangles[t];
    let index = corner_index(tri, vertex);
    let view_pos = to_view(positions[index].xyz);
    var out: VertexOut;
    out.clip = view_to_clip(view_pos);
    out.view_pos = view_pos;
    out.uv = attributes[index].xy;
    out.material = tri.w;
    out.triangle = t;
    return out;
}

struct GBufferOut {
    depth: f32,
    normal: vec4<f32>,
}

fn srgb_to_linear(c: vec3<f32>) -> vec3<f32> {
    return select(pow((c + 0.055) / 1.055, vec3<f32>(2.4)), c / 12.92, c <= vec3<f32>(0.04045));
}

// The G-buffer's values for a surface point: `view_pos`, its triangle's (unnormalised) face
// normal `face` and the interpolated vertex normal `shading` (zero: none).
fn gbuffer_out(view_pos: vec3<f32>, face: vec3<f32>, shading: vec3<f32>) -> GBufferOut {
    var n = face;
    let len = length(n);
    n = select(-normalize(view_pos), n / len, len > 0.0);
    // Face the camera (docs/AUTHORS_CODE.md §1.1: flipped when dot(posV, n) > 0).
    if (dot(view_pos, n) > 0.0) {
        n = -n;
    }
    if (SHADING_NORMALS) {
        n = oriented_shading_normal(shading, n);
    }
    var out: GBufferOut;
    out.depth = -view_pos.z;
    out.normal = vec4<f32>(n, 0.0);
    return out;
}

// The visibility pass: the triangle's index + 1 per pixel where a triangle is drawn (the target is
// never cleared: the depth buffer tells where, src/raster/gbuffer.rs `VISIBILITY_FORMAT`).
struct VisibilityVertex {
    @builtin(position) clip: vec4<f32>,
    @location(0) @interpolate(flat) id: u32,
}

// Only the position and the triangle: nothing else is interpolated.
@vertex
fn vs_visibility(@builtin(vertex_index) vertex: u32) -> VisibilityVertex {
    let t = drawn_triangle(vertex);
    let tri = triangles[t];
    var out: VisibilityVertex;
    out.clip = view_to_clip(to_view(positions[corner_index(tri, vertex)].xyz));
    out.id = t + 1u;
    return out;
}

// Triangles that are never alpha-tested (culled or double-sided, src/raster/gpu_scene.rs): no
// `discard`, so the hardware may test depth before shading.
@fragment
fn fs_visibility(in: VisibilityVertex) -> @location(0) u32 {
    return in.id;
}

// Alpha-tested triangles: the texel decides.
@fragment
fn fs_visibility_masked(in: VertexOut) -> @location(0) u32 {
    if (!material_passes_alpha(materials[in.material], textures, in.uv)) {
        discard;
    }
    return in.triangle + 1u;
}

// Base colour (linear; the target is sRGB), drawn only when asked for (composites), with the same
// draws and depth test as the G-buffer so the same fragments win.
@fragment
fn fs_albedo(in: VertexOut) -> @location(0) vec4<f32> {
    let material = materials[in.material];
    if (!material_passes_alpha(material, textures, in.uv)) {
        discard;
    }
    let t = material_texel(material, textures, in.uv);
    let color = material.base_color * vec4<f32>(srgb_to_linear(t.rgb), t.a);
    return vec4<f32>(color.rgb, 1.0);
}

