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
    return single_pass(p).acc;
}

// The sample loop's results: the estimator's state and, with BENT_NORMALS, the sums of its
// per-sample bent vectors over the samples' values and over their unoccluded values
// (estimator_bent_sample; estimators that form the bent normal from `acc` add nothing).
struct SinglePass {
    acc: EstimatorAccum,
    bent_visible: vec3<f32>,
    bent_open: vec3<f32>,
}

// Resolve the samples the first look cannot decide after every other sample, one per loop turn
// over a bit mask of them (ours): in the unrolled loop below a warp runs sample i's resolve
// (the hidden-depth reads) whenever any of its lanes needs it, so with a quarter of the samples
// flagged it runs nearly every one; deferred, a warp runs as many resolves as its busiest lane
// has. Set by schedules::deferred_resolve where it measured faster (VAO and SSAO over the maps
// and column rays); needs an estimator whose result does not depend on the order of its
// samples and at most 32 samples (one bit each).
override DEFERRED_RESOLVE: bool = false;

fn single_pass(p: EstimatorPixel) -> SinglePass {
    var r: SinglePass;
    r.acc = estimator_accum_init();
    r.bent_visible = vec3<f32>(0.0);
    r.bent_open = vec3<f32>(0.0);
    // DEFERRED_RESOLVE: the samples left for the loop below, one bit each.
    var flagged = 0u;
    // Written out as one call per sample where no costly resolve is inline
    // (schedules::write_out_sample_loop, which finds this loop by its text).
    for (var i = 0u; i < SAMPLE_COUNT; i++) {
        single_pass_sample(p, i, &r, &flagged);
    }
    // The flagged samples, each made again from its index with its first look (a cached read)
    // rather than held in registers.
    while (flagged != 0u) {
        let i = firstTrailingBit(flagged);
        flagged &= flagged - 1u;
        let s = estimator_sample(p, i);
        r = single_pass_value(p, s, r, source_resolve(p, s, source_lookup(p, s)));
    }
    return r;
}

// Sample `i` of the loop above: its value into `r`, or its bit into `flagged` (DEFERRED_RESOLVE).
fn single_pass_sample(p: EstimatorPixel, i: u32, r: ptr<function, SinglePass>, flagged: ptr<function, u32>) {
    let s = estimator_sample(p, i);
    if (!estimator_sample_active(s)) {
        return;
    }
    let l = source_lookup(p, s);
    if (DEFERRED_RESOLVE && SAMPLE_COUNT <= 32u && l.trace) {
        *flagged |= 1u << i;
    } else {
        var value = l.value;
        if (l.trace) {
            value = source_resolve(p, s, l);
        }
        *r = single_pass_value(p, s, *r, value);
    }
    (*r).acc = estimator_accum_sample((*r).acc, s);
    if (BENT_NORMALS) {
        (*r).bent_open += estimator_bent_sample(p, s, estimator_unoccluded(p, s));
    }
}

// Adds sample `s`'s value to the loop's results.
fn single_pass_value(p: EstimatorPixel, s: EstimatorSample, r: SinglePass, value: EstimatorValue) -> SinglePass {
    var out = r;
    out.acc = estimator_accum_value(r.acc, s, value);
    if (BENT_NORMALS) {
        out.bent_visible += estimator_bent_sample(p, s, value);
    }
    return out;
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
    let result = single_pass(p);
    let acc = result.acc;
    if (BENT_NORMALS) {
        let bent = estimator_bent_normal(p, acc, result.bent_visible, result.bent_open);
        textureStore(bent_out, id, vec4<f32>(bent, 1.0));
    }
    if (ESTIMATOR_DEBUG) {
        textureStore(ao_out, id, vec4<f32>(estimator_debug(p, acc)));
    } else {
        textureStore(ao_out, id, vec4<f32>(estimator_finish(p, acc)));
    }
}
