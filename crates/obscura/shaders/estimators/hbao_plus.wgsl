// HBAO+ estimator: NVIDIA-style per-sample horizon AO, as the seed authors ran it for their
// baseline (seed 000 §2.1; their shader: docs/AUTHORS_CODE.md §1.7): D directions in
// screen space, S steps each, every sample occluding by
//     saturate(N·V/|V| − bias) · saturate(1 − |V|²/R²)
// (V from the shading point to the sample's surface), AO = saturate(1 − 2·mean)^exponent. Steps
// are (R_px)/(S + 1) pixels apart from a jittered start of at least one pixel; a pixel whose
// radius covers less than one pixel is unoccluded. Implements the estimator contract
// (docs/ARCHITECTURE.md): a sample's value is its occlusion, several depths for one sample combine
// by the maximum (seed 001 §3.2), and a depth can hide more when the sample lies in the positive
// hemisphere but beyond R (the authors' SD rule, docs/AUTHORS_CODE.md §1.7).
//
// Ours: the per-pixel direction rotation and start jitter come from the 4×4 Bayer matrix (rotation
// 2π·B/16/D, jitter from the transposed matrix) instead of the authors' 16 random vectors of the
// 4×4 interleaved slices; the bilateral blur's 4-pixel radius averages them alike. Interleaved
// rendering is not built yet; this is the single-pass, full-resolution HBAO+.

struct HbaoPlusParams {
    radius: f32,
    // -1 / R².
    neg_inv_r2: f32,
    bias: f32,
    exponent: f32,
    directions: u32,
    steps: u32,
    _pad0: u32,
    _pad1: u32,
    // Index x % 4 + 4 * (y % 4): xy (cos, sin) of the direction rotation, z the start jitter in
    // [0, 1).
    pattern: array<vec4<f32>, 16>,
    // Sample i = direction i / steps, step i % steps: xy the unrotated unit direction, z the step
    // (tabulated on the CPU: no trigonometry or integer division per sample).
    samples: array<vec4<f32>, 32>,
}

@group(GROUP_ESTIMATOR) @binding(ESTIMATOR_PARAMS) var<uniform> params: HbaoPlusParams;

// directions × steps, at most 32 (one bit per sample in the two-phase mask).
override SAMPLE_COUNT: u32 = 32u;
// Steps per direction (`steps`). With bent normals, sample i's direction is read from the table
// entry of its direction's first step, a constant index in the unrolled loop, so the bent
// tangent made of it alone is made once per direction (estimator_bent_sample). Without them each
// sample reads its own entry, which measured faster (BENCHMARKS.md).
override STEPS: u32 = 4u;

struct EstimatorPixel {
    pos: vec3<f32>,
    normal: vec3<f32>,
    // Framebuffer pixel of the shading point.
    pixel: vec2<u32>,
    rotation: vec2<f32>,
    // Pixels between steps, and the first step's distance; 0 when the radius covers < 1 px.
    step_px: f32,
    start_px: f32,
    // −1/R², R capped on screen (screen_space.wgsl).
    neg_inv_r2: f32,
    valid: bool,
}

struct EstimatorSample {
    px: vec2<f32>,
    // The unit screen direction (screen y down), rotated by the pixel's pattern.
    dir: vec2<f32>,
    on: bool,
}

// A sample's value: its occlusion.
alias EstimatorValue = f32;

struct EstimatorAccum {
    occlusion: f32,
    count: f32,
    _pad: f32,
}

struct Occluder {
    value: f32,
    hidden: bool,
}

fn estimator_pixel(id: vec2<u32>) -> EstimatorPixel {
    let base = screen_pixel(id, params.radius);
    var p: EstimatorPixel;
    p.pixel = base.pixel;
    p.valid = base.valid;
    if (!p.valid) {
        return p;
    }
    p.pos = base.pos;
    p.normal = base.normal;
    let pattern = params.pattern[pattern_index(id)];
    p.rotation = pattern.xy;
    p.step_px = select(0.0, base.radius_px / f32(params.steps + 1u), base.radius_px >= 1.0);
    p.start_px = pattern.z * p.step_px + 1.0;
    p.neg_inv_r2 = params.neg_inv_r2 / (base.radius_scale * base.radius_scale);
    return p;
}

fn estimator_sample(p: EstimatorPixel, i: u32) -> EstimatorSample {
    var s: EstimatorSample;
    s.on = p.step_px > 0.0;
    let k = params.samples[i];
    s.dir = rotate_by(select(k.xy, params.samples[i / STEPS * STEPS].xy, BENT_NORMALS), p.rotation);
    let distance = p.start_px + k.z * p.step_px;
    // Screen y runs down, view y up: the direction is a screen direction either way.
    s.px = vec2<f32>(p.pixel) + 0.5 + s.dir * distance;
    return s;
}

fn estimator_unoccluded(p: EstimatorPixel, s: EstimatorSample) -> f32 {
    return 0.0;
}

fn estimator_occluder(p: EstimatorPixel, s: EstimatorSample, pos: vec3<f32>) -> Occluder {
    let v = pos - p.pos;
    let v_dot_v = max(dot(v, v), 1e-20);
    let angle_term = saturate(dot(p.normal, v) * inverseSqrt(v_dot_v) - params.bias);
    let distance_term = saturate(v_dot_v * p.neg_inv_r2 + 1.0);
    var o: Occluder;
    o.value = angle_term * distance_term;
    // In the positive hemisphere but beyond R: a surface behind it could be within R.
    o.hidden = angle_term > 0.0 && distance_term <= 0.0;
    return o;
}

// Several depths for one sample: the largest occlusion (seed 001 §3.2).
fn estimator_combine(a: f32, b: f32) -> f32 {
    return max(a, b);
}

// Missing-occlusion compensation (seed 001 §4; read.wgsl's SD_COMPENSATION): a stochastic
// sample's occlusion counts `factor` times.
fn estimator_compensate(p: EstimatorPixel, s: EstimatorSample, value: f32, factor: f32) -> f32 {
    return value * factor;
}

fn estimator_accum_init() -> EstimatorAccum {
    return EstimatorAccum(0.0, 0.0, 0.0);
}

fn estimator_accum_sample(acc: EstimatorAccum, s: EstimatorSample) -> EstimatorAccum {
    var a = acc;
    a.count += 1.0;
    return a;
}

fn estimator_accum_value(acc: EstimatorAccum, s: EstimatorSample, value: f32) -> EstimatorAccum {
    var a = acc;
    a.occlusion += value;
    return a;
}

fn estimator_finish(p: EstimatorPixel, acc: EstimatorAccum) -> f32 {
    if (acc.count == 0.0) {
        return 1.0;
    }
    return pow(saturate(1.0 - 2.0 * acc.occlusion / acc.count), params.exponent);
}

// The debug image (`render --debug-out`): the mean per-sample occlusion, before 1 − 2·mean and
// the exponent.
fn estimator_debug(p: EstimatorPixel, acc: EstimatorAccum) -> f32 {
    return select(0.0, acc.occlusion / acc.count, acc.count > 0.0);
}

// Bent normals (`bent_normals`, seed 001 §4; the rule is ours): a sample's occlusion
// o = sin h − bias (attenuated) reads as the sine of the horizon elevation h it sees in its
// direction. The visible arc of that direction's half-slice runs from h to the normal. Its
// cosine-weighted mean direction lies at elevation m = (h + π/2)/2, with weight
// ∫_h^{π/2} sin θ dθ = cos h. With sin h = o and no trigonometry:
//     cos h · (cos m · t + sin m · n),  cos m = sqrt((1 − o)/2),  sin m = sqrt((1 + o)/2),
// where t is the sample's screen direction laid into the tangent plane. The schedule sums this
// over the samples' values and over their unoccluded values (o = 0: (t + n)/√2), and
// common/bent.wgsl forms the bent normal from the two sums. An open hemisphere gives the normal
// exactly; if every direction were blocked to the zenith on one side (o = 1 there), the normal
// would tilt by atan(2/π) away from that side, the cosine-weighted hemisphere's limit.
//
// The sums are kept in screen terms and laid into view space once per pixel
// (estimator_bent_normal): with P = I − n nᵀ the projection onto the tangent plane, a sample's
// t = P d / |P d| for its screen direction d (view z 0), so Σ w·t = P Σ (w / |P d|)·d. Per sample
// that leaves |P d|² = |d|² − (n·d)² (n is unit), one reciprocal root and a 2D sum; z carries
// the normal's weight. w / |P d| · d does not depend on |d|, so d is the sample's unit direction,
// the same for every step of a direction (STEPS), and only the weights are made per sample.
fn estimator_bent_sample(p: EstimatorPixel, s: EstimatorSample, value: f32) -> vec3<f32> {
    // Screen y runs down, view y up.
    let d = vec2<f32>(s.dir.x, -s.dir.y);
    let nd = dot(p.normal.xy, d);
    let len2 = dot(d, d) - nd * nd;
    let inv_len = select(0.0, inverseSqrt(len2), len2 > 1e-24);
    let o = saturate(value);
    // cos h · cos m = (1 − o)·sqrt((1 + o)/2) and cos h · sin m = (1 + o)·sqrt((1 − o)/2), as
    // cos h = sqrt((1 − o)(1 + o)): two square roots per sample instead of three.
    let along = (1.0 - o) * sqrt((1.0 + o) * 0.5) * inv_len;
    return vec3<f32>(along * d, (1.0 + o) * sqrt((1.0 - o) * 0.5));
}

// The bent normal from the samples' sums (common/bent.wgsl), view space.
fn estimator_bent_normal(
    p: EstimatorPixel,
    acc: EstimatorAccum,
    sample_visible: vec3<f32>,
    sample_open: vec3<f32>,
) -> vec3<f32> {
    return bent_from_sums(
        p.normal,
        bent_to_view(p.normal, sample_visible),
        bent_to_view(p.normal, sample_open),
    );
}

// A sum of estimator_bent_sample in view space: P (x, y, 0) + z·n.
fn bent_to_view(n: vec3<f32>, sum: vec3<f32>) -> vec3<f32> {
    let d = vec3<f32>(sum.xy, 0.0);
    return d - n * dot(n, d) + sum.z * n;
}
