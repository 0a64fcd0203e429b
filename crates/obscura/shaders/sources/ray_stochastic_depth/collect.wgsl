// Ray-traced stochastic depth map, collection by ray (seed 002 §3.1, Listing 1; the authors' code,
// docs/AUTHORS_CODE.md §2.3): one camera ray per map texel through our BVH
// (common/bvh.wgsl) in compute, every hit behind the first visible layer handled as the paper's
// any-hit shader handles it. Reservoir sampling (Vitter 1985): the first N distinct depths fill
// the N slots, each further hit takes a slot with probability N/count; with z-culling (the
// paper's default) a slot is only overwritten by a nearer depth; after MAX_COUNT hits the ray
// stops. The back-face and alpha rules are the BVH's (hits reach `bvh_on_hit` only after them).
// The first visible layer is skipped as the raster map skips it: the ray starts `separation`
// behind the G-buffer's linear depth, and a pixel without a first surface stores nothing.
//
// Low resolution (§3.3, Fig. 5): with divisor d > 1 a texel of the map covers d×d pixels and its
// ray passes through a jittered point of that block: texel t's point is (t + j) d, j from a 4×4
// tile of 16 positions (index (t.y % 4) · 4 + t.x % 4) of the 2D Sobol sequence, which lie one
// per row and column of the tile's 16×16 grid. At d = 1 the ray passes through the pixel centre.
//
// Guard band (§3.5): the map reaches `guard` texels beyond the framebuffer on each side (texel t
// covers pixels (t − guard) d …). A texel whose ray point lies off the framebuffer has no first
// layer (the G-buffer ends there), so its ray starts at the near plane and keeps every layer, the
// first visible one included (the authors read a depth of 0 there); off-screen samples read these
// texels (read.wgsl's guard_band_lookup). Without a band the point is clamped into the
// framebuffer, as a texel there is read only by the framebuffer's pixels.
//
// Entry points (one appended per pipeline, src/sources/ray_stochastic_depth.rs): `collect_all.wgsl`
// traces every texel it is given, `collect_requested.wgsl` only the requested ones, packed.
//
// Ours: the reservoir's random number is a hash of the texel, the triangle and the map's seed
// (the paper hashes the barycentrics; both are stable while nothing moves); the slots are stored
// as reversed-Z `near / depth` (0 = empty), the raster map's encoding, so the AO passes read both
// maps with the same code (samples.wgsl).

// The BVH (common/bvh.wgsl) in group 1 from binding 0.
const BVH_GROUP: u32 = 1u;
const BVH_BINDING: u32 = 0u;

struct RaySdParams {
    // First: what the AO passes bind as `sd_near` (samples.wgsl).
    near: f32,
    separation: f32,
    seed: u32,
    // Non-zero: trace only the texels whose request flag is set (two-phase schedules).
    requested_only: u32,
    camera_to_world: mat4x4<f32>,
    inverse_projection: mat4x4<f32>,
    // Framebuffer size in pixels.
    size: vec2<u32>,
    // The map's size in texels, ⌈size / divisor⌉.
    map_size: vec2<u32>,
    divisor: u32,
    // Non-zero: trace only the depth interval phase 1's samples need (seed 002 §3.2).
    intervals: u32,
    // The map's guard band in texels on each side (§3.5).
    guard: u32,
    // The word of `sd_map` where the hit counts start.
    hits_offset: u32,
    // xy: the jitter of texels with (t.y % 4) · 4 + t.x % 4 = index, in [0, 1)².
    jitter: array<vec4<f32>, 16>,
}

// Slots per texel (N, at most 8).
override RESERVOIR: u32 = 4u;
// Hits a ray handles before it stops.
override MAX_COUNT: u32 = 8u;
// Overwrite a slot only with a nearer depth (seed 002 §3.1).
override Z_CULL: bool = true;

@group(0) @binding(0) var<uniform> params: RaySdParams;
@group(0) @binding(1) var first_layer: texture_2d<f32>;
// One u32 per map texel, non-zero = requested (read when `requested_only`;
// ray_stochastic_depth/request.wgsl marks the texel of every flagged sample).
@group(0) @binding(2) var<storage, read> sd_request: array<u32>;
// RESERVOIR f32 bits per map texel, row-major (what the AO passes read as floats); then from
// `hits_offset` on the hits handled per texel (the debug output "hits per ray"). One buffer, so
// that with the BVH's five this pass binds WebGPU's default of 8 storage buffers per stage.
@group(0) @binding(3) var<storage, read_write> sd_map: array<u32>;
// Per map texel, read when `intervals`: the complement of the nearest needed depth's bits (0:
// none) and the farthest needed depth's bits (ray_stochastic_depth/request.wgsl).
@group(0) @binding(4) var<storage, read> sd_interval: array<u32>;

var<private> slots: array<f32, 8>;
var<private> count: u32;
var<private> texel_hash: u32;

fn bvh_on_hit(hit: BvhHit) -> u32 {
    // Distinct depths only: a ray through a shared edge meets both triangles at one depth.
    for (var i = 0u; i < min(count, RESERVOIR); i++) {
        if (abs(slots[i] - hit.t) <= 1e-6 * hit.t) {
            return BVH_CONTINUE;
        }
    }
    var slot = count;
    count += 1u;
    if (count > RESERVOIR) {
        let xi = hash_to_unit(pcg_hash(texel_hash ^ pcg_hash(hit.slot ^ pcg_hash(count))));
        slot = min(u32(xi * f32(count)), count - 1u);
    }
    if (slot < RESERVOIR && (!Z_CULL || hit.t < slots[slot])) {
        slots[slot] = hit.t;
    }
    return select(BVH_CONTINUE, BVH_STOP, count >= MAX_COUNT);
}

// The reservoir of map texel `id` (requested, or every texel of a one-pass row).
fn collect_texel(id: vec2<u32>) {
    let texel = id.y * params.map_size.x + id.x;
    // The depths the texel's requests need (all of them without intervals).
    var needed = vec2<f32>(0.0, 3.0e38);
    if (params.requested_only != 0u && params.intervals != 0u) {
        needed = vec2<f32>(bitcast<f32>(~sd_interval[2u * texel]), bitcast<f32>(sd_interval[2u * texel + 1u]));
    }
    for (var i = 0u; i < 8u; i++) {
        slots[i] = 3.0e38;
    }
    count = 0u;
    texel_hash = pcg_hash(texel ^ pcg_hash(params.seed));
    let d = params.divisor;
    var offset = vec2<f32>(0.5);
    if (d > 1u) {
        offset = params.jitter[(id.y % 4u) * 4u + id.x % 4u].xy;
    }
    let size = vec2<f32>(params.size);
    var point = (vec2<f32>(id.xy) - f32(params.guard) + offset) * f32(d);
    if (params.guard == 0u) {
        point = min(point, size - 0.5);
    }
    // Off the framebuffer no first layer is known: every layer from the near plane on. A
    // pixel without a first surface has nothing behind it either.
    var start = params.near;
    var open = true;
    if (all(point >= vec2<f32>(0.0)) && all(point < size)) {
        let first = textureLoad(first_layer, vec2<u32>(point), 0).r;
        start = first + params.separation;
        open = first > 0.0;
    }
    // The ray through `point`, its direction scaled so that t is linear view depth.
    let ndc = point / size * vec2<f32>(2.0, -2.0) + vec2<f32>(-1.0, 1.0);
    let far_point = params.inverse_projection * vec4<f32>(ndc, 0.0, 1.0);
    let view_dir = far_point.xyz / -far_point.z;
    let origin = (params.camera_to_world * vec4<f32>(0.0, 0.0, 0.0, 1.0)).xyz;
    let dir = (params.camera_to_world * vec4<f32>(view_dir, 0.0)).xyz;
    let t_min = max(start, needed.x);
    if (open && t_min <= needed.y) {
        bvh_traverse(origin, dir, t_min, needed.y);
    }
    for (var i = 0u; i < RESERVOIR; i++) {
        sd_map[texel * RESERVOIR + i] = bitcast<u32>(select(0.0, params.near / slots[i], slots[i] < 3.0e38));
    }
    sd_map[params.hits_offset + texel] = count;
}
