// The stochastic depth map rasterised in compute (ours; issue 16; src/sources/stochastic_depth/
// compute_raster.rs). Appended to gbuffer.wgsl, common/hash.wgsl, common/material.wgsl, map.wgsl
// and gbuffer_resolve.wgsl: the same triangles, camera, alpha test, and Alg. 1 per fragment
// (sd_fragment, seed 001 §3.1). Why: the map's raster pass spends its time on fragments the
// hardware makes, not on the shader's atomics (without any atomic it kept 92 % of its time on an
// H200, BENCHMARKS.md), and the H100/H200 we measure on have few raster units and much compute.
// The map is order-independent (every fragment's store is an atomicMax), so any order of
// fragments, and any fragment made twice (the same pixel and triangle draw the same samples and
// store the same depth), gives the same map: a rasteriser in compute needs no ordering and no
// depth buffer.
//
// Two passes over the frame's triangles:
// - `sd_raster_bin`, one invocation per triangle: projects it as vs_depth does, drops what the
//   hardware would draw nothing of (outside the frustum, back faces where culled, no pixel centre
//   inside), clips what crosses the near plane or reaches past a guard band as the hardware does
//   (Sutherland-Hodgman), rasterises small triangles in its workgroup (their covered pixels
//   queued, then shaded an invocation each), and for larger ones writes a record and the items
//   (runs of up to CR_ITEM_TILES 8×8 tiles of their bounding box) they may touch. Triangles
//   whose record or items do not fit their buffers are left to the hardware (the map's raster
//   pass draws them).
// - `sd_raster_tiles`, workgroups of 64 invocations over the items: the covered pixels of the
//   item's tiles the triangle may touch queued, then shaded an invocation each.
// Coverage is the rasteriser's: pixel centres, corners snapped to 1/256 pixel (8 sub-pixel bits,
// what Vulkan devices commonly have), the top-left rule on exact ties. An edge two triangles
// share is evaluated from the same end point with the same operands by both (cr_edge), so a pixel
// centre on it, or within rounding of it, goes to exactly one of them. Texture coordinates are
// interpolated perspective-correct at the pixel centre. The depth is the G-buffer's own: where the
// pixel centre's line meets the triangle's plane (gbuffer_resolve.wgsl's pixel_plane_point), not
// an interpolation between corners snapped to the sub-pixel grid. Why: a surface's own fragment
// must not pass for a hidden one, and at grazing angles a 1/256-pixel shift of a corner moves the
// interpolated depth by more than the separation the first layer is skipped by (on the test scene
// of compute_raster/tests.rs with a floor reaching behind the camera: 0.015 at 21 m, against a
// separation of 0.01).

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

// A triangle left to the tile pass (or a part of one, after clipping): corners on screen in the
// order that makes its area positive, per corner 1 / w and texture coordinates, its material, the
// pixel centres of its bounding box, and the whole triangle's first corner and face normal in
// view space (its plane).
struct CrRecord {
    p01: vec4<f32>,
    p2: vec2<f32>,
    first: vec2<u32>,
    last: vec2<u32>,
    tiles_x: u32,
    triangle: u32,
    inv_w: vec3<f32>,
    material: u32,
    v0: vec3<f32>,
    _pad: u32,
    face: vec3<f32>,
    _pad1: u32,
    uv01: vec4<f32>,
    uv2: vec2<f32>,
    _pad2: vec2<u32>,
}

// cr_counts: items written, records written, triangles left to the hardware, records or item
// runs that did not fit (their triangles are left to the hardware), and the fragments each pass
// shaded (pixel centres covered and requested, before the alpha and first-layer tests; `bench`
// reports them as the passes' fragments).
const CR_ITEMS: u32 = 0u;
const CR_RECORDS: u32 = 1u;
const CR_LEFT: u32 = 2u;
const CR_OVERFLOW: u32 = 3u;
const CR_SHADED_BIN: u32 = 4u;
const CR_SHADED_TILES: u32 = 5u;
// A triangle whose bounding box holds at most this many pixel centres is rasterised by the bin
// pass; larger ones go to the tile pass. At most 16 (the bin pass's queue entries index a box's
// pixels in 4 bits).
const CR_SMALL_PIXELS: u32 = 16u;
// Tiles of one item (one workgroup of the tile pass takes them in turn).
const CR_ITEM_TILES: u32 = 16u;
// The record of an item slot left empty.
const CR_NO_RECORD: u32 = 0xffffffffu;
// Sub-pixel steps per pixel of the snapped corners.
const CR_SUBPIXEL: f32 = 256.0;

@group(2) @binding(0) var<uniform> cr: SdComputeRaster;
@group(2) @binding(1) var<storage, read_write> cr_counts: array<atomic<u32>, 6>;
// (record, first tile) per item.
@group(2) @binding(2) var<storage, read_write> cr_items: array<vec2<u32>>;
@group(2) @binding(3) var<storage, read_write> cr_records: array<CrRecord>;
// The triangles left to the hardware, each group's from its first triangle
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

// One triangle set up for its pixels: its edges, per corner 1 / w and the texture coordinates
// (read only for alpha-tested materials), and the whole triangle's plane (first corner and face
// normal in view space).
struct CrTriangle {
    edges: array<CrEdge, 3>,
    inv_w: vec3<f32>,
    uv: array<vec2<f32>, 3>,
    triangle: u32,
    material: u32,
    v0: vec3<f32>,
    face: vec3<f32>,
}

fn cr_triangle(p0: vec2<f32>, p1: vec2<f32>, p2: vec2<f32>) -> array<CrEdge, 3> {
    // Edge i lies opposite corner i, so its function is corner i's (unnormalised) barycentric.
    return array<CrEdge, 3>(cr_edge(p1, p2), cr_edge(p2, p0), cr_edge(p0, p1));
}

// The triangle of record `rec`, set up for its pixels.
fn cr_triangle_of(rec: CrRecord) -> CrTriangle {
    var r: CrTriangle;
    r.edges = cr_triangle(rec.p01.xy, rec.p01.zw, rec.p2);
    r.inv_w = rec.inv_w;
    r.v0 = rec.v0;
    r.face = rec.face;
    r.triangle = rec.triangle;
    r.material = rec.material;
    r.uv = array<vec2<f32>, 3>(rec.uv01.xy, rec.uv01.zw, rec.uv2);
    return r;
}

// The edge functions of `t` at the centre of `pixel` (corner i's unnormalised barycentrics).
fn cr_edges_at(t: CrTriangle, pixel: vec2<u32>) -> vec3<f32> {
    let p = vec2<f32>(pixel) + 0.5;
    return vec3<f32>(
        cr_edge_at(t.edges[0], p),
        cr_edge_at(t.edges[1], p),
        cr_edge_at(t.edges[2], p),
    );
}

// Whether `t` covers the pixel centre its edge functions `e` were taken at, and the request
// mask (cr_requested, generated by compute_raster.rs) asks for `pixel`: what decides, before
// anything is shaded, whether `pixel` gets a fragment to shade.
fn cr_covered(t: CrTriangle, pixel: vec2<u32>, e: vec3<f32>) -> bool {
    return cr_covers(t.edges[0], e.x) && cr_covers(t.edges[1], e.y) && cr_covers(t.edges[2], e.z)
        && cr_requested(pixel);
}

// The fragment of `t` at covered `pixel` (edge functions `e`): Alg. 1 for it (sd_fragment),
// after the alpha test where it applies.
fn cr_shade(t: CrTriangle, pixel: vec2<u32>, e: vec3<f32>) {
    if (t.triangle >= cr.opaque_count) {
        // Perspective-correct weights (the rasteriser's interpolation of a varying).
        let w = e * t.inv_w;
        let uv = (w.x * t.uv[0] + w.y * t.uv[1] + w.z * t.uv[2]) / (w.x + w.y + w.z);
        if (!material_passes_alpha(materials[t.material], textures, uv)) {
            return;
        }
    }
    // A covered pixel centre's line meets the triangle's plane in one point in front of the
    // camera; only a triangle too thin for its face normal (covering a pixel centre by rounding
    // alone) gives none, and no fragment.
    let depth = -pixel_plane_point(pixel_ndc(pixel, cr.size), t.v0, t.face).z;
    if (!(depth > 0.0 && depth <= 3.0e38)) {
        return;
    }
    sd_fragment(pixel, depth, t.triangle);
}

// A corner of a triangle, or of the polygon left of it by clipping: clip-space position and
// texture coordinates.
struct CrVertex {
    clip: vec4<f32>,
    uv: vec2<f32>,
}

// How far the screen may reach beyond the frame, in frames (clip space: |x|, |y| ≤ CR_GUARD w):
// corners past it are clipped away, so that snapped corners stay exact in f32 (8 × a 4096-pixel
// map × 256 sub-pixel steps < 2^24). The hardware clips against a guard band the same way.
const CR_GUARD: f32 = 8.0;

// Plane `k` of the clip volume at `v`, non-negative inside: the near plane (reversed Z: z ≤ w),
// then the guard band's four sides.
fn cr_plane(k: u32, v: vec4<f32>) -> f32 {
    switch k {
        case 0u: { return v.w - v.z; }
        case 1u: { return CR_GUARD * v.w - v.x; }
        case 2u: { return CR_GUARD * v.w + v.x; }
        case 3u: { return CR_GUARD * v.w - v.y; }
        default: { return CR_GUARD * v.w + v.y; }
    }
}

fn cr_lerp(a: CrVertex, b: CrVertex, t: f32) -> CrVertex {
    return CrVertex(mix(a.clip, b.clip, t), mix(a.uv, b.uv, t));
}

// Both passes' workgroups: the covered pixels queued for shading, and how many. Room for
// 64 × CR_ITEM_TILES pixels of a tile pass's item (each (x, y), 16 bits a coordinate: a map is
// smaller than 65,536 pixels a side) and for 64 × CR_SMALL_PIXELS of a bin pass's small
// triangles (each the owner's invocation, then the pixel's index in its box in 4 bits).
var<workgroup> cr_queue: array<u32, 1024>;
var<workgroup> cr_queued: atomic<u32>;

// The bin pass's workgroup: each invocation's small triangle (where it has one), set up as a
// record; the (record, invocation) of triangles (or parts of clipped ones: up to 6 an
// invocation) with many items, and how many; and of the one whose items are being written, how
// many it may touch, (first slot, that count), and the slots taken.
var<workgroup> cr_small: array<CrRecord, 64>;
var<workgroup> cr_big: array<vec2<u32>, 384>;
// Bit i: invocation i's triangle is left to the hardware (cr_leave, once, at the pass's end).
var<workgroup> cr_leaving: array<atomic<u32>, 2>;
var<workgroup> cr_big_count: atomic<u32>;
var<workgroup> cr_big_total: u32;
var<workgroup> cr_big_touched: atomic<u32>;
var<workgroup> cr_big_slots: vec2<u32>;
var<workgroup> cr_big_cursor: atomic<u32>;

// One invocation per triangle, in two steps: each bins its triangle, testing the pixel centres
// of a small one's box and queueing the covered ones; then the workgroup shades the queue, one
// fragment an invocation. Why: a box holds up to CR_SMALL_PIXELS pixel centres, and shading them
// in the invocation that owns the triangle left the others of its workgroup idle meanwhile (on
// Sponza at 1080p the bin pass shades 145,532 fragments of 400,885 centres tried, across 262,267
// triangles of which most have none).
@compute @workgroup_size(64)
fn sd_raster_bin(
    @builtin(global_invocation_id) gid: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
    @builtin(num_workgroups) groups: vec3<u32>,
) {
    if (lane == 0u) {
        atomicStore(&cr_queued, 0u);
        atomicStore(&cr_big_count, 0u);
        atomicStore(&cr_leaving[0], 0u);
        atomicStore(&cr_leaving[1], 0u);
    }
    workgroupBarrier();
    let t = gid.x + gid.y * groups.x * 64u;
    if (t < cr.triangle_count) {
        cr_bin(t, lane);
    }
    workgroupBarrier();
    let queued = atomicLoad(&cr_queued);
    if (lane == 0u && queued > 0u) {
        atomicAdd(&cr_counts[CR_SHADED_BIN], queued);
    }
    for (var q = lane; q < queued; q += 64u) {
        // The owner's lane, then the pixel's index in its box.
        let rec = cr_small[cr_queue[q] >> 4u];
        let r = cr_triangle_of(rec);
        let width = rec.last.x - rec.first.x + 1u;
        let index = cr_queue[q] & 15u;
        let pixel = rec.first + vec2<u32>(index % width, index / width);
        cr_shade(r, pixel, cr_edges_at(r, pixel));
    }
    if (lane == 0u) {
        cr_big_total = atomicLoad(&cr_big_count);
    }
    // (The records the invocations wrote, visible to the whole workgroup.)
    storageBarrier();
    let bigs = workgroupUniformLoad(&cr_big_total);
    for (var b = 0u; b < bigs; b++) {
        cr_items_together(cr_big[b].x, cr_big[b].y, lane);
    }
    // Each triangle that did not fit is left to the hardware once, however many of its parts
    // did not (the lists of left triangles have room for each once).
    if (t < cr.triangle_count && (atomicLoad(&cr_leaving[lane / 32u]) & (1u << (lane % 32u))) != 0u) {
        cr_leave(t);
    }
}

// The invocation (of its workgroup) binning the triangle cr_rasterize is given parts of.
var<private> cr_owner: u32;

// Marks invocation `lane`'s triangle as left to the hardware.
fn cr_mark_left(lane: u32) {
    atomicOr(&cr_leaving[lane / 32u], 1u << (lane % 32u));
}

// The items the triangle of record `record` may touch, written by the workgroup, invocation
// `lane` taking every 64th: counted, given their slots by one atomic, written in any order (the
// tile pass takes items in any order). Where they do not fit, their slots are marked empty and
// the triangle (invocation `owner`'s) is left to the hardware, as cr_rasterize does.
fn cr_items_together(record: u32, owner: u32, lane: u32) {
    let rec = cr_records[record];
    let r = cr_triangle_of(rec);
    let tile_count = cr_tile_count(rec);
    let item_count = cr_items_of(tile_count);
    if (lane == 0u) {
        atomicStore(&cr_big_touched, 0u);
        atomicStore(&cr_big_cursor, 0u);
    }
    workgroupBarrier();
    for (var i = lane; i < item_count; i += 64u) {
        if (cr_item_touched(r, rec, tile_count, i)) {
            atomicAdd(&cr_big_touched, 1u);
        }
    }
    workgroupBarrier();
    if (lane == 0u) {
        let touched = atomicLoad(&cr_big_touched);
        cr_big_slots = vec2<u32>(atomicAdd(&cr_counts[CR_ITEMS], touched), touched);
    }
    let slots = workgroupUniformLoad(&cr_big_slots);
    let fits = slots.x + slots.y <= cr.item_capacity;
    for (var i = lane; i < item_count; i += 64u) {
        if (cr_item_touched(r, rec, tile_count, i)) {
            let slot = slots.x + atomicAdd(&cr_big_cursor, 1u);
            if (slot < cr.item_capacity) {
                cr_items[slot] = cr_item_entry(record, i, fits);
            }
        }
    }
    if (lane == 0u && !fits) {
        atomicAdd(&cr_counts[CR_OVERFLOW], 1u);
        cr_mark_left(owner);
    }
    // Nobody resets the counts for the next triangle while another invocation still uses them.
    workgroupBarrier();
}

// Bins triangle `t` (invocation `lane` of its workgroup).
fn cr_bin(t: u32, lane: u32) {
    cr_owner = lane;
    let tri = triangles[t];
    let masked = t >= cr.opaque_count;
    var v: array<CrVertex, 3>;
    // The whole triangle's plane, as the G-buffer's resolve takes it.
    var plane: CrPlane;
    plane.v0 = to_view(positions[tri.x].xyz);
    plane.face = view_face_normal(tri);
    // Which planes of the clip volume each corner lies outside of (bit k: plane k), and the
    // frustum's sides.
    var outside_all = 0x1ffu;
    var outside_any = 0u;
    for (var i = 0u; i < 3u; i++) {
        let c = view_to_clip(to_view(positions[tri[i]].xyz));
        v[i] = CrVertex(c, vec2<f32>(0.0));
        if (masked) {
            v[i].uv = attributes[tri[i]].xy;
        }
        var code = 0u;
        for (var k = 0u; k < 5u; k++) {
            code |= u32(cr_plane(k, c) < 0.0) << k;
        }
        code |= u32(c.x < -c.w) << 5u | u32(c.x > c.w) << 6u | u32(c.y < -c.w) << 7u
            | u32(c.y > c.w) << 8u;
        outside_all &= code;
        outside_any |= code;
    }
    // Every corner outside one plane: nothing drawn.
    if (outside_all != 0u) {
        return;
    }
    if ((outside_any & 0x1fu) == 0u) {
        if (!cr_rasterize(t, tri.w, plane, v[0], v[1], v[2], lane)) {
            cr_mark_left(lane);
        }
        return;
    }
    // Clipped (Sutherland-Hodgman) against the planes the corners cross: at most 3 + 5 corners.
    var poly: array<CrVertex, 8>;
    var n = 3u;
    for (var i = 0u; i < 3u; i++) {
        poly[i] = v[i];
    }
    for (var k = 0u; k < 5u; k++) {
        if ((outside_any & (1u << k)) == 0u) {
            continue;
        }
        var next: array<CrVertex, 8>;
        var m = 0u;
        for (var i = 0u; i < n; i++) {
            let a = poly[i];
            let b = poly[(i + 1u) % n];
            let fa = cr_plane(k, a.clip);
            let fb = cr_plane(k, b.clip);
            if (fa >= 0.0) {
                next[m] = a;
                m++;
            }
            if ((fa >= 0.0) != (fb >= 0.0) && m < 8u) {
                next[m] = cr_lerp(a, b, fa / (fa - fb));
                m++;
            }
        }
        poly = next;
        n = m;
    }
    // A fan of triangles, each with the triangle's own orientation; the whole triangle is left
    // to the hardware, once, if any part did not fit.
    var fits = true;
    for (var i = 1u; i + 1u < n; i++) {
        fits = cr_rasterize(t, tri.w, plane, poly[0], poly[i], poly[i + 1u], CR_INLINE) && fits;
    }
    if (!fits) {
        cr_mark_left(lane);
    }
}

// The plane of a triangle in view space: a corner and the face normal (unnormalised).
struct CrPlane {
    v0: vec3<f32>,
    face: vec3<f32>,
}

// Where cr_rasterize shades a small triangle itself instead of queueing it (a clipped triangle's
// parts: an invocation queues one small triangle at most).
const CR_INLINE: u32 = 0xffffffffu;
// CR_OWN_ITEMS (generated by compute_raster.rs, 16; tests set 0): a triangle with more items
// than this has them written by its whole workgroup. Why: one invocation writing them one after
// another held its workgroup, and the pass, for as long: on the built-in `colonnade` (1,236
// triangles, a ground whose box spans the map) the bin pass took 1.16 ms on an H200, against
// 0.08 ms for Sibenik's 73,564 (BENCHMARKS.md, 2026-12-05).

// Triangle `t` (material `material`, `plane`), or a part of it left by clipping, with corners
// `a`, `b`, `c` inside the clip volume: where small, its covered pixels queued for the workgroup
// (as invocation `lane`'s) or, with `lane` CR_INLINE, shaded here; else handed to the tile pass.
// False where its record or items did not fit (the caller leaves `t` to the hardware).
fn cr_rasterize(
    t: u32,
    material: u32,
    plane: CrPlane,
    a: CrVertex,
    b: CrVertex,
    c: CrVertex,
    lane: u32,
) -> bool {
    let size = vec2<f32>(cr.size);
    var p = array<vec2<f32>, 3>(cr_screen(a.clip, size), cr_screen(b.clip, size), cr_screen(c.clip, size));
    let area = (p[1].x - p[0].x) * (p[2].y - p[0].y) - (p[1].y - p[0].y) * (p[2].x - p[0].x);
    // Front faces are counter-clockwise in normalised device coordinates (y up), so of negative
    // area here (y down).
    if (area == 0.0 || (t < cr.culled_count && area > 0.0)) {
        return true;
    }
    var r: CrTriangle;
    r.triangle = t;
    r.material = material;
    r.inv_w = 1.0 / vec3<f32>(a.clip.w, b.clip.w, c.clip.w);
    r.uv = array<vec2<f32>, 3>(a.uv, b.uv, c.uv);
    r.v0 = plane.v0;
    r.face = plane.face;
    // Corners in the order that makes the area positive.
    if (area < 0.0) {
        let q = p[1];
        p[1] = p[2];
        p[2] = q;
        r.inv_w = r.inv_w.xzy;
        r.uv = array<vec2<f32>, 3>(a.uv, c.uv, b.uv);
    }
    r.edges = cr_triangle(p[0], p[1], p[2]);
    // The pixel centres of the bounding box, within the map.
    let lo = min(min(p[0], p[1]), p[2]);
    let hi = max(max(p[0], p[1]), p[2]);
    let first = max(ceil(lo - 0.5), vec2<f32>(0.0));
    let last = min(floor(hi - 0.5), size - 1.0);
    if (any(first > last)) {
        return true;
    }
    let first_px = vec2<u32>(first);
    let extent = vec2<u32>(last - first) + 1u;
    let tiles = (extent + 7u) / 8u;
    var rec: CrRecord;
    rec.p01 = vec4<f32>(p[0], p[1]);
    rec.p2 = p[2];
    rec.first = first_px;
    rec.last = vec2<u32>(last);
    rec.tiles_x = tiles.x;
    rec.triangle = t;
    rec.inv_w = r.inv_w;
    rec.material = material;
    rec.v0 = plane.v0;
    rec.face = plane.face;
    rec.uv01 = vec4<f32>(r.uv[0], r.uv[1]);
    rec.uv2 = r.uv[2];
    if (extent.x * extent.y <= CR_SMALL_PIXELS) {
        if (lane != CR_INLINE) {
            cr_small[lane] = rec;
        }
        for (var i = 0u; i < extent.x * extent.y; i++) {
            let pixel = first_px + vec2<u32>(i % extent.x, i / extent.x);
            let e = cr_edges_at(r, pixel);
            if (cr_covered(r, pixel, e)) {
                if (lane == CR_INLINE) {
                    atomicAdd(&cr_counts[CR_SHADED_BIN], 1u);
                    cr_shade(r, pixel, e);
                } else {
                    cr_queue[atomicAdd(&cr_queued, 1u)] = (lane << 4u) | i;
                }
            }
        }
        return true;
    }
    // Only the items the triangle may touch: its box can be far larger than it (a long thin
    // triangle across the frame), and the tile pass would spend a round on each item.
    let tile_count = tiles.x * tiles.y;
    let item_count = cr_items_of(tile_count);
    if (item_count > CR_OWN_ITEMS) {
        // Many items: written by the whole workgroup after binning (cr_items_together).
        let record = cr_write_record(rec);
        if (record == CR_NO_RECORD) {
            return false;
        }
        cr_big[atomicAdd(&cr_big_count, 1u)] = vec2<u32>(record, cr_owner);
        return true;
    }
    var touched = 0u;
    for (var i = 0u; i < item_count; i++) {
        touched += u32(cr_item_touched(r, rec, tile_count, i));
    }
    if (touched == 0u) {
        return true;
    }
    let record = cr_write_record(rec);
    if (record == CR_NO_RECORD) {
        return false;
    }
    // Items that do not all fit are not rasterised here: the slots they got within the capacity
    // are marked empty (the tile pass reads the first `item_capacity` slots) and the hardware
    // draws the triangle. (Of a clipped triangle, parts that fitted are rasterised here as well;
    // where the hardware's fragments of it store again, at depths a rounding apart, the
    // stochastic map keeps the nearer, and the nearest layers may hold both.)
    let base = atomicAdd(&cr_counts[CR_ITEMS], touched);
    let fits = base + touched <= cr.item_capacity;
    var slot = base;
    for (var i = 0u; i < item_count && slot < cr.item_capacity; i++) {
        if (cr_item_touched(r, rec, tile_count, i)) {
            cr_items[slot] = cr_item_entry(record, i, fits);
            slot++;
        }
    }
    if (!fits) {
        atomicAdd(&cr_counts[CR_OVERFLOW], 1u);
    }
    return fits;
}

// Record `rec` written to a free slot: its index, or CR_NO_RECORD where none is left (counted
// as an overflow; the caller leaves the triangle to the hardware).
fn cr_write_record(rec: CrRecord) -> u32 {
    let record = atomicAdd(&cr_counts[CR_RECORDS], 1u);
    if (record >= cr.record_capacity) {
        atomicAdd(&cr_counts[CR_OVERFLOW], 1u);
        return CR_NO_RECORD;
    }
    cr_records[record] = rec;
    return record;
}

// Item `i` of record `record` as the tile pass reads it: (record, first tile), or an empty slot
// where the triangle's items do not all `fit`.
fn cr_item_entry(record: u32, i: u32, fit: bool) -> vec2<u32> {
    return select(vec2<u32>(CR_NO_RECORD, 0u), vec2<u32>(record, i * CR_ITEM_TILES), fit);
}

// The items (runs of CR_ITEM_TILES tiles) of a box of `tile_count` tiles.
fn cr_items_of(tile_count: u32) -> u32 {
    return (tile_count + CR_ITEM_TILES - 1u) / CR_ITEM_TILES;
}

// The 8×8 tiles of record `rec`'s box.
fn cr_tile_count(rec: CrRecord) -> u32 {
    return rec.tiles_x * ((rec.last.y - rec.first.y) / 8u + 1u);
}

// Whether `t` (record `rec`, of `tile_count` tiles) may touch item `i`'s tiles: the rectangle of
// the tile rows the item's run spans (row-major, so a run across rows spans whole rows).
fn cr_item_touched(t: CrTriangle, rec: CrRecord, tile_count: u32, i: u32) -> bool {
    let k0 = i * CR_ITEM_TILES;
    let k1 = min(k0 + CR_ITEM_TILES, tile_count) - 1u;
    let rows = vec2<u32>(k0, k1) / rec.tiles_x;
    let columns = select(vec2<u32>(0u, rec.tiles_x - 1u), vec2<u32>(k0, k1) % rec.tiles_x, rows.x == rows.y);
    let lo = rec.first + vec2<u32>(columns.x, rows.x) * 8u;
    let hi = min(rec.first + vec2<u32>(columns.y, rows.y) * 8u + 7u, rec.last);
    return cr_rect_touched(t, lo, hi);
}

// Framebuffer position of clip-space point `c` in a map of `size` pixels, snapped to the
// sub-pixel grid.
fn cr_screen(c: vec4<f32>, size: vec2<f32>) -> vec2<f32> {
    let ndc = c.xy / c.w;
    let s = vec2<f32>(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5) * size;
    return round(s * CR_SUBPIXEL) / CR_SUBPIXEL;
}

// Triangle `t` drawn by the hardware after all, by its group's draw.
fn cr_leave(t: u32) {
    atomicAdd(&cr_counts[CR_LEFT], 1u);
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

// The tile pass's workgroup: the items' count and the item it works on, as values every
// invocation agrees on (workgroupUniformLoad), and which of the item's tiles the triangle may
// touch (bit i: its i-th tile).
var<workgroup> cr_item_count: u32;
var<workgroup> cr_item: vec2<u32>;
var<workgroup> cr_tiles_touched: atomic<u32>;

// The first pixel of tile `k` (row-major over the tiles of the box) of record `rec`.
fn cr_tile_origin(rec: CrRecord, k: u32) -> vec2<u32> {
    return rec.first + vec2<u32>(k % rec.tiles_x, k / rec.tiles_x) * 8u;
}

// Whether `t` may cover a pixel centre of the pixels `lo` to `hi` (a rectangle, both included):
// false only where, for one edge, even the rectangle's centre farthest inside lies more than
// 1/64 pixel outside. Edge functions are affine, so that centre is the corner the edge's inward
// normal points to. The margin is conservative against rounding (a corner is evaluated, not the
// centres themselves; the values' rounding is below 1/256 pixel of distance for the map's
// coordinates), so a rejected rectangle holds no centre the per-pixel test would take.
// (CR_TILE_TESTS, generated by compute_raster.rs, is false only in a test that holds the map to
// the one made without these tests.)
fn cr_rect_touched(t: CrTriangle, lo: vec2<u32>, hi: vec2<u32>) -> bool {
    if (!CR_TILE_TESTS) {
        return true;
    }
    for (var i = 0u; i < 3u; i++) {
        let e = t.edges[i];
        // cr_edge_at(e, p) = dot(normal, p - e.origin).
        let normal = e.sign * vec2<f32>(-e.direction.y, e.direction.x);
        let corner = vec2<f32>(select(lo, hi, normal > vec2<f32>(0.0))) + 0.5;
        if (cr_edge_at(e, corner) < -(abs(normal.x) + abs(normal.y)) / 64.0) {
            return false;
        }
    }
    return true;
}

// Each workgroup takes every n-th item in three steps: 16 of its invocations test which of the
// item's tiles the triangle may touch; all 64 test the pixel centres of those tiles (edge
// functions and the request mask only) and queue the covered ones; then they shade the queue,
// one fragment each. Why: the item's triangle covers few of its tiles' pixels (15 % of them on
// Sponza at 1080p and 24 % on Sibenik, BENCHMARKS.md), and shading tile by tile kept the other
// invocations idle while a few ran the alpha test, the plane intersection and the map's
// atomics; queued, all 64 share that work. And most of its tiles it does not touch at all (69 %
// on Sponza, 49 % on Sibenik: its box is much larger than it), which the tile test skips.
@compute @workgroup_size(64)
fn sd_raster_tiles(
    @builtin(local_invocation_index) lane: u32,
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
) {
    if (lane == 0u) {
        cr_item_count = min(atomicLoad(&cr_counts[CR_ITEMS]), cr.item_capacity);
    }
    let count = workgroupUniformLoad(&cr_item_count);
    let local = vec2<u32>(lane % 8u, lane / 8u);
    let stride = groups.x * groups.y;
    // The fragments this workgroup shades (counted in its first invocation, added once).
    var shaded = 0u;
    for (var i = group.x + group.y * groups.x; i < count; i += stride) {
        if (lane == 0u) {
            cr_item = cr_items[i];
            atomicStore(&cr_queued, 0u);
            atomicStore(&cr_tiles_touched, 0u);
        }
        let item = workgroupUniformLoad(&cr_item);
        if (item.x != CR_NO_RECORD) {
            let rec = cr_records[item.x];
            let r = cr_triangle_of(rec);
            let end = min(item.y + CR_ITEM_TILES, cr_tile_count(rec));
            // The item's tiles that the triangle may touch, an invocation a tile.
            let own_tile = item.y + lane;
            let own_origin = cr_tile_origin(rec, own_tile);
            if (lane < CR_ITEM_TILES && own_tile < end
                && cr_rect_touched(r, own_origin, min(own_origin + 7u, rec.last))) {
                atomicOr(&cr_tiles_touched, 1u << lane);
            }
            workgroupBarrier();
            var touched = atomicLoad(&cr_tiles_touched);
            while (touched != 0u) {
                let origin = cr_tile_origin(rec, item.y + firstTrailingBit(touched));
                touched &= touched - 1u;
                let pixel = origin + local;
                if (all(pixel <= rec.last) && cr_covered(r, pixel, cr_edges_at(r, pixel))) {
                    cr_queue[atomicAdd(&cr_queued, 1u)] = pixel.x | (pixel.y << 16u);
                }
            }
            workgroupBarrier();
            let queued = atomicLoad(&cr_queued);
            shaded += queued;
            for (var q = lane; q < queued; q += 64u) {
                let pixel = vec2<u32>(cr_queue[q] & 0xffffu, cr_queue[q] >> 16u);
                cr_shade(r, pixel, cr_edges_at(r, pixel));
            }
        }
        // Nobody changes the item or empties the queue while another invocation still reads
        // them.
        workgroupBarrier();
    }
    if (lane == 0u && shaded > 0u) {
        atomicAdd(&cr_counts[CR_SHADED_TILES], shaded);
    }
}
