// SSAO as seed 001 §3.2 extends it: Alchemy AO (McGuire, Osman, Bukowski, Hennessy, HPG 2011),
// the estimator SAO later scaled. N samples around the pixel within the world radius R; each
// within R adds max(0, v·n + z·β)/(v·v + ε) (v from the shading point to the sample's surface, z
// the shading point's depth, β a depth-scaled bias, ε against division by zero), and
//     A = max(0, 1 − (2σ·u/N) Σ)^k
// (the paper's Eq. 10; σ the intensity, k the contrast, 1 by default; u = 0.1 R, the length of
// Alchemy's falloff u·t/max(u, t)², written out here so that σ is dimensionless and the result
// does not change with the scene's units: ours, the paper folds it into σ). Seed 001 Tab. 1 runs
// it with 32 samples.
//
// Estimator contract (docs/ARCHITECTURE.md): a sample's value is its term; several depths combine
// by the maximum (seed 001 §3.3: "we do not access the stochastic samples if the regular depth
// map sample already represents an occluder" — a surface in front within R already occludes; a
// surface beyond R, or below the tangent plane, may hide one that occludes); the accumulator
// sums, so the order of samples never matters (two-phase schedules run it too).
//
// Ours, where the paper leaves it to the implementation: the samples lie on SAO's spiral (7
// turns, tap i at (i + 0.5)/N of the radius) turned by the pixel's 4×4 Bayer rotation, rather
// than the paper's per-pixel random disc. β = 10⁻⁴ is the paper's value; ε = (0.02 R)², the
// paper's 10⁻⁴ at our default R = 0.5, proportional to R² so that the units do not matter.

// `stochastic_depth.query = "first-layer"`: read the map wherever the first surface does not
// occlude, as seed 001 §3.3 words it, without the exact test below that skips samples no deeper
// surface can change (same image, more reads).
override SSAO_LITERAL_QUERY: bool = false;

struct SsaoParams {
    radius: f32,
    radius2: f32,
    // 2σ·u/N.
    scale: f32,
    bias: f32,
    contrast: f32,
    epsilon: f32,
    spiral_turns: f32,
    _pad0: f32,
    // Index x % 4 + 4 * (y % 4): x the rotation in radians.
    pattern: array<vec4<f32>, 16>,
}

@group(GROUP_ESTIMATOR) @binding(ESTIMATOR_PARAMS) var<uniform> params: SsaoParams;

// N, at most 32 (one bit per sample in the two-phase mask).
override SAMPLE_COUNT: u32 = 32u;

struct EstimatorSample {
    px: vec2<f32>,
    on: bool,
}

// The sample's term.
alias EstimatorValue = f32;

struct EstimatorAccum {
    sum: f32,
    // The debug image only: the samples that occlude.
    occluding: f32,
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
    s.px = vec2<f32>(p.pixel) + 0.5 + tap.xy;
    return s;
}

fn estimator_unoccluded(p: EstimatorPixel, s: EstimatorSample) -> f32 {
    return 0.0;
}

fn estimator_occluder(p: EstimatorPixel, s: EstimatorSample, pos: vec3<f32>) -> Occluder {
    let v = pos - p.pos;
    let vv = dot(v, v);
    // View-space z is negative in front of the camera: z·β lowers the term by depth·β.
    let term = max(dot(v, p.normal) + p.pos.z * params.bias, 0.0) / (vv + params.epsilon);
    var o: Occluder;
    o.value = select(0.0, term, vv < p.radius2);
    // Beyond R or below the tangent plane: a deeper surface may still occlude (seed 001 §3.3).
    o.hidden = o.value <= 0.0;
    if (o.hidden && !SSAO_LITERAL_QUERY) {
        // Ours, exact: every deeper surface at this pixel lies on the camera ray through `pos`,
        // at pos + t·r (t > 0, r the ray's direction). Its v·n + z·β changes by t·(r·n), so it
        // can rise above 0 only if it already is or if r·n > 0; and its distance to the shading
        // point can fall within R only if the ray's closest approach does. Where neither can
        // happen no deeper surface occludes, and the map is not read: the image is the same
        // (`stochastic_depth.query = "first-layer"` reads it anyway, to show that).
        let r = -toward_camera(view, pos);
        let along = dot(v, r);
        let closest2 = select(vv, vv - along * along, along < 0.0);
        let can_rise = dot(v, p.normal) + p.pos.z * params.bias > 0.0 || dot(r, p.normal) > 0.0;
        o.hidden = closest2 < p.radius2 && can_rise;
    }
    return o;
}

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
    return acc;
}

fn estimator_accum_value(acc: EstimatorAccum, s: EstimatorSample, value: f32) -> EstimatorAccum {
    var a = acc;
    a.sum += value;
    if (ESTIMATOR_DEBUG && value > 0.0) {
        a.occluding += 1.0;
    }
    return a;
}

fn estimator_finish(p: EstimatorPixel, acc: EstimatorAccum) -> f32 {
    // The normalisation is proportional to R (src/estimators/ssao.rs).
    return pow(max(1.0 - params.scale * p.radius_scale * acc.sum, 0.0), params.contrast);
}

// The debug image (`render --debug-out`): the fraction of the samples that occlude, none black
// … all white.
fn estimator_debug(p: EstimatorPixel, acc: EstimatorAccum) -> f32 {
    return acc.occluding / f32(SAMPLE_COUNT);
}
