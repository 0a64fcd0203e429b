// Hidden-depth source "dual depth" (`vao-dual`, seed 000 §2.1 / docs/AUTHORS_CODE.md §1.2): as
// first_layer.wgsl, but a sample whose first surface may hide more (the estimator's verdict) also
// reads the second depth layer from depth peeling and combines the two values.

@group(GROUP_SOURCE) @binding(SOURCE_SECOND_DEPTH) var second_depth: texture_2d<f32>;

fn source_lookup(p: EstimatorPixel, s: EstimatorSample) -> DepthLookup {
    return first_layer_lookup(p, s);
}

fn source_resolve(p: EstimatorPixel, s: EstimatorSample, l: DepthLookup) -> EstimatorValue {
    let z2 = textureLoad(second_depth, vec2<u32>(l.px), 0).r;
    if (is_background(z2)) {
        return l.value;
    }
    return estimator_combine(l.value, estimator_occluder_at(p, s, l.px, z2).value);
}

// Two-phase phase 1: the second layer exists already.
fn source_request(l: DepthLookup) {}
