// Hidden-depth source "stochastic depth" (SD-VAO, seed 000 §3.7; docs/AUTHORS_CODE.md §1.2, §1.3):
// as dual_depth.wgsl, but a sample whose first surface may hide more reads every sample of the
// stochastic depth map at the sample's pixel (seed 001 §3.1; made by stochastic_depth/map.wgsl) and
// combines all of their values (VAO: the lowest visibility).
//
// Preceded by samples.wgsl (the map's bindings and `sd_resolve`).

// `stochastic_depth.query = "always"`: read the map for every sample whose pixel shows a surface,
// not only where the estimator says the first surface may hide more (seed 001 §3.3's heuristic,
// the default); a switch to measure what the heuristic saves and what it changes.
override SD_QUERY_ALWAYS: bool = false;

// The ray-traced map's radius cutoff (seed 002 §3.4, `ray_sd.radius_cutoff`): a sample closer
// than this many pixels to its shading pixel keeps the first layer's answer and never reads (or,
// in phase 1, requests) the map. 0: off (the raster map's rows).
override SD_RADIUS_CUTOFF: f32 = 0.0;

// The ray-traced map's ray intervals (seed 002 §3.2, `ray_sd.intervals`): a traced sample also
// carries the depths along its ray that can change its value (estimator_depth_interval), which
// phase 1's request records for the map's rays. Off: the raster map's rows.
override SD_INTERVALS: bool = false;

// The map's own guard band (seed 002 §3.5, `ray_sd.guard_band` for the ray-traced map; ours,
// `stochastic_depth.guard_band`, for the raster map): a sample that falls off the framebuffer,
// where the map's band holds its pixel (`sd_guard_covers`, from the generated bindings; without
// a band they set SD_HAS_GUARD_BAND false so that none of this is compiled in), knows no first
// layer: it starts unoccluded and always reads the map, whose band texels hold every layer (the
// authors' "force a ray off screen").
// Elsewhere off the framebuffer a sample reads the framebuffer's edge (first_layer_lookup).
fn guard_band_lookup(p: EstimatorPixel, s: EstimatorSample) -> DepthLookup {
    var l: DepthLookup;
    l.trace = false;
    if (!SD_HAS_GUARD_BAND) {
        return l;
    }
    let raw = clamp(estimator_sample_px(p, s), vec2<f32>(-1.0e6), vec2<f32>(1.0e6));
    let pixel = vec2<i32>(floor(raw));
    if (all(pixel >= vec2<i32>(0)) && all(pixel < vec2<i32>(view.full_size))) {
        return l;
    }
    if (!sd_guard_covers(pixel)) {
        return l;
    }
    l.value = estimator_unoccluded(p, s);
    l.t_after = 0.0;
    l.px = vec2<f32>(pixel) + 0.5;
    l.trace = true;
    if (SD_INTERVALS) {
        l.interval = estimator_depth_interval(p, s, l.px);
    }
    return l;
}

// `trace` = read the stochastic depth map at pixel `px`; the two-phase schedule's phase 1 flags
// exactly these samples.
fn source_lookup(p: EstimatorPixel, s: EstimatorSample) -> DepthLookup {
    let band = guard_band_lookup(p, s);
    if (band.trace) {
        return band;
    }
    var l = first_layer_lookup(p, s);
    if (SD_QUERY_ALWAYS && !l.trace) {
        let pixel = vec2<u32>(l.px);
        l.trace = any(pixel != estimator_shading_pixel(p))
            && !is_background(textureLoad(depth_tex, pixel, 0).r);
    }
    if (SD_RADIUS_CUTOFF > 0.0 && l.trace) {
        let shading = vec2<f32>(estimator_shading_pixel(p)) + 0.5;
        l.trace = distance(l.px, shading) >= SD_RADIUS_CUTOFF;
    }
    if (SD_INTERVALS && l.trace) {
        l.interval = estimator_depth_interval(p, s, l.px);
    }
    return l;
}

// The value combined over the first surface (`l.value`) and every stored stochastic sample
// (samples.wgsl).
fn source_resolve(p: EstimatorPixel, s: EstimatorSample, l: DepthLookup) -> EstimatorValue {
    return sd_resolve(p, s, l);
}
