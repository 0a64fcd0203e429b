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
