// Schedule "single pass" (`vao`, `vao-dual`, `rt-vao`, `sd-vao`): one invocation per visible pixel
// runs every sample of the estimator, each consulting the hidden-depth source inline. Any estimator
// and source that implement their contracts (docs/ARCHITECTURE.md) compose with it.

// The AO of one pixel: every active sample's value from the source (resolved at once where the
// first look cannot decide), accumulated and finished by the estimator. The ground truth
// (reference.wgsl) runs this loop too, over its all-layers source.
fn single_pass_ao(p: EstimatorPixel) -> f32 {
    return estimator_finish(p, single_pass_accum(p));
}

// The accumulated state of every active sample of pixel `p`, in order.
fn single_pass_accum(p: EstimatorPixel) -> EstimatorAccum {
    var acc = estimator_accum_init();
    for (var i = 0u; i < SAMPLE_COUNT; i++) {
        let s = estimator_sample(p, i);
        if (!estimator_sample_active(s)) {
            continue;
        }
        let l = source_lookup(p, s);
        var value = l.value;
        if (l.trace) {
            value = source_resolve(p, s, l);
        }
        acc = estimator_accum_value(acc, s, value);
        acc = estimator_accum_sample(acc, s);
    }
    return acc;
}

// Writes visible pixel `id`'s result: 1 where there is no surface, else the estimator's AO, or
// its debug image under ESTIMATOR_DEBUG (frame.wgsl). The single pass and the interleaved
// schedule both end here.
fn store_pixel(id: vec2<u32>, p: EstimatorPixel) {
    if (!estimator_pixel_valid(p)) {
        textureStore(ao_out, id, vec4<f32>(1.0));
        if (BENT_NORMALS) {
            textureStore(bent_out, id, vec4<f32>(0.0));
        }
        return;
    }
    let acc = single_pass_accum(p);
    if (BENT_NORMALS) {
        textureStore(bent_out, id, vec4<f32>(estimator_bent_normal(p, acc), 1.0));
    }
    if (ESTIMATOR_DEBUG) {
        textureStore(ao_out, id, vec4<f32>(estimator_debug(p, acc)));
    } else {
        textureStore(ao_out, id, vec4<f32>(estimator_finish(p, acc)));
    }
}
