// The occlusion pyramid (src/raster/occlusion_pyramid.rs; layout: common/occlusion_pyramid.wgsl):
// the farthest depth per tile of the first raster phase's reversed-Z depth buffer, read by the
// second phase's triangle culling (shaders/raster/triangle_cull.wgsl). Two-phase occlusion culling as in
// Haar and Aaltonen, "GPU-Driven Rendering Pipelines" (SIGGRAPH 2015 Advances course): what was
// visible last frame is drawn first, and its depths decide which of the other triangles can be
// seen at all.
//
// One workgroup covers 2^PYRAMID_LAST_LEVEL = 64 pixels square: each invocation copies its 4×4
// pixels (level 0), writes the farthest of each 2×2 of them (level 1) and of all 16 (level 2),
// then the workgroup halves its tile of those in workgroup memory level by level, so the depth
// buffer is read once and every level is written in one dispatch.

@group(0) @binding(0) var z: texture_depth_2d;
@group(0) @binding(1) var<storage, read_write> pyramid: array<f32>;

const SIDE: u32 = 16u;
var<workgroup> tiles: array<f32, 256>; // SIDE * SIDE

fn store_tile(size: vec2<u32>, level: u32, tile: vec2<u32>, far: f32) {
    if (all(tile < pyramid_level_size(size, level))) {
        pyramid[pyramid_index(size, level, tile)] = far;
    }
}

@compute @workgroup_size(16, 16)
fn main(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_id) local: vec3<u32>) {
    let size = textureDimensions(z);
    let tile = group.xy * SIDE + local.xy;
    // Pixels outside the framebuffer count as the near plane (1), which no minimum keeps: no
    // triangle's pixels lie there.
    var quads = vec4<f32>(1.0);
    for (var y = 0u; y < 4u; y++) {
        for (var x = 0u; x < 4u; x++) {
            let p = tile * 4u + vec2<u32>(x, y);
            if (all(p < size)) {
                let d = textureLoad(z, p, 0);
                store_tile(size, 0u, p, d);
                let q = (y / 2u) * 2u + x / 2u;
                quads[q] = min(quads[q], d);
            }
        }
    }
    for (var q = 0u; q < 4u; q++) {
        store_tile(size, 1u, tile * 2u + vec2<u32>(q % 2u, q / 2u), quads[q]);
    }
    var far = min(min(quads.x, quads.y), min(quads.z, quads.w));
    store_tile(size, 2u, tile, far);
    tiles[local.y * SIDE + local.x] = far;
    var width = SIDE;
    for (var level = 3u; level <= PYRAMID_LAST_LEVEL; level++) {
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
