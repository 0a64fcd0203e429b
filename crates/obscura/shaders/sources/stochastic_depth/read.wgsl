// Hidden-depth source "stochastic depth" (SD-VAO, seed 000 §3.7; seed-code-notes §1.2/1.3): as
// dual_depth.wgsl, but a sample whose first surface may hide more reads every sample of the
// stochastic depth map at the sample's pixel (seed 001 §3.1; made by stochastic_depth/map.wgsl) and
// combines all of their values (VAO: the lowest visibility).
//
// Preceded by bindings generated in src/sources/stochastic_depth/mod.rs (WGSL cannot index an array
// of multisampled textures): the SD_MAPS maps of SD_SAMPLES samples each, read by
// `fn sd_load(map: u32, pixel: vec2<u32>, s: u32) -> f32` (reversed-Z: near / linear depth,
// 0 = empty).

// The projection's near plane (the first member of map.wgsl's SdRaster).
@group(GROUP_SOURCE) @binding(SOURCE_SD_NEAR) var<uniform> sd_near: vec4<f32>;

// `stochastic_depth.query = "always"`: read the map for every sample whose pixel shows a surface,
// not only where the estimator says the first surface may hide more (seed 001 §3.3's heuristic,
// the default); a switch to measure what the heuristic saves and what it changes.
override SD_QUERY_ALWAYS: bool = false;

// `stochastic_depth.compensation` (seed 001 §4, "missing occlusion compensation", Figs. 7–8): the
// occlusion a stochastic sample contributes is multiplied by this factor before it meets the first
// surface's, to make up for occluders the few samples missed (the paper found 2 works at low
// sample counts; 1, the default, is the plain estimator). What "occlusion contributed" means is the
// estimator's (`estimator_compensate`).
override SD_COMPENSATION: f32 = 1.0;

// `trace` = read the stochastic depth map at pixel `px`; the two-phase schedule's phase 1 flags
// exactly these samples.
fn source_lookup(p: EstimatorPixel, s: EstimatorSample) -> DepthLookup {
    var l = first_layer_lookup(p, s);
    if (SD_QUERY_ALWAYS && !l.trace) {
        let pixel = vec2<u32>(l.px);
        l.trace = any(pixel != estimator_shading_pixel(p))
            && !is_background(textureLoad(depth_tex, pixel, 0).r);
    }
    return l;
}

// The value combined over the first surface (`l.value`) and every stored stochastic sample.
fn source_resolve(p: EstimatorPixel, s: EstimatorSample, l: DepthLookup) -> EstimatorValue {
    let pixel = vec2<u32>(l.px);
    var value = l.value;
    for (var m = 0u; m < SD_MAPS; m++) {
        for (var k = 0u; k < SD_SAMPLES; k++) {
            let v = sd_load(m, pixel, k);
            if (v > 0.0) {
                let pos = pixel_to_view(view, l.px, sd_near.x / v);
                var sample_value = estimator_occluder(p, s, pos).value;
                if (SD_COMPENSATION != 1.0) {
                    sample_value = estimator_compensate(p, s, sample_value, SD_COMPENSATION);
                }
                value = estimator_combine(value, sample_value);
            }
        }
    }
    return value;
}

// Two-phase phase 1: mark the sample's pixel (not the shading pixel) so the map is rasterised there
// (seed 000 §3.9). One u32 per framebuffer pixel; every writer stores 1.
@group(GROUP_SOURCE) @binding(SOURCE_SD_REQUEST) var<storage, read_write> sd_request: array<u32>;

fn source_request(l: DepthLookup) {
    let pixel = vec2<u32>(l.px);
    sd_request[pixel.y * view.full_size.x + pixel.x] = 1u;
}
