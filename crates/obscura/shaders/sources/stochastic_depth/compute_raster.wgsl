// The stochastic depth map rasterised in compute (ours; issue 16; src/sources/stochastic_depth/
// compute_raster.rs). Appended to gbuffer.wgsl, common/hash.wgsl, common/material.wgsl and
// map.wgsl: the same triangles, camera, alpha test, and Alg. 1 per fragment (sd_fragment, seed
// 001 §3.1). Why: the map's raster pass spends its time on fragments the hardware makes, not on
// the shader's atomics (without any atomic it kept 92 % of its time on an H200, BENCHMARKS.md),
// and the H100/H200 we measure on have few raster units and much compute. The map is
// order-independent (every fragment's store is an atomicMax), so any order of fragments, and any
// fragment made twice (the same pixel and triangle draw the same samples and store the same
// depth), gives the same map: a rasteriser in compute needs no ordering and no depth buffer.
//
// Two passes over the frame's triangles:
// - `sd_raster_bin`, one invocation per triangle: projects it as vs_depth does, drops what the
//   hardware would draw nothing of (outside the frustum, back faces where culled, no pixel centre
//   inside), leaves the triangles that cross the near plane to the hardware (counted in
//   `cr_counts[CR_NEAR]`; they need clipping), rasterises small ones itself, and for larger ones
//   writes a record and items of up to CR_ITEM_TILES 8×8 tiles of their bounding box.
// - `sd_raster_tiles`, workgroups of 8×8 invocations, one pixel each, over the items.
// Coverage is the rasteriser's: pixel centres, corners snapped to 1/256 pixel (8 sub-pixel bits,
// what Vulkan devices commonly have), the top-left rule on exact ties; depth and texture
// coordinates interpolated perspective-correct at the pixel centre. An edge two triangles share is
// evaluated from the same end point with the same operands by both (cr_edge), so a pixel centre
// on it, or within rounding of it, goes to exactly one of them.

struct SdComputeRaster {
    // The map's size in pixels (its own band included).
    size: vec2<u32>,
    triangle_count: u32,
    // Triangles 0..culled_count cull back faces; opaque_count.. are alpha-tested.
    culled_count: u32,
    opaque_count: u32,
    item_capacity: u32,
    record_capacity: u32,
    _pad: u32,
}

// A triangle left to the tile pass: corners on screen in the order that makes its area
// positive (corner 1 and 2 swapped where `swapped`), per corner 1 / w and linear depth, and the
// pixel centres of its bounding box.
struct CrRecord {
    p01: vec4<f32>,
    p2: vec2<f32>,
    first: vec2<u32>,
    last: vec2<u32>,
    tiles_x: u32,
    triangle: u32,
    inv_w: vec3<f32>,
    swapped: u32,
    depth: vec3<f32>,
    _pad: u32,
}

// cr_counts: items written, records written, triangles left to the hardware, items that did not
// fit (their triangles were left to the hardware too).
const CR_ITEMS: u32 = 0u;
const CR_RECORDS: u32 = 1u;
const CR_NEAR: u32 = 2u;
const CR_OVERFLOW: u32 = 3u;
// A triangle whose bounding box holds at most this many pixel centres is rasterised by its bin
// invocation; larger ones go to the tile pass.
const CR_SMALL_PIXELS: u32 = 16u;
// Tiles of one item (one workgroup of the tile pass takes them in turn).
const CR_ITEM_TILES: u32 = 16u;
// Sub-pixel steps per pixel of the snapped corners.
const CR_SUBPIXEL: f32 = 256.0;

@group(2) @binding(0) var<uniform> cr: SdComputeRaster;
@group(2) @binding(1) var<storage, read_write> cr_counts: array<atomic<u32>, 4>;
// (record, first tile) per item.
@group(2) @binding(2) var<storage, read_write> cr_items: array<vec2<u32>>;
@group(2) @binding(3) var<storage, read_write> cr_records: array<CrRecord>;
// The triangles left to the hardware (near plane, overflow), each group's from its first triangle
// on (the group's draw reads them as `drawn_triangles`), and the three groups' `draw_indirect`
// arguments, whose vertex counts grow by three a triangle.
@group(2) @binding(4) var<storage, read_write> cr_left: array<u32>;
@group(2) @binding(5) var<storage, read_write> cr_left_args: array<atomic<u32>, 12>;

// One edge of an oriented triangle, from the end point that sorts first (x, then y): `origin`,
// `direction` to the other end, `sign` +1 where that is the triangle's own direction, and
// whether a pixel centre exactly on it belongs to the triangle (`owned`: the top-left rule in
// framebuffer coordinates, y down, for triangles of positive area).
struct CrEdge {
    origin: vec2<f32>,
    direction: vec2<f32>,
    sign: f32,
    owned: bool,
}

fn cr_edge(a: vec2<f32>, b: vec2<f32>) -> CrEdge {
    let forward = a.x < b.x || (a.x == b.x && a.y < b.y);
    var e: CrEdge;
    e.origin = select(b, a, forward);
    e.direction = select(a - b, b - a, forward);
    e.sign = select(-1.0, 1.0, forward);
    let d = b - a;
    e.owned = d.y < 0.0 || (d.y == 0.0 && d.x > 0.0);
    return e;
}

// The edge function of pixel centre `p`: positive inside, the same magnitude for both triangles
// of a shared edge.
fn cr_edge_at(e: CrEdge, p: vec2<f32>) -> f32 {
    let o = p - e.origin;
    return e.sign * (e.direction.x * o.y - e.direction.y * o.x);
}

fn cr_covers(e: CrEdge, value: f32) -> bool {
    return value > 0.0 || (value == 0.0 && e.owned);
}

// One triangle set up for its pixels.
struct CrTriangle {
    edges: array<CrEdge, 3>,
    inv_w: vec3<f32>,
    depth: vec3<f32>,
    triangle: u32,
    swapped: bool,
}

fn cr_triangle(p0: vec2<f32>, p1: vec2<f32>, p2: vec2<f32>) -> array<CrEdge, 3> {
    // Edge i lies opposite corner i, so its function is corner i's (unnormalised) barycentric.
    return array<CrEdge, 3>(cr_edge(p1, p2), cr_edge(p2, p0), cr_edge(p0, p1));
}

// The fragment of `t` at `pixel`, if its centre is covered: Alg. 1 for it (sd_fragment), after
// the alpha test and the request mask where they apply.
fn cr_fragment(t: CrTriangle, pixel: vec2<u32>) {
    let p = vec2<f32>(pixel) + 0.5;
    let e = vec3<f32>(
        cr_edge_at(t.edges[0], p),
        cr_edge_at(t.edges[1], p),
        cr_edge_at(t.edges[2], p),
    );
    if (!(cr_covers(t.edges[0], e.x) && cr_covers(t.edges[1], e.y) && cr_covers(t.edges[2], e.z))) {
        return;
    }
    // Perspective-correct weights (the rasteriser's interpolation of a varying).
    let w = e * t.inv_w;
    let total = w.x + w.y + w.z;
    let depth = dot(w, t.depth) / total;
    if (t.triangle >= cr.opaque_count) {
        let tri = triangles[t.triangle];
        let c1 = select(tri.y, tri.z, t.swapped);
        let c2 = select(tri.z, tri.y, t.swapped);
        let uv = (w.x * attributes[tri.x].xy + w.y * attributes[c1].xy + w.z * attributes[c2].xy)
            / total;
        if (!material_passes_alpha(materials[tri.w], textures, uv)) {
            return;
        }
    }
    if (!cr_requested(pixel)) {
        return;
    }
    sd_fragment(pixel, depth, t.triangle);
}

@compute @workgroup_size(64)
fn sd_raster_bin(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let t = gid.x + gid.y * groups.x * 64u;
    if (t >= cr.triangle_count) {
        return;
    }
    let tri = triangles[t];
    var clip: array<vec4<f32>, 3>;
    var depth: vec3<f32>;
    for (var i = 0u; i < 3u; i++) {
        let view_pos = to_view(positions[tri[i]].xyz);
        clip[i] = view_to_clip(view_pos);
        depth[i] = -view_pos.z;
    }
    // Outside one plane of the frustum with every corner: nothing drawn.
    var outside = vec4<bool>(true);
    var in_front = true;
    var crosses = false;
    for (var i = 0u; i < 3u; i++) {
        let c = clip[i];
        outside = outside & vec4<bool>((c.x < -c.w), (c.x > c.w), (c.y < -c.w), (c.y > c.w));
        // Reversed Z: in front of the near plane is z > w.
        in_front = in_front && c.z > c.w;
        crosses = crosses || c.z > c.w || c.z < 0.0;
    }
    if (any(outside) || in_front) {
        return;
    }
    if (crosses) {
        cr_leave(t);
        return;
    }
    let size = vec2<f32>(cr.size);
    var p: array<vec2<f32>, 3>;
    for (var i = 0u; i < 3u; i++) {
        let ndc = clip[i].xy / clip[i].w;
        let s = vec2<f32>(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5) * size;
        p[i] = round(s * CR_SUBPIXEL) / CR_SUBPIXEL;
    }
    let area = (p[1].x - p[0].x) * (p[2].y - p[0].y) - (p[1].y - p[0].y) * (p[2].x - p[0].x);
    // Front faces are counter-clockwise in normalised device coordinates (y up), so of negative
    // area here (y down).
    if (area == 0.0 || (t < cr.culled_count && area > 0.0)) {
        return;
    }
    let swapped = area < 0.0;
    var r: CrTriangle;
    r.triangle = t;
    r.swapped = swapped;
    r.inv_w = 1.0 / vec3<f32>(clip[0].w, clip[1].w, clip[2].w);
    r.depth = depth;
    if (swapped) {
        let q = p[1];
        p[1] = p[2];
        p[2] = q;
        r.inv_w = r.inv_w.xzy;
        r.depth = r.depth.xzy;
    }
    r.edges = cr_triangle(p[0], p[1], p[2]);
    // The pixel centres of the bounding box, within the map.
    let lo = min(min(p[0], p[1]), p[2]);
    let hi = max(max(p[0], p[1]), p[2]);
    let first = max(ceil(lo - 0.5), vec2<f32>(0.0));
    let last = min(floor(hi - 0.5), size - 1.0);
    if (any(first > last)) {
        return;
    }
    let first_px = vec2<u32>(first);
    let extent = vec2<u32>(last - first) + 1u;
    if (extent.x * extent.y <= CR_SMALL_PIXELS) {
        for (var y = 0u; y < extent.y; y++) {
            for (var x = 0u; x < extent.x; x++) {
                cr_fragment(r, first_px + vec2<u32>(x, y));
            }
        }
        return;
    }
    let tiles = (extent + 7u) / 8u;
    let tile_count = tiles.x * tiles.y;
    let item_count = (tile_count + CR_ITEM_TILES - 1u) / CR_ITEM_TILES;
    let record = atomicAdd(&cr_counts[CR_RECORDS], 1u);
    if (record >= cr.record_capacity) {
        atomicAdd(&cr_counts[CR_OVERFLOW], 1u);
        cr_leave(t);
        return;
    }
    var rec: CrRecord;
    rec.p01 = vec4<f32>(p[0], p[1]);
    rec.p2 = p[2];
    rec.first = first_px;
    rec.last = vec2<u32>(last);
    rec.tiles_x = tiles.x;
    rec.triangle = t;
    rec.inv_w = r.inv_w;
    rec.swapped = u32(swapped);
    rec.depth = r.depth;
    cr_records[record] = rec;
    // Items past the capacity are not written (the tile pass reads only the first
    // `item_capacity`); the triangle is then drawn by the hardware as well, and the fragments
    // both make store the same depths twice.
    let base = atomicAdd(&cr_counts[CR_ITEMS], item_count);
    for (var i = 0u; i < item_count && base + i < cr.item_capacity; i++) {
        cr_items[base + i] = vec2<u32>(record, i * CR_ITEM_TILES);
    }
    if (base + item_count > cr.item_capacity) {
        atomicAdd(&cr_counts[CR_OVERFLOW], 1u);
        cr_leave(t);
    }
}

// Triangle `t` drawn by the hardware after all, by its group's draw.
fn cr_leave(t: u32) {
    atomicAdd(&cr_counts[CR_NEAR], 1u);
    var group = 2u;
    var start = cr.opaque_count;
    if (t < cr.culled_count) {
        group = 0u;
        start = 0u;
    } else if (t < cr.opaque_count) {
        group = 1u;
        start = cr.culled_count;
    }
    let slot = atomicAdd(&cr_left_args[4u * group], 3u) / 3u;
    cr_left[start + slot] = t;
}

@compute @workgroup_size(8, 8)
fn sd_raster_tiles(
    @builtin(local_invocation_id) local: vec3<u32>,
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
) {
    let count = min(atomicLoad(&cr_counts[CR_ITEMS]), cr.item_capacity);
    let stride = groups.x * groups.y;
    for (var i = group.x + group.y * groups.x; i < count; i += stride) {
        let item = cr_items[i];
        let rec = cr_records[item.x];
        var r: CrTriangle;
        r.edges = cr_triangle(rec.p01.xy, rec.p01.zw, rec.p2);
        r.inv_w = rec.inv_w;
        r.depth = rec.depth;
        r.triangle = rec.triangle;
        r.swapped = rec.swapped != 0u;
        let tiles_y = (rec.last.y - rec.first.y) / 8u + 1u;
        let end = min(item.y + CR_ITEM_TILES, rec.tiles_x * tiles_y);
        for (var k = item.y; k < end; k++) {
            let pixel = rec.first + vec2<u32>(k % rec.tiles_x, k / rec.tiles_x) * 8u + local.xy;
            if (all(pixel <= rec.last)) {
                cr_fragment(r, pixel);
            }
        }
    }
}
