// Source "depth pyramid" (`sao`, `pyramid-hbao`; seed 004 §3.3, McGuire et al. 2012 §3): the
// estimator names the level each sample reads (`estimator_sample_level`); level 0 is the frame's
// depth (frame.wgsl's first_layer_lookup), level l ≥ 1 a texel of the pyramid, the mean linear
// depth of K^l × K^l pixels, placed at that block's centre. (At the block's centre rather than at
// the sample: depth is convex over a plane's pixels, so the mean lies on or behind the plane there
// and an unoccluded plane stays unoccluded at every level; at the sample it could lie in front.)
// Nothing is hidden: the pyramid only coarsens what the first layer shows.
//
// The source contract (docs/ARCHITECTURE.md): source_lookup, source_resolve, source_request.

struct PyramidParams {
    // Level l: x = K^l (pixels per texel), yz its size in texels (level 0: the framebuffer).
    levels: array<vec4<f32>, 8>,
}

@group(GROUP_SOURCE) @binding(SOURCE_PYRAMID_PARAMS) var<uniform> pyramid: PyramidParams;
// Layer l − 1: level l.
@group(GROUP_SOURCE) @binding(SOURCE_PYRAMID_LEVELS) var pyramid_levels: texture_2d_array<f32>;

fn source_lookup(p: EstimatorPixel, s: EstimatorSample) -> DepthLookup {
    let level = estimator_sample_level(s);
    if (level == 0u) {
        var l = first_layer_lookup(p, s);
        l.trace = false;
        return l;
    }
    var l: DepthLookup;
    l.value = estimator_unoccluded(p, s);
    l.trace = false;
    l.t_after = 0.0;
    let info = pyramid.levels[level];
    let texel = vec2<u32>(clamp(estimator_sample_px(p, s) / info.x, vec2<f32>(0.0), info.yz - 0.5));
    l.px = (vec2<f32>(texel) + 0.5) * info.x;
    let z = textureLoad(pyramid_levels, texel, level - 1u, 0).r;
    if (is_background(z)) {
        return l;
    }
    l.value = estimator_occluder_at(p, s, l.px, z).value;
    return l;
}

fn source_resolve(p: EstimatorPixel, s: EstimatorSample, l: DepthLookup) -> EstimatorValue {
    return l.value;
}

fn source_request(l: DepthLookup) {}
