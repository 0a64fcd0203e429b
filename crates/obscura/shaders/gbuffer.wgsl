// G-buffer (raster): linear view depth and camera-facing normals in view space for the
// guard-banded framebuffer, and base colour on request. Vertices are pulled from storage buffers so
// the face normal comes from the triangle itself (the authors' AO uses face normals,
// seed-code-notes §1.1) and the same buffers serve ray tracing. With SHADING_NORMALS the vertex
// normals are interpolated instead (common/vertex_normal.wgsl), turned to the face normal's side.
// Alpha test: `material_passes_alpha` (common/material.wgsl), the lookup the ray tracer and the
// CPU use too.

struct Camera {
    view: mat4x4<f32>,
    projection: mat4x4<f32>,
}


@group(0) @binding(0) var<uniform> camera: Camera;
@group(0) @binding(1) var<storage, read> positions: array<vec4<f32>>;
// Per vertex (u, v, octahedral normal).
@group(0) @binding(2) var<storage, read> attributes: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> triangles: array<vec4<u32>>;
@group(0) @binding(4) var<storage, read> materials: array<Material>;
@group(0) @binding(5) var textures: texture_2d_array<f32>;

// Interpolate vertex normals (the scene's `Normals::Shading`); off: face normals, and the vertex
// shader reads no normals.
override SHADING_NORMALS: bool = false;

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) view_pos: vec3<f32>,
    @location(1) uv: vec2<f32>,
    @location(2) @interpolate(flat) normal: vec3<f32>,
    @location(3) @interpolate(flat) material: u32,
    // Index of the triangle in `triangles` (the stochastic depth map hashes it).
    @location(4) @interpolate(flat) triangle: u32,
    // The vertex normal in view space; zero without SHADING_NORMALS or where a corner lacks one.
    @location(5) shading: vec3<f32>,
}

@vertex
fn vs_main(@builtin(vertex_index) vertex: u32) -> VertexOut {
    let tri = triangles[vertex / 3u];
    let corner = vertex % 3u;
    let index = select(select(tri.z, tri.y, corner == 1u), tri.x, corner == 0u);
    let p0 = positions[tri.x].xyz;
    let p1 = positions[tri.y].xyz;
    let p2 = positions[tri.z].xyz;
    let world = positions[index].xyz;
    let view_pos = (camera.view * vec4<f32>(world, 1.0)).xyz;
    var out: VertexOut;
    out.clip = camera.projection * vec4<f32>(view_pos, 1.0);
    out.view_pos = view_pos;
    out.uv = attributes[index].xy;
    out.normal = (camera.view * vec4<f32>(cross(p1 - p0, p2 - p0), 0.0)).xyz;
    out.material = tri.w;
    out.triangle = vertex / 3u;
    out.shading = vec3<f32>(0.0);
    if (SHADING_NORMALS) {
        let n0 = decode_vertex_normal(attributes[tri.x].zw);
        let n1 = decode_vertex_normal(attributes[tri.y].zw);
        let n2 = decode_vertex_normal(attributes[tri.z].zw);
        // A triangle with a corner lacking a normal keeps its face normal (Scene::surface_normal).
        if (all(vec3<f32>(dot(n0, n0), dot(n1, n1), dot(n2, n2)) > vec3<f32>(0.0))) {
            let n = select(select(n2, n1, corner == 1u), n0, corner == 0u);
            out.shading = (camera.view * vec4<f32>(n, 0.0)).xyz;
        }
    }
    return out;
}

struct GBufferOut {
    @location(0) depth: f32,
    @location(1) normal: vec4<f32>,
}

fn srgb_to_linear(c: vec3<f32>) -> vec3<f32> {
    return select(pow((c + 0.055) / 1.055, vec3<f32>(2.4)), c / 12.92, c <= vec3<f32>(0.04045));
}

fn gbuffer_out(in: VertexOut) -> GBufferOut {
    var n = in.normal;
    let len = length(n);
    n = select(-normalize(in.view_pos), n / len, len > 0.0);
    // Face the camera (seed-code-notes §1.1: flipped when dot(posV, n) > 0).
    if (dot(in.view_pos, n) > 0.0) {
        n = -n;
    }
    if (SHADING_NORMALS) {
        n = oriented_shading_normal(in.shading, n);
    }
    var out: GBufferOut;
    out.depth = -in.view_pos.z;
    out.normal = vec4<f32>(n, 0.0);
    return out;
}

// Materials without an alpha test (every back-face-culled triangle: alpha-tested materials keep
// their back faces, src/raster/gpu_scene.rs): no `discard`, so the hardware may test depth before
// shading.
@fragment
fn fs_opaque(in: VertexOut) -> GBufferOut {
    return gbuffer_out(in);
}

// Triangles that may be alpha-tested.
@fragment
fn fs_main(in: VertexOut) -> GBufferOut {
    if (!material_passes_alpha(materials[in.material], textures, in.uv)) {
        discard;
    }
    return gbuffer_out(in);
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
