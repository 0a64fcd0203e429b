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

// The raster map's `nearest` selection (map.wgsl, sd_store_nearest) fills a pixel's samples
// from the first on: the first empty one ends the pixel's depths. Off: empty samples may lie
// anywhere (Alg. 1's stochastic choice, the ray-traced reservoir).
override SD_SORTED: bool = false;

// `l.value` combined with the values of every sample the map stores at `l.px`.
fn sd_resolve(p: EstimatorPixel, s: EstimatorSample, l: DepthLookup) -> EstimatorValue {
    let pixel = vec2<i32>(floor(l.px));
    var value = l.value;
    for (var m = 0u; m < SD_MAPS; m++) {
        for (var k = 0u; k < SD_SAMPLES; k++) {
            let v = sd_load(m, pixel, k);
            if (SD_SORTED && !(v > 0.0)) {
                break;
            }
            if (v > 0.0) {
                var sample_value = estimator_occluder_at(p, s, l.px, sd_near.x / v).value;
                if (SD_COMPENSATION != 1.0) {
                    sample_value = estimator_compensate(p, s, sample_value, SD_COMPENSATION);
                }
                value = estimator_combine(value, sample_value);
            }
        }
    }
    return value;
}
