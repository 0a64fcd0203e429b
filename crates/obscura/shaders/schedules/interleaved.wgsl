// Schedule "interleaved" (seed-code-notes §1.7, the authors' HBAO+: NVIDIA's interleaved
// rendering): the AO runs layer by layer over the 16 quarter-resolution depth layers of
// interleaved_split.wgsl. A pixel's samples read only its own layer, the framebuffer pixels of its
// residue class (x % 4, y % 4): each sample takes the class's pixel nearest to where the estimator
// put it, so a workgroup's fetches stay within a quarter-size texture (the cache-friendliness the
// technique exists for), and sample offsets become multiples of 4 px. Every pixel of a layer shares
// the pattern entry of the 4×4 Bayer table, so "one jitter per layer" holds by construction.
//
// The estimator contract as the single pass uses it, samples in order (order-dependent estimators
// work too); the first depth layer is the only source (the table allows no other): this file does
// the lookup itself, the first-layer source's functions stay unused.

@group(GROUP_SCHEDULE) @binding(SCHEDULE_DEPTH_LAYERS) var depth_layers: texture_2d_array<f32>;

// The value of sample `s` of pixel `p` from the pixel's own layer.
fn interleaved_value(p: EstimatorPixel, s: EstimatorSample) -> EstimatorValue {
    let own = estimator_shading_pixel(p);
    let residue = own % 4u;
    let size = vec2<f32>(textureDimensions(depth_layers).xy);
    let cell = vec2<u32>(clamp(
        round((estimator_sample_px(p, s) - 0.5 - vec2<f32>(residue)) / 4.0),
        vec2<f32>(0.0),
        size - 1.0,
    ));
    let pixel = cell * 4u + residue;
    if (all(pixel == own)) {
        return estimator_unoccluded(p, s);
    }
    let z = textureLoad(depth_layers, cell, residue.x + 4u * residue.y, 0).r;
    if (is_background(z)) {
        return estimator_unoccluded(p, s);
    }
    return estimator_occluder(p, s, pixel_to_view(view, vec2<f32>(pixel) + 0.5, z)).value;
}

// One invocation per framebuffer pixel of layer `id.z`, (4x, 4y) + its residue; the guard band
// and what lies past the visible image are skipped.
@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let pixel = gid.xy * 4u + vec2<u32>(gid.z % 4u, gid.z / 4u);
    let guard = vec2<u32>(view.guard_band);
    if (any(pixel < guard) || any(pixel - guard >= view.visible_size)) {
        return;
    }
    let id = pixel - guard;
    let p = estimator_pixel(id);
    if (!estimator_pixel_valid(p)) {
        textureStore(ao_out, id, vec4<f32>(1.0));
        return;
    }
    var acc = estimator_accum_init();
    for (var i = 0u; i < SAMPLE_COUNT; i++) {
        let s = estimator_sample(p, i);
        if (!estimator_sample_active(s)) {
            continue;
        }
        acc = estimator_accum_value(acc, s, interleaved_value(p, s));
        acc = estimator_accum_sample(acc, s);
    }
    if (ESTIMATOR_DEBUG) {
        textureStore(ao_out, id, vec4<f32>(estimator_debug(p, acc)));
    } else {
        textureStore(ao_out, id, vec4<f32>(estimator_finish(p, acc)));
    }
}
