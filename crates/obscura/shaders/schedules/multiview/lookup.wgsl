// Multi-view (seed 001 §3.4, Algorithm 3, lines 19–24), the second view's source: the second
// stochastic depth map keeps every layer (the first visible one included; no depth buffer of that
// view exists), so every sample inside the second framebuffer reads all of its depths
// (samples.wgsl's sd_resolve) and keeps the estimator's largest occlusion.

fn source_lookup(p: EstimatorPixel, s: EstimatorSample) -> DepthLookup {
    var l: DepthLookup;
    l.value = estimator_unoccluded(p, s);
    l.t_after = 0.0;
    let px = estimator_sample_px(p, s);
    let full = vec2<f32>(view.full_size);
    l.px = floor(clamp(px, vec2<f32>(0.0), full - 0.5)) + 0.5;
    l.trace = all(px >= vec2<f32>(0.0)) && all(px < full);
    return l;
}

fn source_resolve(p: EstimatorPixel, s: EstimatorSample, l: DepthLookup) -> EstimatorValue {
    return sd_resolve(p, s, l);
}

fn source_request(l: DepthLookup) {}
