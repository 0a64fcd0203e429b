// Scalable Ambient Obscurance (McGuire, Mara, Luebke, HPG 2012), the baseline of seed 004 §2.2.2:
// N taps on a spiral of τ turns around the pixel, tap i at α_i = (i + 0.5)/N of the screen radius
// r' and angle 2π·α_i·τ + φ (φ the pixel's rotation); each tap reads the depth pyramid level its
// distance calls for, m = ⌊log_K(α_i r' / q)⌋ clamped to the pyramid (q = 8 px: McGuire's
// LOG_MAX_OFFSET 3 with K = 2, taps within q texels of the pixel read its level), so distant taps
// read coarse, cache-friendly depths (§3). Every tap adds the Alchemy AO term with SAO's falloff,
//     (R² − v·v)³ · max(0, (v·n − β)/(v·v + ε)),    ε = (0.2 R)² (SAO's code: 0.01, in metres),
// and A = max(0, 1 − σR/R⁶ · (5/N) · Σ): the shipped normalisation intensity/R⁶ · (5/N), whose
// sum has the dimension of an inverse length, with its intensity (a length) written σR, σ
// dimensionless, so that the obscurance follows R; R capped on screen (screen_space.wgsl) scales
// all of R⁵ and ε alike (issue 62: with the intensity held, a capped R darkened as 1/R).
//
// Estimator contract (docs/ARCHITECTURE.md): a tap's value is its term, several depths combine by
// the maximum, the accumulator sums; order-independent. Level reads: sources/depth_pyramid.wgsl.
//
// Ours: the pyramid is the shared mean pyramid (seed 004 §3.3, K = 3 by default) rather than SAO's
// rotated-grid subsampling with K = 2; taps reading level l ≥ 1 see the K^l-pixel block's mean
// depth at the block's centre; the rotation φ is the 4×4 Bayer pattern's, not SAO's hash.

struct SaoParams {
    radius: f32,
    radius2: f32,
    // σ · 5 / (N R⁵), for the uncapped R.
    scale: f32,
    bias: f32,
    spiral_turns: f32,
    // 1 / ln K and ln q: the level of a tap at d px is ⌊(ln d − ln q) / ln K⌋.
    inv_log_factor: f32,
    log_q: f32,
    // ε against division by zero, (0.2 R)² for the uncapped R (src/estimators/sao.rs).
    epsilon: f32,
    // Index x % 4 + 4 * (y % 4): x the rotation φ in radians.
    pattern: array<vec4<f32>, 16>,
}

@group(GROUP_ESTIMATOR) @binding(ESTIMATOR_PARAMS) var<uniform> params: SaoParams;

// N taps, and the pyramid's levels (level 0 included).
override SAMPLE_COUNT: u32 = 11u;
override LEVELS: u32 = 5u;

struct EstimatorSample {
    px: vec2<f32>,
    level: u32,
    on: bool,
}

// The tap's term.
alias EstimatorValue = f32;

struct EstimatorAccum {
    sum: f32,
    // The debug image only: the levels the taps read, summed.
    levels: f32,
    _pad0: f32,
}

struct Occluder {
    value: f32,
    hidden: bool,
}

fn estimator_sample(p: EstimatorPixel, i: u32) -> EstimatorSample {
    var s: EstimatorSample;
    s.on = p.radius_px > 0.0;
    let tap = spiral_tap(i, SAMPLE_COUNT, params.spiral_turns, p.rotation, p.radius_px);
    let level = floor((log(max(tap.z, 1.0)) - params.log_q) * params.inv_log_factor);
    s.level = u32(clamp(level, 0.0, f32(LEVELS - 1u)));
    s.px = vec2<f32>(p.pixel) + 0.5 + tap.xy;
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
    let vv = dot(v, v);
    let f = max(p.radius2 - vv, 0.0);
    var o: Occluder;
    let epsilon = params.epsilon * p.radius_scale * p.radius_scale;
    o.value = f * f * f * max((dot(v, p.normal) - params.bias) / (epsilon + vv), 0.0);
    o.hidden = false;
    return o;
}

fn estimator_combine(a: f32, b: f32) -> f32 {
    return max(a, b);
}

fn estimator_accum_init() -> EstimatorAccum {
    return EstimatorAccum(0.0, 0.0, 0.0);
}

fn estimator_accum_sample(acc: EstimatorAccum, s: EstimatorSample) -> EstimatorAccum {
    return acc;
}

fn estimator_accum_value(acc: EstimatorAccum, s: EstimatorSample, value: f32) -> EstimatorAccum {
    var a = acc;
    a.sum += value;
    if (ESTIMATOR_DEBUG) {
        a.levels += f32(s.level);
    }
    return a;
}

fn estimator_finish(p: EstimatorPixel, acc: EstimatorAccum) -> f32 {
    // The normalisation is proportional to 1/R⁵ (src/estimators/sao.rs): (R² − v·v)³ scales as
    // R⁶ and the term as 1/R.
    let s2 = p.radius_scale * p.radius_scale;
    return max(0.0, 1.0 - acc.sum * (params.scale / (s2 * s2 * p.radius_scale)));
}

// The debug image (`render --debug-out`): the mean pyramid level the taps read, level 0 black …
// level L − 1 white.
fn estimator_debug(p: EstimatorPixel, acc: EstimatorAccum) -> f32 {
    return acc.levels / (f32(SAMPLE_COUNT) * f32(max(LEVELS - 1u, 1u)));
}
