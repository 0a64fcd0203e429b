// Pyramid HBAO (Astapov, Frolov, Galaktionov, GraphiCon 2021, seed 004 §3): D directions per
// pixel; along each, `steps` samples on every level of the depth pyramid (level 0 the depth buffer,
// level l the mean depth of K^l × K^l pixels; sources/depth_pyramid.wgsl), the step size growing
// by K from one level to the next, so the reach grows as K^L while the samples grow as L (§3.2).
// Instead of a horizon, a direction's occlusion is the largest weighted contribution of its samples
// (§3.4, Eq. 8) with the linear attenuation of Eq. 7:
//     A(θ) = max_samples W(r)·sin α,    W(r) = max(0, 1 − r/R),
// α the sample's elevation above the tangent plane (sin α = n·v/|v|), and AO = 1 − mean_θ A(θ),
// then the exponent (1 by default).
//
// Estimator contract (docs/ARCHITECTURE.md), per-sample form: sample i is direction
// i / (levels·steps), level (i / steps) % levels, step i % steps, read from that level
// (estimator_sample_level). The accumulator holds the current direction's maximum and the sum of
// the finished ones, so samples arrive direction by direction (single-pass schedule only, as HBAO).
//
// Ours, where the paper is silent or our setting differs:
// - level 0 steps 1 px apart, level l K^l px, level l starting where level l − 1 ends; the paper
//   fixes the steps per level but not the first step;
// - §3.5's "random" directions and per-direction start offsets: direction d at angle
//   2π(d + u_d)/D and start offset o_d, with u_d, o_d from the pixel's 4×4 Bayer values advanced
//   per direction by the golden-ratio sequences (0.618…, 0.754…): deterministic, and the 4-px
//   bilateral blur averages them as it does every screen-space estimator's pattern;
// - a surface on or below the tangent plane (within 1e-3 rad) adds nothing, as sin α ≤ 0 would.

struct PyramidHbaoParams {
    radius: f32,
    inv_radius: f32,
    exponent: f32,
    factor: f32,
    directions: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
    // Index x % 4 + 4 * (y % 4): x the direction offset u in [0, 1), y the start offset o.
    pattern: array<vec4<f32>, 16>,
}

@group(GROUP_ESTIMATOR) @binding(ESTIMATOR_PARAMS) var<uniform> params: PyramidHbaoParams;

// directions × levels × steps, levels and steps (per level).
override SAMPLE_COUNT: u32 = 160u;
override LEVELS: u32 = 5u;
override STEPS: u32 = 4u;

struct EstimatorPixel {
    pos: vec3<f32>,
    normal: vec3<f32>,
    pixel: vec2<u32>,
    offsets: vec2<f32>,
    // 1/R, R capped on screen (screen_space.wgsl; the pyramid's steps are fixed in pixels).
    inv_radius: f32,
    valid: bool,
}

struct EstimatorSample {
    px: vec2<f32>,
    direction: u32,
    level: u32,
    on: bool,
}

// W(r)·sin α, 0 where nothing occludes.
alias EstimatorValue = f32;

struct EstimatorAccum {
    sum: f32,
    current: f32,
    direction: u32,
    // The debug image only: the level of the current direction's largest contribution, and those
    // of the finished directions summed.
    current_level: f32,
    levels: f32,
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
    p.offsets = params.pattern[pattern_index(id)].xy;
    p.inv_radius = params.inv_radius / base.radius_scale;
    return p;
}

fn estimator_sample(p: EstimatorPixel, i: u32) -> EstimatorSample {
    var s: EstimatorSample;
    s.on = true;
    s.direction = i / (LEVELS * STEPS);
    s.level = (i / STEPS) % LEVELS;
    let step = f32(i % STEPS);
    let d = f32(s.direction);
    let u = fract(p.offsets.x + 0.6180339887 * d);
    let o = fract(p.offsets.y + 0.7548776662 * d);
    let angle = 6.283185307179586 * (d + u) / f32(params.directions);
    // Level l: steps K^l px apart from S·(K^l − 1)/(K − 1) px on.
    let size = pow(params.factor, f32(s.level));
    let start = f32(STEPS) * (size - 1.0) / (params.factor - 1.0);
    let distance = max(start + (step + o) * size, 1.0);
    // View y is up, framebuffer y down.
    s.px = vec2<f32>(p.pixel) + 0.5 + vec2<f32>(cos(angle), -sin(angle)) * distance;
    return s;
}

fn estimator_sample_level(s: EstimatorSample) -> u32 {
    return s.level;
}

fn estimator_unoccluded(p: EstimatorPixel, s: EstimatorSample) -> f32 {
    return 0.0;
}

fn estimator_occluder(p: EstimatorPixel, s: EstimatorSample, pos: vec3<f32>) -> Occluder {
    let v = pos - p.pos;
    let distance = length(v);
    let sin_alpha = dot(v, p.normal) / max(distance, 1e-20);
    var o: Occluder;
    o.value = select(0.0, max(1.0 - distance * p.inv_radius, 0.0) * sin_alpha, sin_alpha > 1e-3);
    o.hidden = false;
    return o;
}

fn estimator_combine(a: f32, b: f32) -> f32 {
    return max(a, b);
}

fn estimator_accum_init() -> EstimatorAccum {
    return EstimatorAccum(0.0, 0.0, 0u, 0.0, 0.0);
}

fn estimator_accum_sample(acc: EstimatorAccum, s: EstimatorSample) -> EstimatorAccum {
    return acc;
}

// Eq. 8: a direction's largest contribution; a new direction adds the last one's to the sum.
fn estimator_accum_value(acc: EstimatorAccum, s: EstimatorSample, value: f32) -> EstimatorAccum {
    var a = acc;
    if (s.direction != a.direction) {
        a.sum += a.current;
        a.current = 0.0;
        a.direction = s.direction;
        if (ESTIMATOR_DEBUG) {
            a.levels += a.current_level;
            a.current_level = 0.0;
        }
    }
    if (ESTIMATOR_DEBUG && value > a.current) {
        a.current_level = f32(s.level);
    }
    a.current = max(a.current, value);
    return a;
}

fn estimator_finish(p: EstimatorPixel, acc: EstimatorAccum) -> f32 {
    let occlusion = (acc.sum + acc.current) / f32(params.directions);
    return pow(saturate(1.0 - occlusion), params.exponent);
}

// The debug image (`render --debug-out`): the mean level of each direction's largest
// contribution (level 0 where nothing occludes), level 0 black … level L − 1 white.
fn estimator_debug(p: EstimatorPixel, acc: EstimatorAccum) -> f32 {
    let levels = acc.levels + acc.current_level;
    return levels / (f32(params.directions) * f32(max(LEVELS - 1u, 1u)));
}
