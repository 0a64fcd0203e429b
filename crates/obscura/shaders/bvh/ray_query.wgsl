// A batch of rays through the BVH (common/bvh.wgsl): the closest hit, or up to 16 hits in the
// interval. It exposes the traversal directly, so tests can hold it to the CPU oracle hit for hit.

struct QueryRay {
    origin: vec3<f32>,
    t_min: f32,
    dir: vec3<f32>,
    t_max: f32,
}

struct QueryParams {
    count: u32,
    // 0: closest hit, 1: all hits.
    mode: u32,
    _pad0: u32,
    _pad1: u32,
}

const MAX_QUERY_HITS: u32 = 16u;

struct QueryResult {
    // Closest hit (mode 0): t (-1: none), original triangle index, barycentrics, front face.
    t: f32,
    triangle: u32,
    u: f32,
    v: f32,
    front_face: u32,
    // All hits (mode 1): how many, and the first MAX_QUERY_HITS original triangle indices.
    hit_count: u32,
    stack_overflow: u32,
    _pad: u32,
    triangles: array<u32, 16>,
}

// The BVH (common/bvh.wgsl) in group 1 from binding 0.
const BVH_GROUP: u32 = 1u;
const BVH_BINDING: u32 = 0u;

@group(0) @binding(0) var<uniform> params: QueryParams;
@group(0) @binding(1) var<storage, read> rays: array<QueryRay>;
@group(0) @binding(2) var<storage, read_write> results: array<QueryResult>;
@group(0) @binding(3) var<storage, read> primitive_ids: array<u32>;

var<private> closest: BvhHit;
var<private> hit_count: u32;
var<private> hit_triangles: array<u32, 16>;

fn bvh_on_hit(hit: BvhHit) -> u32 {
    if (params.mode == 0u) {
        if (closest.t < 0.0 || hit.t < closest.t) {
            closest = hit;
        }
        return BVH_SHRINK;
    }
    if (hit_count < MAX_QUERY_HITS) {
        hit_triangles[hit_count] = primitive_ids[hit.slot];
    }
    hit_count += 1u;
    return BVH_CONTINUE;
}

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if (id.x >= params.count) {
        return;
    }
    let ray = rays[id.x];
    closest.t = -1.0;
    hit_count = 0u;
    bvh_traverse(ray.origin, ray.dir, ray.t_min, ray.t_max);
    var r: QueryResult;
    r.t = closest.t;
    r.triangle = select(0xffffffffu, primitive_ids[closest.slot], closest.t >= 0.0);
    r.u = closest.u;
    r.v = closest.v;
    r.front_face = u32(closest.front_face);
    r.hit_count = hit_count;
    r.stack_overflow = u32(bvh_stack_overflow);
    r.triangles = hit_triangles;
    results[id.x] = r;
}
