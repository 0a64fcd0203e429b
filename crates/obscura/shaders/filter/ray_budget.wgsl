// The ray budget (issue 58; ours): at most `budget` hemisphere rays a frame, given to the pixels
// whose accumulated AO is least certain. Three passes before the AO pass, after
// temporal_accumulation.wgsl (its bindings and `read_history`, so a pixel's history is found by
// the same reprojection the accumulation then uses):
// - `priority`: each visible pixel's key, from its reprojected history (AO a, frames n): the
//   variance of its running mean of n·N rays (common/visibility_variance.wgsl), on a log scale
//   in the key's high 10 bits; no history sorts first. Its low 6 bits are a hash of the pixel
//   and frame, so pixels of equal priority are taken in a different order each frame. Every surface pixel's key is counted in a histogram of the 2^16 keys.
// - `threshold` (one workgroup): walks the histogram from the highest key down and finds the key
//   T at which N rays for every pixel above would pass the budget: pixels above T get N rays,
//   pixels at T share what is left (the same count each, at most N), pixels below get none, so
//   the rays granted never exceed the budget. The histogram is emptied on the way.
// - `grant`: each pixel's rays into the grant image the AO pass reads (FRAME_RAY_GRANT).
// A selection by histogram rather than a sort or an atomic counter: two small passes at any
// size, and the same grants for the same inputs (a counter would hand out the last rays in the
// order threads happen to run).

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

@compute @workgroup_size(8, 8)
fn priority(@builtin(global_invocation_id) gid: vec3<u32>) {
    if (any(gid.xy >= view.visible_size)) {
        return;
    }
    let id = gid.xy;
    let index = id.y * view.visible_size.x + id.x;
    let full = id + vec2<u32>(view.guard_band);
    let z = textureLoad(depth_tex, full, 0).x;
    if (is_background(z)) {
        keys[index] = 0u;
        return;
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
    let level = priority_level(history.x, round(history.y));
    let hash = pcg_hash(pcg_hash(budget.frame ^ 0x68bc21ebu) ^ (id.x + pcg_hash(id.y)));
    let key = (level << HASH_BITS) | (hash >> (32u - HASH_BITS));
    keys[index] = key;
    atomicAdd(&histogram[key], 1u);
}

const THREADS: u32 = 256u;
const KEYS_PER_THREAD: u32 = KEY_COUNT / THREADS;
// Pixels each thread's keys hold, then (after the scan) pixels above each thread's keys.
var<workgroup> above: array<u32, THREADS>;

@compute @workgroup_size(256)
fn threshold(@builtin(local_invocation_index) t: u32) {
    // Thread t holds keys [t·256, t·256 + 256); key 0 (the background) is never counted.
    let first = t * KEYS_PER_THREAD;
    var own = 0u;
    for (var k = 0u; k < KEYS_PER_THREAD; k++) {
        own += atomicLoad(&histogram[first + k]);
    }
    above[t] = own;
    workgroupBarrier();
    if (t == 0u) {
        // Suffix sums: the pixels with keys above each thread's range.
        var sum = 0u;
        for (var u = THREADS; u > 0u; u--) {
            let count = above[u - 1u];
            above[u - 1u] = sum;
            sum += count;
        }
        result.threshold = 0u;
        result.rays_at_threshold = budget.rays;
        result.wanted = sum * budget.rays;
        result.budget = budget.budget;
        result.granted = min(sum * budget.rays, budget.budget);
    }
    storageBarrier();
    workgroupBarrier();
    // At most one thread finds the key where the budget runs out (the ranges are disjoint and
    // the counts above grow downwards).
    var pixels = above[t];
    for (var k = KEYS_PER_THREAD; k > 0u; k--) {
        let key = first + k - 1u;
        let count = atomicExchange(&histogram[key], 0u);
        if (count > 0u && pixels * budget.rays <= budget.budget
            && (pixels + count) * budget.rays > budget.budget) {
            let rays = (budget.budget - pixels * budget.rays) / count;
            result.threshold = key;
            result.rays_at_threshold = rays;
            result.granted = pixels * budget.rays + count * rays;
        }
        pixels += count;
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
