// BVH traversal on the GPU: the flat BVH2 of src/bvh (root at 0, an empty pad at 1, sibling pairs
// at even indices; leaves index the leaf-ordered triangle list) walked nearest child first with a
// bounded stack — the loop of src/bvh/traverse.rs, and the watertight ray/triangle test of
// src/bvh/triangle.rs (Woop, Benthin, Wald, JCGT 2(1) 2013) without its f64 tie-break: a ray that
// passes exactly through an edge counts as inside for both triangles here.
//
// Every ray-tracing pass includes this file once (after common/material.wgsl) and defines
//     fn bvh_on_hit(hit: BvhHit) -> u32
// returning BVH_CONTINUE, BVH_SHRINK (the interval ends at hit.t: closest-hit search) or BVH_STOP:
// the shape of an any-hit shader. Hits reach it only after the back-face and alpha rules.
// bvh_closest_hit and bvh_any_hit are built in and do not call it.

struct BvhNode {
    min: vec3<f32>,
    first: u32,
    max: vec3<f32>,
    count: u32,
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
// Entries of the traversal stack. A deeper tree sets `bvh_stack_overflow` (never silently).
const BVH_STACK_SIZE: u32 = 64u;
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
    return r;
}

// Entry distance of the ray into the box, or -1 when it misses [t_lo, t_hi] (t_lo >= 0).
// Entry and exit planes are chosen by the direction's sign, so an inverted (empty) box never hits.
fn bvh_box_entry(r: BvhRay, lo: vec3<f32>, hi: vec3<f32>, t_lo: f32, t_hi: f32) -> f32 {
    let negative = r.inv_dir < vec3<f32>(0.0);
    let near = (select(lo, hi, negative) - r.origin) * r.inv_dir;
    let far = (select(hi, lo, negative) - r.origin) * r.inv_dir;
    let entry = max(max(max(near.x, near.y), near.z), t_lo);
    var exit = min(min(far.x, far.y), far.z);
    exit = min(max(exit * (1.0 + BVH_T_SLACK), exit * (1.0 - BVH_T_SLACK)), t_hi);
    return select(-1.0, entry, entry <= exit);
}

fn bvh_sheared(r: BvhRay, p: vec3<f32>) -> vec3<f32> {
    let a = p - r.origin;
    return vec3<f32>(a[r.k.x] - r.shear.x * a[r.k.z], a[r.k.y] - r.shear.y * a[r.k.z], r.shear.z * a[r.k.z]);
}

// The watertight test; `hit.t < 0` for a miss.
fn bvh_intersect(r: BvhRay, slot: u32, t_min: f32, t_max: f32) -> BvhHit {
    var hit: BvhHit;
    hit.t = -1.0;
    let tri = bvh_triangles[slot];
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
    hit.slot = slot;
    hit.u = e1 / det;
    hit.v = e2 / det;
    hit.front_face = det > 0.0;
    return hit;
}

// The scene's rules (src/bvh/traverse.rs: passes_rules).
fn bvh_passes_rules(hit: BvhHit) -> bool {
    let tri = bvh_triangles[hit.slot];
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

// Walks the BVH over [t_min, t_max] (t_min >= 0), handing every hit that passes the rules to
// bvh_on_hit.
fn bvh_traverse(origin: vec3<f32>, dir: vec3<f32>, t_min: f32, t_max_in: f32) {
    if (arrayLength(&bvh_nodes) < 2u || !(t_min <= t_max_in)) {
        return;
    }
    let r = bvh_ray(origin, dir);
    var t_max = t_max_in;
    var t_cull = max(t_max * (1.0 + BVH_T_SLACK), t_max * (1.0 - BVH_T_SLACK));
    var stack_node: array<u32, BVH_STACK_SIZE>;
    var stack_t: array<f32, BVH_STACK_SIZE>;
    var sp = 0u;
    var pair = 0u;
    loop {
        // Both children of the pair; go on with the nearer one that is hit, push the other.
        let left = bvh_nodes[2u * pair];
        let right = bvh_nodes[2u * pair + 1u];
        let tl = bvh_box_entry(r, left.min, left.max, t_min, t_cull);
        let tr = bvh_box_entry(r, right.min, right.max, t_min, t_cull);
        var node = 0xffffffffu;
        if (tl >= 0.0 && tr >= 0.0) {
            let near_is_right = tr < tl;
            node = select(2u * pair, 2u * pair + 1u, near_is_right);
            if (sp < BVH_STACK_SIZE) {
                stack_node[sp] = select(2u * pair + 1u, 2u * pair, near_is_right);
                stack_t[sp] = select(tr, tl, near_is_right);
                sp += 1u;
            } else {
                bvh_stack_overflow = true;
            }
        } else if (tl >= 0.0) {
            node = 2u * pair;
        } else if (tr >= 0.0) {
            node = 2u * pair + 1u;
        }
        loop {
            if (node == 0xffffffffu) {
                // Pop the next node that still overlaps the (possibly shrunk) interval.
                loop {
                    if (sp == 0u) {
                        return;
                    }
                    sp -= 1u;
                    if (stack_t[sp] <= t_cull) {
                        node = stack_node[sp];
                        break;
                    }
                }
            }
            let n = bvh_nodes[node];
            if (n.count == 0u) {
                pair = n.first / 2u;
                break;
            }
            for (var slot = n.first; slot < n.first + n.count; slot++) {
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
            node = 0xffffffffu;
        }
    }
}
