// The occlusion pyramid (src/raster/occlusion_pyramid.rs; layout: common/occlusion_pyramid.wgsl):
// the farthest reversed-Z depth per tile of what the first raster phase drew, read by the second
// phase's triangle culling (shaders/triangle_cull.wgsl). Appended to gbuffer.wgsl and
// gbuffer_resolve.wgsl. Two-phase occlusion culling as in
// Haar and Aaltonen, "GPU-Driven Rendering Pipelines" (SIGGRAPH 2015 Advances course): what was
// visible last frame is drawn first, and its depths decide which of the other triangles can be
// seen at all.
//
// One workgroup covers 2^PYRAMID_LAST_LEVEL = 64 pixels square: each invocation takes the
// farthest of 4×4 pixels (level 2), then the workgroup halves its tile of them in workgroup
// memory level by level, so each pixel is read once and every level is written in one dispatch.
//
// The depths come from the visibility buffer, not from the depth buffer (which no shader samples:
// src/raster/gbuffer.rs, `Z_FORMAT`): each pixel's triangle at the pixel centre, as the resolve
// finds it, kept within the depths of the triangle's corners (the rasteriser's depth there is a
// convex combination of theirs) and moved farther by PIXEL_SLACK, so the pyramid is never nearer
// than what the rasteriser stored.

@group(0) @binding(6) var visibility: texture_2d<u32>;
@group(0) @binding(7) var<storage, read_write> pyramid: array<f32>;

// Relative: covers the rounding between the resolve's plane point and the rasteriser's depth.
const PIXEL_SLACK: f32 = 1.0e-6;

// Reversed-Z depth of a view-space point (w > 0 in front of the eye).
fn clip_depth(view_pos: vec3<f32>) -> vec2<f32> {
    let c = view_to_clip(view_pos);
    return vec2<f32>(c.z, c.w);
}

// A depth no nearer than the rasteriser's at pixel `p` (of `size`), 0 (the far end) where nothing
// was drawn or the triangle reaches behind the eye.
fn drawn_depth(p: vec2<u32>, size: vec2<u32>) -> f32 {
    let visible = textureLoad(visibility, p, 0).r;
    if (visible == 0u) {
        return 0.0;
    }
    let tri = triangles[visible - 1u];
    let s = pixel_surface(tri, p, size);
    let a = clip_depth(s.v0);
    let b = clip_depth(s.v1);
    let c = clip_depth(s.v2);
    let d = clip_depth(s.view_pos);
    if (!(a.y > 0.0 && b.y > 0.0 && c.y > 0.0 && d.y > 0.0)) {
        return 0.0;
    }
    let lo = min(a.x / a.y, min(b.x / b.y, c.x / c.y));
    let hi = max(a.x / a.y, max(b.x / b.y, c.x / c.y));
    // A degenerate plane point (NaN) falls back on the farthest corner.
    let z = d.x / d.y;
    return select(lo, clamp(z, lo, hi), z == z) * (1.0 - PIXEL_SLACK);
}

const SIDE: u32 = 16u;
var<workgroup> tiles: array<f32, 256>; // SIDE * SIDE

fn store_tile(size: vec2<u32>, level: u32, tile: vec2<u32>, far: f32) {
    if (all(tile < pyramid_level_size(size, level))) {
        pyramid[pyramid_index(size, level, tile)] = far;
    }
}

@compute @workgroup_size(16, 16)
fn main(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_id) local: vec3<u32>) {
    let size = textureDimensions(visibility);
    let tile = group.xy * SIDE + local.xy;
    // Pixels outside the framebuffer count as the near plane (1), which no minimum keeps: no
    // triangle's pixels lie there.
    var far = 1.0;
    for (var y = 0u; y < 4u; y++) {
        for (var x = 0u; x < 4u; x++) {
            let p = tile * 4u + vec2<u32>(x, y);
            if (all(p < size)) {
                far = min(far, drawn_depth(p, size));
            }
        }
    }
    store_tile(size, PYRAMID_FIRST_LEVEL, tile, far);
    tiles[local.y * SIDE + local.x] = far;
    var width = SIDE;
    for (var level = PYRAMID_FIRST_LEVEL + 1u; level <= PYRAMID_LAST_LEVEL; level++) {
        width /= 2u;
        let in_level = all(local.xy < vec2<u32>(width));
        workgroupBarrier();
        if (in_level) {
            let i = local.y * 2u * SIDE + local.x * 2u;
            far = min(min(tiles[i], tiles[i + 1u]), min(tiles[i + SIDE], tiles[i + SIDE + 1u]));
        }
        workgroupBarrier();
        if (in_level) {
            tiles[local.y * SIDE + local.x] = far;
            store_tile(size, level, group.xy * width + local.xy, far);
        }
    }
}
