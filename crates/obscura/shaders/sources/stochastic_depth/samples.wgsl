// Reading the stochastic depth map (seed 001 §3.1, made by map.wgsl) for one estimator sample:
// every stored sample at the sample's pixel, each turned into the estimator's value and combined
// with what the caller found before (estimator_combine). Shared by the stochastic-depth source
// (read.wgsl, over the first layer's answer) and the multi-view schedule's second view
// (schedules/multiview/lookup.wgsl, where the map keeps every layer).
//
// Preceded by bindings generated in src/sources/stochastic_depth/mod.rs (WGSL cannot index an array
// of multisampled textures): the SD_MAPS maps of SD_SAMPLES samples each, read by
// `fn sd_load(map: u32, pixel: vec2<i32>, s: u32) -> f32` (reversed-Z: near / linear depth,
// 0 = empty; `pixel` lies in the framebuffer, or in the ray-traced map's guard band where
// `sd_guard_covers(pixel)`).

// The projection's near plane (the first member of map.wgsl's SdRaster).
@group(GROUP_SOURCE) @binding(SOURCE_SD_NEAR) var<uniform> sd_near: vec4<f32>;

// `stochastic_depth.compensation` (seed 001 §4, "missing occlusion compensation", Figs. 7–8): the
// occlusion a stochastic sample contributes is multiplied by this factor before it meets the first
// surface's, to make up for occluders the few samples missed (the paper found 2 works at low
// sample counts; 1, the default, is the plain estimator). What "occlusion contributed" means is the
// estimator's (`estimator_compensate`).
override SD_COMPENSATION: f32 = 1.0;

// A map that fills a pixel's samples from the first on, so that the first empty one ends the
// pixel's depths: the ray-traced map's reservoir (its first N distinct hits take the slots in
// order, and a later hit only ever overwrites one: ray_stochastic_depth/collect.wgsl), and the
// raster map's `nearest` selection. Off: empty samples may lie anywhere (Alg. 1's stochastic
// choice).
override SD_COMPACT: bool = false;

// A compact map whose depths are also nearest first: the raster map's `nearest` selection
// (map.wgsl, sd_store_nearest). The ray-traced reservoir, stored sorted, made its map pass 1–2 %
// slower and only GTAO-VB's reads faster (H200, BENCHMARKS.md): it is not sorted.
override SD_SORTED: bool = false;

// Resolve each distinct depth of a pixel once, nearest first (set by src/schedules/mod.rs where
// the estimator measured faster with it, `Estimator::resolves_distinct_depths`; S = 4, the
// default). The stochastic map stores a hidden fragment in ⌊αS + ξ⌋ of a pixel's samples (1.5 on
// average at the default α = 1.5/S) and leaves others empty anywhere, and the unrolled loop over
// the samples made a value wherever any lane of a warp had a depth in sample k. With the copies
// emptied and the depths sorted, the loop ends at the first empty one, and a warp runs as many
// values as its busiest lane has distinct depths (or fewer, SD_SETTLED_STOPS). Every estimator's
// combine keeps one of its arguments (a minimum, a maximum, a union of bits, the larger by a key),
// so a depth met once instead of twice and in another order gives the same value. A loop over the
// depths that took the nearest left each turn was twice as slow (H200, BENCHMARKS.md, issue 11).
override SD_DISTINCT: bool = false;

// For an estimator whose `hidden` is exact (no deeper surface at the pixel can change the value
// when it is false; `Estimator::exact_hidden`), wherever the depths come nearest first
// (SD_DISTINCT, SD_SORTED): the rest lie deeper, so the loop ends at the first depth that says
// so. Compensated values are not held to that, so they go on.
override SD_SETTLED_STOPS: bool = false;

// The value of the stored depth `v` (reversed Z) as the sample's occluder.
fn sd_occluder(p: EstimatorPixel, s: EstimatorSample, l: DepthLookup, v: f32) -> EstimatorValue {
    var value = estimator_occluder_at(p, s, l.px, sd_near.x / v).value;
    if (SD_COMPENSATION != 1.0) {
        value = estimator_compensate(p, s, value, SD_COMPENSATION);
    }
    return value;
}

// One step of a pixel's depths taken nearest first: `value` combined with the stored depth `v`'s,
// and whether no deeper depth at the pixel can change it any more (SD_SETTLED_STOPS).
struct SdNearestStep {
    value: EstimatorValue,
    settled: bool,
}

fn sd_nearest_step(
    p: EstimatorPixel,
    s: EstimatorSample,
    l: DepthLookup,
    value: EstimatorValue,
    v: f32,
) -> SdNearestStep {
    let o = estimator_occluder_at(p, s, l.px, sd_near.x / v);
    if (SD_COMPENSATION != 1.0) {
        let compensated = estimator_compensate(p, s, o.value, SD_COMPENSATION);
        return SdNearestStep(estimator_combine(value, compensated), false);
    }
    return SdNearestStep(estimator_combine(value, o.value), SD_SETTLED_STOPS && !o.hidden);
}

// The four stored depths of a pixel (0: empty) with every later copy of one depth emptied,
// sorted nearest (largest reversed Z) first, so the empty ones come last.
fn sd_distinct_nearest_first(stored: vec4<f32>) -> vec4<f32> {
    var v = stored;
    v.y = select(v.y, 0.0, v.y == v.x);
    v.z = select(v.z, 0.0, v.z == v.x || v.z == v.y);
    v.w = select(v.w, 0.0, v.w == v.x || v.w == v.y || v.w == v.z);
    // A sorting network of four: (x, y), (z, w), (x, z), (y, w), (y, z).
    var a = vec4<f32>(max(v.x, v.y), min(v.x, v.y), max(v.z, v.w), min(v.z, v.w));
    a = vec4<f32>(max(a.x, a.z), max(a.y, a.w), min(a.x, a.z), min(a.y, a.w));
    return vec4<f32>(a.x, max(a.y, a.z), min(a.y, a.z), a.w);
}

// `l.value` combined with the values of every sample the map stores at `l.px`.
fn sd_resolve(p: EstimatorPixel, s: EstimatorSample, l: DepthLookup) -> EstimatorValue {
    let pixel = vec2<i32>(floor(l.px));
    var value = l.value;
    for (var m = 0u; m < SD_MAPS; m++) {
        if (SD_DISTINCT && SD_SAMPLES == 4u && !SD_COMPACT && !SD_SORTED) {
            // The four loads written out: loaded in a loop into a vector the passes measured
            // 6–16 % slower (H200, BENCHMARKS.md).
            let d = sd_distinct_nearest_first(vec4<f32>(
                sd_load(m, pixel, 0u),
                sd_load(m, pixel, 1u),
                sd_load(m, pixel, 2u),
                sd_load(m, pixel, 3u),
            ));
            for (var k = 0u; k < 4u; k++) {
                if (!(d[k] > 0.0)) {
                    break;
                }
                let step = sd_nearest_step(p, s, l, value, d[k]);
                value = step.value;
                if (step.settled) {
                    break;
                }
            }
            continue;
        }
        for (var k = 0u; k < SD_SAMPLES; k++) {
            let v = sd_load(m, pixel, k);
            if ((SD_COMPACT || SD_SORTED) && !(v > 0.0)) {
                break;
            }
            if (SD_SORTED) {
                let step = sd_nearest_step(p, s, l, value, v);
                value = step.value;
                if (step.settled) {
                    break;
                }
            } else if (v > 0.0) {
                value = estimator_combine(value, sd_occluder(p, s, l, v));
            }
        }
    }
    return value;
}
