// Depth peeling (seed 000 §2.1; docs/AUTHORS_CODE.md §2.1): the scene again, keeping per pixel the
// nearest surface that lies more than `separation` behind the first layer (linear depth compare, as
// the authors' 2024 code). Appended to gbuffer.wgsl: same vertices, alpha test and culling. Like
// the G-buffer it stores the triangle only (a visibility buffer); depth_peel_resolve.wgsl computes
// the layer's depth at the pixel centres.

struct PeelParams {
    separation: f32,
    _pad0: f32,
    _pad1: f32,
    _pad2: f32,
}

@group(0) @binding(6) var first_layer: texture_2d<f32>;
@group(0) @binding(7) var<uniform> peel: PeelParams;

// A fragment at linear depth `depth` in framebuffer pixel `pixel` belongs to the peeled layer.
// Background in the first layer means nothing is there at all; the first layer itself and
// anything within `separation` behind it is peeled away.
fn peel_keeps(pixel: vec2<u32>, depth: f32) -> bool {
    let first = textureLoad(first_layer, pixel, 0).r;
    return first > 0.0 && depth > first + peel.separation;
}

// Triangles without an alpha test: nothing is interpolated; the fragment's linear depth is
// 1 / w of its position (the clip w of a perspective projection is the linear depth).
@fragment
fn fs_peel(in: VisibilityVertex) -> @location(0) u32 {
    if (!peel_keeps(vec2<u32>(in.clip.xy), 1.0 / in.clip.w)) {
        discard;
    }
    return in.id;
}

@fragment
fn fs_peel_masked(in: VertexOut) -> @location(0) u32 {
    if (!material_passes_alpha(materials[in.material], textures, in.uv)
        || !peel_keeps(vec2<u32>(in.clip.xy), -in.view_pos.z)) {
        discard;
    }
    return in.triangle + 1u;
}
