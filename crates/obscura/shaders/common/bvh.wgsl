// BVH traversal on the GPU: the four-wide tree of src/bvh/wide.rs (collapsed from the flat BVH2 of
// src/bvh: the same boxes and leaves; leaves index the leaf-ordered triangle list) walked nearest
// child first with a bounded stack, as src/bvh/traverse.rs walks the BVH2, and the watertight
// ray/triangle test of src/bvh/triangle.rs (Woop, Benthin, Wald, JCGT 2(1) 2013) without its f64
// tie-break: a ray that passes exactly through an edge counts as inside for both triangles here.
//
// Every ray-tracing pass includes this file once (after common/material.wgsl) and defines
//     fn bvh_on_hit(hit: BvhHit) -> u32
// returning BVH_CONTINUE, BVH_SHRINK (the interval ends at hit.t: closest-hit search) or BVH_STOP:
// the shape of an any-hit shader. Hits reach it only after the back-face and alpha rules.
// bvh_closest_hit and bvh_any_hit are built in and do not call it.

// Four children (src/bvh/wide.rs WideNode): their boxes per axis; child k is a leaf of the
// triangle slots child[k] .. child[k] + count[k] when count[k] > 0, else the inner node child[k].
// Unused slots have inverted boxes, which no ray enters.
struct BvhNode {
    // Per axis a: bounds[2a] the children's minima, bounds[2a + 1] their maxima (a ray reads the
    // planes it enters and leaves by index, BvhRay.near / far, or reads both and chooses:
    // BVH_PLANES_BY_INDEX).
    bounds: array<vec4<f32>, 6>,
    child: vec4<u32>,
    count: vec4<u32>,
}

@group(BVH_GROUP) @binding(BVH_BINDING) var<storage, read> bvh_nodes: array<BvhNode>;
// Leaf order: (vertex 0, vertex 1, vertex 2, material).
@group(BVH_GROUP) @binding(BVH_BINDING + 1u) var<storage, read> bvh_triangles: array<vec4<u32>>;
@group(BVH_GROUP) @binding(BVH_BINDING + 2u) var<storage, read> bvh_positions: array<vec4<f32>>;
// Per vertex (u, v, octahedral normal): common/vertex_normal.wgsl.
@group(BVH_GROUP) @binding(BVH_BINDING + 3u) var<storage, read> bvh_attributes: array<vec4<f32>>;
@group(BVH_GROUP) @binding(BVH_BINDING + 4u) var<storage, read> bvh_materials: array<Material>;
@group(BVH_GROUP) @binding(BVH_BINDING + 5u) var bvh_textures: texture_2d_array<f32>;

const BVH_CONTINUE: u32 = 0u;
const BVH_SHRINK: u32 = 1u;
const BVH_STOP: u32 = 2u;
// Entries of the traversal stack (src/bvh/gpu.rs STACK_SIZE says why this many). A tree whose walk
// needs more sets `bvh_stack_overflow` (never silently).
const BVH_STACK_SIZE: u32 = 64u;
// How a node's box test reads the planes a ray enters and leaves a box by: by their index for the
// ray's direction (true), or both planes of an axis and a choice between them. Ours, measured on
// an H200 (BENCHMARKS.md, 2026-12-04): by index, the rays traced in the AO passes (`rt-vao`,
// `rt-svao`) were 3–5 % faster and the ray-traced stochastic depth map 1–9 % slower, so the
// map's pipeline sets it false.
override BVH_PLANES_BY_INDEX: bool = true;
// Relative slack of box exits (src/bvh/triangle.rs: T_SLACK).
const BVH_T_SLACK: f32 = 4.76837158e-7;

struct BvhHit {
    t: f32,
    // Leaf-order slot of the triangle (see bvh_triangles).
    slot: u32,
    u: f32,
    v: f32,
    front_face: bool,
}

// Set when a traversal had to drop a subtree because its stack was full.
var<private> bvh_stack_overflow: bool = false;

// Built-in hit handling for bvh_closest_hit / bvh_any_hit; otherwise hits go to bvh_on_hit.
const BVH_MODE_PASS: u32 = 0u;
const BVH_MODE_CLOSEST: u32 = 1u;
const BVH_MODE_ANY: u32 = 2u;
var<private> bvh_mode: u32 = 0u;
var<private> bvh_found: BvhHit;

fn bvh_handle_hit(hit: BvhHit) -> u32 {
    if (bvh_mode == BVH_MODE_CLOSEST) {
        bvh_found = hit;
        return BVH_SHRINK;
    }
    if (bvh_mode == BVH_MODE_ANY) {
        bvh_found = hit;
        return BVH_STOP;
    }
    return bvh_on_hit(hit);
}

// The closest hit in [t_min, t_max] (`t < 0`: none).
fn bvh_closest_hit(origin: vec3<f32>, dir: vec3<f32>, t_min: f32, t_max: f32) -> BvhHit {
    bvh_mode = BVH_MODE_CLOSEST;
    bvh_found.t = -1.0;
    bvh_traverse(origin, dir, t_min, t_max);
    bvh_mode = BVH_MODE_PASS;
    return bvh_found;
}

// Whether anything is hit in [t_min, t_max].
fn bvh_any_hit(origin: vec3<f32>, dir: vec3<f32>, t_min: f32, t_max: f32) -> bool {
    bvh_mode = BVH_MODE_ANY;
    bvh_found.t = -1.0;
    bvh_traverse(origin, dir, t_min, t_max);
    bvh_mode = BVH_MODE_PASS;
    return bvh_found.t >= 0.0;
}

struct BvhRay {
    origin: vec3<f32>,
    inv_dir: vec3<f32>,
    // Axis permutation of the watertight test and its shear constants.
    k: vec3<u32>,
    shear: vec3<f32>,
    // Per axis, the index into BvhNode.bounds of the planes the ray enters and leaves a box by
    // (the minima for a positive direction).
    near: vec3<u32>,
    far: vec3<u32>,
}

fn bvh_ray(origin: vec3<f32>, dir: vec3<f32>) -> BvhRay {
    let a = abs(dir);
    var kz = 2u;
    if (a.x >= a.y && a.x >= a.z) {
        kz = 0u;
    } else if (a.y >= a.z) {
        kz = 1u;
    }
    var kx = (kz + 1u) % 3u;
    var ky = (kz + 2u) % 3u;
    if (dir[kz] < 0.0) {
        let swap = kx;
        kx = ky;
        ky = swap;
    }
    var r: BvhRay;
    r.origin = origin;
    // A zero component gets a huge finite inverse instead of inf, so no 0 * inf appears.
    let tiny = abs(dir) < vec3<f32>(1e-30);
    r.inv_dir = select(1.0 / dir, select(vec3<f32>(1e30), vec3<f32>(-1e30), dir < vec3<f32>(0.0)), tiny);
    r.k = vec3<u32>(kx, ky, kz);
    r.shear = vec3<f32>(dir[kx] / dir[kz], dir[ky] / dir[kz], 1.0 / dir[kz]);
    let negative = select(vec3<u32>(0u), vec3<u32>(1u), r.inv_dir < vec3<f32>(0.0));
    r.near = vec3<u32>(0u, 2u, 4u) + negative;
    r.far = vec3<u32>(1u, 3u, 5u) - negative;
    return r;
}

// Entry distances of the ray into the node's four boxes, -1 for those it misses in [t_lo, t_hi]
// (t_lo >= 0). Entry and exit planes are chosen by the direction's sign, so an inverted (empty)
// box never hits.
fn bvh_box_entries(r: BvhRay, node: u32, t_lo: f32, t_hi: f32) -> vec4<f32> {
    // Only the planes the test needs are loaded (and live) here; the children's links are loaded
    // after it.
    var near_x: vec4<f32>;
    var far_x: vec4<f32>;
    var near_y: vec4<f32>;
    var far_y: vec4<f32>;
    var near_z: vec4<f32>;
    var far_z: vec4<f32>;
    if (BVH_PLANES_BY_INDEX) {
        near_x = bvh_nodes[node].bounds[r.near.x];
        far_x = bvh_nodes[node].bounds[r.far.x];
        near_y = bvh_nodes[node].bounds[r.near.y];
        far_y = bvh_nodes[node].bounds[r.far.y];
        near_z = bvh_nodes[node].bounds[r.near.z];
        far_z = bvh_nodes[node].bounds[r.far.z];
    } else {
        // From the direction, not from `r.near`: that would keep the indices live through the
        // walk (measured slower).
        let negative = r.inv_dir < vec3<f32>(0.0);
        let min_x = bvh_nodes[node].bounds[0];
        let max_x = bvh_nodes[node].bounds[1];
        let min_y = bvh_nodes[node].bounds[2];
        let max_y = bvh_nodes[node].bounds[3];
        let min_z = bvh_nodes[node].bounds[4];
        let max_z = bvh_nodes[node].bounds[5];
        near_x = select(min_x, max_x, negative.x);
        far_x = select(max_x, min_x, negative.x);
        near_y = select(min_y, max_y, negative.y);
        far_y = select(max_y, min_y, negative.y);
        near_z = select(min_z, max_z, negative.z);
        far_z = select(max_z, min_z, negative.z);
    }
    near_x = (near_x - r.origin.x) * r.inv_dir.x;
    far_x = (far_x - r.origin.x) * r.inv_dir.x;
    near_y = (near_y - r.origin.y) * r.inv_dir.y;
    far_y = (far_y - r.origin.y) * r.inv_dir.y;
    near_z = (near_z - r.origin.z) * r.inv_dir.z;
    far_z = (far_z - r.origin.z) * r.inv_dir.z;
    let entry = max(max(max(near_x, near_y), near_z), vec4<f32>(t_lo));
    // The exit widened by the relative slack: exit (1 + slack) for exits at or beyond 0, and an
    // exit below 0 misses either way (entry >= t_lo >= 0). (Written as the larger of exit (1 ±
    // slack) it cost the ray-traced passes up to 1.5 % on an H200, BENCHMARKS.md.)
    let exit = min(min(min(far_x, far_y), far_z) * (1.0 + BVH_T_SLACK), vec4<f32>(t_hi));
    return select(vec4<f32>(-1.0), entry, entry <= exit);
}

// The node's four slots ordered by entry distance, nearest first, the missed ones last (their
// entry is -1). Branch-free: each slot's key is its entry's bits (non-negative floats order as
// their bits do) with the slot in the two low bits, sorted by a network of min/max.
fn bvh_order(entry: vec4<f32>) -> vec4<u32> {
    let key = (select(vec4<u32>(0xfffffffcu), bitcast<vec4<u32>>(entry), entry >= vec4<f32>(0.0))
        & vec4<u32>(0xfffffffcu)) | vec4<u32>(0u, 1u, 2u, 3u);
    let a = min(key.x, key.y);
    let b = max(key.x, key.y);
    let c = min(key.z, key.w);
    let d = max(key.z, key.w);
    let e = min(b, d);
    let f = max(a, c);
    return vec4<u32>(min(a, c), min(e, f), max(e, f), max(b, d)) & vec4<u32>(3u);
}

// Component k of v, by selects: a vector indexed by a value the shader computes can be put in
// memory by the compiler, where every access is a load.
fn bvh_pick_f32(v: vec4<f32>, k: u32) -> f32 {
    return select(select(v.x, v.y, k == 1u), select(v.z, v.w, k == 3u), k >= 2u);
}

fn bvh_pick_u32(v: vec4<u32>, k: u32) -> u32 {
    return select(select(v.x, v.y, k == 1u), select(v.z, v.w, k == 3u), k >= 2u);
}

fn bvh_sheared(r: BvhRay, p: vec3<f32>) -> vec3<f32> {
    let a = p - r.origin;
    return vec3<f32>(a[r.k.x] - r.shear.x * a[r.k.z], a[r.k.y] - r.shear.y * a[r.k.z], r.shear.z * a[r.k.z]);
}

// The watertight test of leaf slot `slot`; `hit.t < 0` for a miss.
fn bvh_intersect(r: BvhRay, slot: u32, t_min: f32, t_max: f32) -> BvhHit {
    var hit = bvh_intersect_triangle(r, bvh_triangles[slot], t_min, t_max);
    hit.slot = slot;
    return hit;
}

// The watertight test of triangle `tri` (vertex 0, vertex 1, vertex 2, material); `hit.t < 0`
// for a miss. Also for a triangle known otherwise than by its leaf slot (`hit.slot` unset): the
// two-phase blocked proof of sources/bvh_rays.wgsl tests the triangle a pixel shows with it.
fn bvh_intersect_triangle(r: BvhRay, tri: vec4<u32>, t_min: f32, t_max: f32) -> BvhHit {
    var hit: BvhHit;
    hit.t = -1.0;
    let a = bvh_sheared(r, bvh_positions[tri.x].xyz);
    let b = bvh_sheared(r, bvh_positions[tri.y].xyz);
    let c = bvh_sheared(r, bvh_positions[tri.z].xyz);
    let e0 = c.x * b.y - c.y * b.x;
    let e1 = a.x * c.y - a.y * c.x;
    let e2 = b.x * a.y - b.y * a.x;
    if ((e0 < 0.0 || e1 < 0.0 || e2 < 0.0) && (e0 > 0.0 || e1 > 0.0 || e2 > 0.0)) {
        return hit;
    }
    let det = e0 + e1 + e2;
    if (det == 0.0) {
        return hit;
    }
    let t = (e0 * a.z + e1 * b.z + e2 * c.z) / det;
    if (!(t >= t_min && t <= t_max)) {
        return hit;
    }
    hit.t = t;
    hit.u = e1 / det;
    hit.v = e2 / det;
    hit.front_face = det > 0.0;
    return hit;
}

// The scene's rules (src/bvh/traverse.rs: passes_rules) for a hit on leaf slot `hit.slot`.
fn bvh_passes_rules(hit: BvhHit) -> bool {
    return bvh_triangle_passes_rules(bvh_triangles[hit.slot], hit);
}

// The scene's rules for a hit on triangle `tri`: a back face counts only on a double-sided
// material, an alpha-tested material only where its texel passes.
fn bvh_triangle_passes_rules(tri: vec4<u32>, hit: BvhHit) -> bool {
    let m = bvh_materials[tri.w];
    if (!hit.front_face && (m.flags & 1u) == 0u) {
        return false;
    }
    if (m.alpha_cutoff < 0.0) {
        return true;
    }
    let uv = bvh_attributes[tri.x].xy * (1.0 - hit.u - hit.v) + bvh_attributes[tri.y].xy * hit.u
        + bvh_attributes[tri.z].xy * hit.v;
    return material_passes_alpha(m, bvh_textures, uv);
}

// A stack entry or the item walked next: a wide node's index, or a leaf as its wide node's
// index times 4 plus its slot, with this bit set (so at most 2^29 nodes, 64 GiB: more than any
// storage binding holds). The leaf's triangles are read from the node when it is walked, so the
// stack holds one word per entry for either.
const BVH_LEAF: u32 = 0x80000000u;
const BVH_NONE: u32 = 0xffffffffu;

// Walks the BVH over [t_min, t_max] (t_min >= 0), handing every hit that passes the rules to
// bvh_on_hit. At a node, the children the ray enters go onto the stack farthest first, leaves and
// inner nodes alike, and the nearest is walked into; a leaf's triangles are tested when it is
// walked, so the nearest leaves come first as in the BVH2 walk of src/bvh/traverse.rs. Leaves
// stay stack entries rather than being tested at their node, so that nothing of the node is live
// while a triangle is tested (the column rays trace inside the AO pass, where registers are few).
fn bvh_traverse(origin: vec3<f32>, dir: vec3<f32>, t_min: f32, t_max_in: f32) {
    if (!(t_min <= t_max_in)) {
        return;
    }
    let r = bvh_ray(origin, dir);
    var t_max = t_max_in;
    var t_cull = max(t_max * (1.0 + BVH_T_SLACK), t_max * (1.0 - BVH_T_SLACK));
    var stack_item: array<u32, BVH_STACK_SIZE>;
    var stack_t: array<f32, BVH_STACK_SIZE>;
    var sp = 0u;
    var item = 0u;
    loop {
        if ((item & BVH_LEAF) != 0u) {
            let w = (item & ~BVH_LEAF) >> 2u;
            let k = item & 3u;
            let first = bvh_nodes[w].child[k];
            let count = bvh_nodes[w].count[k];
            for (var slot = first; slot < first + count; slot++) {
                let hit = bvh_intersect(r, slot, t_min, t_max);
                if (hit.t < 0.0 || !bvh_passes_rules(hit)) {
                    continue;
                }
                let action = bvh_handle_hit(hit);
                if (action == BVH_STOP) {
                    return;
                }
                if (action == BVH_SHRINK && hit.t < t_max) {
                    t_max = hit.t;
                    t_cull = max(t_max * (1.0 + BVH_T_SLACK), t_max * (1.0 - BVH_T_SLACK));
                }
            }
            item = BVH_NONE;
        } else {
            let entry = bvh_box_entries(r, item, t_min, t_cull);
            let order = bvh_order(entry);
            let child = bvh_nodes[item].child;
            let count = bvh_nodes[item].count;
            let node = item;
            item = BVH_NONE;
            var item_t = 0.0;
            // Farthest first: each child but the nearest waits on the stack.
            for (var i = 0u; i < 4u; i++) {
                let k = bvh_pick_u32(order, 3u - i);
                let e = bvh_pick_f32(entry, k);
                if (e < 0.0) {
                    continue;
                }
                if (item != BVH_NONE) {
                    if (sp < BVH_STACK_SIZE) {
                        stack_item[sp] = item;
                        stack_t[sp] = item_t;
                        sp += 1u;
                    } else {
                        bvh_stack_overflow = true;
                    }
                }
                let is_leaf = bvh_pick_u32(count, k) != 0u;
                item = select(bvh_pick_u32(child, k), BVH_LEAF | (node << 2u) | k, is_leaf);
                item_t = e;
            }
        }
        if (item == BVH_NONE) {
            // Pop the next entry that still overlaps the (possibly shrunk) interval.
            loop {
                if (sp == 0u) {
                    return;
                }
                sp -= 1u;
                if (stack_t[sp] <= t_cull) {
                    item = stack_item[sp];
                    break;
                }
            }
        }
    }
}
