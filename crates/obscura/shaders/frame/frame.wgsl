// The frame (bind group 0; binding names from src/bindings.rs): the screen geometry, the first
// depth layer and normals every AO pass reads, and the AO image it writes. Also the first layer's
// answer for one sample, which every depth-buffer source starts from.
//
// Needs common/view.wgsl and an estimator (shaders/estimators/) in front.

@group(GROUP_FRAME) @binding(FRAME_VIEW) var<uniform> view: View;
@group(GROUP_FRAME) @binding(FRAME_DEPTH) var depth_tex: texture_2d<f32>;
@group(GROUP_FRAME) @binding(FRAME_NORMALS) var normal_tex: texture_2d<f32>;
@group(GROUP_FRAME) @binding(FRAME_AO_OUT) var ao_out: texture_storage_2d<r32float, write>;
// View-space unit bent normals (xyz; w = 1), written only with BENT_NORMALS.
@group(GROUP_FRAME) @binding(FRAME_BENT_OUT) var bent_out: texture_storage_2d<rgba16float, write>;

// `bent_normals` (seed 001 §4): the single-pass schedule writes the estimator's bent normal
// (estimator_bent_normal) next to its AO; estimators keep what only it needs behind it.
override BENT_NORMALS: bool = false;
// first_layer_lookup loads a sample's depth after its shading-pixel test instead of before it
// (src/technique.rs Estimator::late_first_layer_load says where).
override FIRST_LAYER_LOAD_LATE: bool = false;

// The shading point of a visible pixel in the view the estimators work in (`frame_point`, made by
// frame/point.wgsl or, in the multi-view schedule's second view, schedules/multiview/point.wgsl).
struct FramePoint {
    // Framebuffer pixel of the point in the working view.
    pixel: vec2<u32>,
    pos: vec3<f32>,
    normal: vec3<f32>,
    valid: bool,
}

// The single-pass and interleaved schedules write the estimator's debug image (estimator_debug)
// instead of its AO (`render --debug-out`); estimators keep what only that image needs behind it,
// so the usual pipelines compile without it.
override ESTIMATOR_DEBUG: bool = false;

// What a source knows about one sample after its first look: the estimator's value for it
// (`value`, of the estimator's `EstimatorValue` type: e.g. VAO's free column length), whether the source must still resolve it (`trace`:
// a deeper surface could change the value), the framebuffer pixel coordinates it looked at (`px`,
// a pixel centre) and, for rays, the ray parameter past which to look (`t_after`).
struct DepthLookup {
    value: EstimatorValue,
    trace: bool,
    px: vec2<f32>,
    t_after: f32,
    // The ray-traced stochastic depth map with ray intervals: the linear depths along the ray
    // through `px` that can change the value (estimator_depth_interval); unused elsewhere.
    interval: vec2<f32>,
}

// The first depth layer's answer for a sample, shared by the depth-buffer sources (first layer,
// dual depth, stochastic depth): read at the pixel the sample falls in, clamped into the
// framebuffer (guard band included) and snapped to its centre. A sample snapping to the shading
// pixel itself, or to background, is unoccluded. `trace` is the estimator's "needs hidden
// depth?" verdict on the surface found there.
fn first_layer_lookup(p: EstimatorPixel, s: EstimatorSample) -> DepthLookup {
    var l: DepthLookup;
    l.value = estimator_unoccluded(p, s);
    l.trace = false;
    l.t_after = 0.0;
    let sample_pixel = vec2<u32>(clamp(estimator_sample_px(p, s), vec2<f32>(0.0), vec2<f32>(view.full_size) - 0.5));
    l.px = vec2<f32>(sample_pixel) + 0.5;
    // Loaded before the test below, whose answer it does not need: the load is then issued
    // without waiting on a branch (0.5–1.7 % off the AO passes on an H200, BENCHMARKS.md), unless
    // FIRST_LAYER_LOAD_LATE.
    var z = 0.0;
    if (!FIRST_LAYER_LOAD_LATE) {
        z = textureLoad(depth_tex, sample_pixel, 0).r;
    }
    if (all(sample_pixel == estimator_shading_pixel(p))) {
        return l;
    }
    if (FIRST_LAYER_LOAD_LATE) {
        z = textureLoad(depth_tex, sample_pixel, 0).r;
    }
    if (is_background(z)) {
        return l;
    }
    let o = estimator_occluder_at(p, s, l.px, z);
    l.value = o.value;
    l.trace = o.hidden;
    return l;
}
