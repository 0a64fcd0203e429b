// The ray budget (issue 58; ours): at most `budget` hemisphere rays a frame, given to the pixels
// whose accumulated AO is least certain. Four passes before the AO pass, after
// temporal_accumulation.wgsl (its bindings and `read_history`, so a pixel's history is found by
// the same reprojection the accumulation then uses):
// - `priority`: each visible pixel's priority, from its reprojected history (AO a, frames n):
//   the variance of its running mean of n·N rays (common/visibility_variance.wgsl), on a log
//   scale; no history sorts first. A tile of 32×4 pixels takes its neediest pixel's priority in
//   its key's high 10 bits, and in its low 6 bits a hash of the tile and frame, so tiles of equal
//   priority are taken in a different order each frame. Every surface pixel's key is counted in
//   a histogram of the 2^16 keys.
// - `block_sums` (one workgroup per block of 256 keys): each block's count of pixels.
// - `threshold` (one workgroup): finds the key T at which N rays for every pixel above would
//   pass the budget, first the block that holds it (a suffix scan of the block counts), then the
//   key within it (a suffix scan of its 256 keys): pixels above T get N rays, pixels at T share
//   what is left (the same count each, at most N), pixels below get none, so the rays granted
//   never exceed the budget. (Before, one workgroup walked all 2^16 keys, 256 a thread, and the
//   budget's passes took 0.55–0.65 ms at 1080p on an H100, BENCHMARKS.md; that walk is the
//   likely cause, not timed alone: a thread's keys were 1 KB apart from its neighbours', so no
//   load was coalesced, and each was waited for in turn.) The histogram is cleared before
//   `priority` (RayBudget::encode).
// - `grant`: each pixel's rays into the grant image the AO pass reads (FRAME_RAY_GRANT).
// A selection by histogram rather than a sort or an atomic counter: small passes at any size,
// and the same grants for the same inputs (a counter would hand out the last rays in the order
// threads happen to run).

struct BudgetParams {
    // Rays a frame, at most.
    budget: u32,
    // N, the rays a pixel casts when granted (hemisphere.rays).
    rays: u32,
    // Frames since the start (the hash's seed).
    frame: u32,
    pad0: u32,
}

// What `threshold` found (read back by AmbientOcclusion::read_ray_budget).
struct BudgetResult {
    // Keys above this get N rays; 0: every surface pixel does.
    threshold: u32,
    // The rays of each pixel whose key is the threshold.
    rays_at_threshold: u32,
    // Rays granted this frame (≤ budget).
    granted: u32,
    // Rays every surface pixel casting N would take.
    wanted: u32,
    // The budget this frame ran under.
    budget: u32,
    pad0: u32,
    pad1: u32,
    pad2: u32,
}

@group(1) @binding(0) var<uniform> budget: BudgetParams;
@group(1) @binding(1) var<storage, read_write> keys: array<u32>;
@group(1) @binding(2) var<storage, read_write> histogram: array<atomic<u32>>;
@group(1) @binding(3) var<storage, read_write> result: BudgetResult;
@group(1) @binding(4) var grant_out: texture_storage_2d<r32uint, write>;
// Pixels per block of 256 keys (`block_sums`).
@group(1) @binding(5) var<storage, read_write> block_counts: array<u32>;

const KEY_COUNT: u32 = 65536u;
const HASH_BITS: u32 = 6u;
// Priority levels 1 … 1023 (0 is the background's key).
const TOP_LEVEL: u32 = 1023u;
// log2 of the variance to a level: 42 levels per octave from 2^-24 (a pixel a(1 − a)/(nN) can
// reach 2^-17 at 255 frames of 32 rays).
const LEVELS_PER_OCTAVE: f32 = 42.0;
const LOWEST_LOG2: f32 = -24.0;

// The priority level of a pixel whose history holds AO `a` over `frames` frames of N rays.
fn priority_level(a: f32, frames: f32) -> u32 {
    if (frames < 0.5) {
        return TOP_LEVEL;
    }
    let variance = visibility_variance(a, frames * f32(budget.rays));
    let level = (log2(variance) - LOWEST_LOG2) * LEVELS_PER_OCTAVE;
    return 1u + u32(clamp(level, 0.0, f32(TOP_LEVEL - 2u)));
}

// A tile of 32×4 pixels takes one key: the AO pass runs 32×8 workgroups (schedules/
// single_main.wgsl), so a warp of 32 lanes is one row of a tile, and a tile's pixels are
// granted rays or not together. With a key per pixel the granted pixels were scattered over
// nearly every warp, and a warp runs as long as its busiest lane: the AO pass took as long under
// a quarter of the rays as under all (BENCHMARKS.md). The tile's priority is its neediest pixel's
// (a pixel with no history puts its tile first).
const TILE: vec2<u32> = vec2<u32>(32u, 4u);
var<workgroup> tile_level: atomic<u32>;

// The priority level of visible pixel `id`, 0 on background or outside the image.
fn pixel_level(id: vec2<u32>) -> u32 {
    if (any(id >= view.visible_size)) {
        return 0u;
    }
    let full = id + vec2<u32>(view.guard_band);
    let z = textureLoad(depth_tex, full, 0).x;
    if (is_background(z)) {
        return 0u;
    }
    let p = pixel_to_view(view, vec2<f32>(full) + 0.5, z);
    let n_world = (params.current_to_world * vec4<f32>(textureLoad(normal_tex, full, 0).xyz, 0.0)).xyz;
    var history = vec2<f32>(0.0);
    if (params.history_valid != 0u) {
        let p_prev = (params.current_to_previous * vec4<f32>(p, 1.0)).xyz;
        if (-p_prev.z > 0.0) {
            let q = view_to_pixel(view, p_prev) - vec2<f32>(f32(view.guard_band) + 0.5);
            history = read_history(q, -p_prev.z, n_world);
        }
    }
    return priority_level(history.x, round(history.y));
}

@compute @workgroup_size(32, 4)
fn priority(
    @builtin(global_invocation_id) gid: vec3<u32>,
    @builtin(workgroup_id) tile: vec3<u32>,
    @builtin(local_invocation_index) t: u32,
) {
    if (t == 0u) {
        atomicStore(&tile_level, 0u);
    }
    workgroupBarrier();
    let id = gid.xy;
    let level = pixel_level(id);
    atomicMax(&tile_level, level);
    let shared_level = workgroupUniformLoad(&tile_level);
    if (any(id >= view.visible_size)) {
        return;
    }
    let index = id.y * view.visible_size.x + id.x;
    if (level == 0u) {
        keys[index] = 0u;
        return;
    }
    let hash = pcg_hash(pcg_hash(budget.frame ^ 0x68bc21ebu) ^ (tile.x + pcg_hash(tile.y)));
    let key = (shared_level << HASH_BITS) | (hash >> (32u - HASH_BITS));
    keys[index] = key;
    atomicAdd(&histogram[key], 1u);
}

const THREADS: u32 = 256u;
// 256 blocks of 256 keys.
const BLOCK: u32 = 256u;
var<workgroup> scan: array<u32, THREADS>;
// The block that holds the threshold key (`threshold`), or NONE.
var<workgroup> found_block: u32;
const NONE: u32 = 0xffffffffu;

// Each thread's value `v` into `scan`, then `scan[t]` = the sum of the values of threads t and
// above (Hillis–Steele, towards the lower indices). Called by the whole workgroup.
fn suffix_sums(t: u32, v: u32) -> u32 {
    scan[t] = v;
    for (var offset = 1u; offset < THREADS; offset *= 2u) {
        workgroupBarrier();
        var above = 0u;
        if (t + offset < THREADS) {
            above = scan[t + offset];
        }
        workgroupBarrier();
        scan[t] += above;
    }
    workgroupBarrier();
    return scan[t];
}

@compute @workgroup_size(256)
fn block_sums(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) t: u32) {
    // Key group.x · 256 + t: neighbouring threads read neighbouring keys.
    let total = suffix_sums(t, atomicLoad(&histogram[group.x * BLOCK + t]));
    if (t == 0u) {
        block_counts[group.x] = total;
    }
}

// Whether a key range holding `count` pixels, with `above` pixels in the keys over it, is where
// N rays a pixel first pass the budget.
fn budget_ends_in(above: u32, count: u32) -> bool {
    return count > 0u && above * budget.rays <= budget.budget
        && (above + count) * budget.rays > budget.budget;
}

@compute @workgroup_size(256)
fn threshold(@builtin(local_invocation_index) t: u32) {
    // Blocks: thread t holds block t (keys t·256 …); key 0 (the background) is never counted.
    let count = block_counts[t];
    let with_block = suffix_sums(t, count);
    let above_block = with_block - count;
    if (t == 0u) {
        result.threshold = 0u;
        result.rays_at_threshold = budget.rays;
        result.wanted = with_block * budget.rays;
        result.budget = budget.budget;
        result.granted = min(with_block * budget.rays, budget.budget);
        found_block = NONE;
    }
    workgroupBarrier();
    // At most one block qualifies (the ranges are disjoint, the counts above grow downwards).
    if (budget_ends_in(above_block, count)) {
        found_block = t;
        scan[0] = above_block;
    }
    let block = workgroupUniformLoad(&found_block);
    if (block == NONE) {
        return;
    }
    // Keys of that block: thread t holds key block·256 + t.
    let base = workgroupUniformLoad(&scan[0]);
    let key = block * BLOCK + t;
    let key_count = atomicLoad(&histogram[key]);
    let above = base + suffix_sums(t, key_count) - key_count;
    if (budget_ends_in(above, key_count)) {
        let rays = (budget.budget - above * budget.rays) / key_count;
        result.threshold = key;
        result.rays_at_threshold = rays;
        result.granted = above * budget.rays + key_count * rays;
    }
}

@compute @workgroup_size(8, 8)
fn grant(@builtin(global_invocation_id) gid: vec3<u32>) {
    if (any(gid.xy >= view.visible_size)) {
        return;
    }
    let key = keys[gid.y * view.visible_size.x + gid.x];
    var rays = 0u;
    if (key > result.threshold) {
        rays = budget.rays;
    } else if (key == result.threshold && key != 0u) {
        rays = result.rays_at_threshold;
    }
    textureStore(grant_out, gid.xy, vec4<u32>(rays));
}
