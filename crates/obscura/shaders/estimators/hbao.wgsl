// HBAO: horizon-based AO (Bavoil, Sainz, Dimitrov 2008) as seed 001 §3.2 Algorithm 2 states it
// and seed 004 §2.2.1 Eqs. 3–5 derive it. Per pixel, D screen directions with a per-pixel rotation;
// along each, S steps r'/(S + 1) apart (r' the radius in pixels) from a jittered start. Every
// direction starts its horizon at the surface tangent's elevation plus an angle bias; a step whose
// surface lies above the current horizon and within R raises it and adds
//     W(|v|)·(sin φ − sin h),    W(r) = max(0, 1 − r/R)    (seed 004 Eq. 4 / Eq. 7),
// and AO = 1 − Σ/D (Algorithm 2, line 36), then the exponent (1 by default: the papers' AO).
//
// Elevations are measured from the plane ⟂ the view ray through the pixel (Algorithm 2's "XY
// plane" of view space, exact at the image centre and for orthographic views). The screen line a
// direction walks lies in the plane through the camera spanned by the view ray V and the screen
// direction, so that plane is the direction's slice; its tangent t_p is where the surface meets it.
//
// Estimator contract (docs/ARCHITECTURE.md), per-sample form: sample i belongs to direction
// i / steps, step i % steps. The accumulator carries the current direction's horizon, so samples
// must arrive direction by direction with ascending steps, which the single-pass schedule does;
// the table keeps HBAO off the two-phase schedules (Estimator::order_independent). A sample's value
// is (sin φ, W). A surface above the tangent plane but beyond R may hide a nearer one behind it
// (Algorithm 2, line 20); several depths for one sample keep the one with the largest
// W·(sin φ + 1), Algorithm 2's "maximum occlusion" (lines 24–32) judged against the lowest
// horizon because the running one is the accumulator's. With dual depth that is exact: the first
// layer reaches the combine only beyond R (W = 0), so the second is taken wherever it lies within
// R, and the accumulator compares it with the running horizon as Algorithm 2 does.
//
// Ours, where the papers are silent:
// - a surface on or below the shading point's tangent plane (within 1e-3 rad) occludes nothing.
//   Samples snap to pixel centres, off the direction's slice, where a tilted plane's elevation
//   differs from its tangent's in the slice: without the rule every tilted unoccluded plane
//   occluded itself by up to 0.12 (measured on tests/common/mod.rs's tilted floor);
// - the start jitter and the 1-pixel minimum first step of our
//   HBAO+ (the authors' HBAO+ placement, docs/AUTHORS_CODE.md §1.7), and the 4×4 Bayer
//   rotation/jitter pattern of every screen-space estimator here (src/estimators/mod.rs).

struct HbaoParams {
    radius: f32,
    inv_radius: f32,
    // cos and sin of the angle bias added to the tangent elevation.
    cos_bias: f32,
    sin_bias: f32,
    exponent: f32,
    directions: u32,
    steps: u32,
    _pad0: u32,
    // Index x % 4 + 4 * (y % 4): xy (cos, sin) of the direction rotation, z the start jitter.
    pattern: array<vec4<f32>, 16>,
    // Direction d: xy the unrotated unit direction 2π·d/D (view-space x right, y up).
    direction_table: array<vec4<f32>, 64>,
}

@group(GROUP_ESTIMATOR) @binding(ESTIMATOR_PARAMS) var<uniform> params: HbaoParams;

// directions × steps, and steps (constants: the per-sample division by STEPS is a multiplication).
override SAMPLE_COUNT: u32 = 32u;
override STEPS: u32 = 4u;

struct EstimatorPixel {
    pos: vec3<f32>,
    // Unit vector to the camera.
    v: vec3<f32>,
    normal: vec3<f32>,
    pixel: vec2<u32>,
    rotation: vec2<f32>,
    // Pixels between steps and the first step's distance; step_px 0 when the radius covers < 1 px.
    step_px: f32,
    start_px: f32,
    // 1/R, R capped on screen (screen_space.wgsl).
    inv_radius: f32,
    valid: bool,
}

struct EstimatorSample {
    px: vec2<f32>,
    direction: u32,
    // sin of the direction's starting horizon, tangent elevation + bias (at most π/2), on step 0;
    // later steps leave it at 1 (unread).
    sin_start: f32,
    on: bool,
}

// (sin φ, W(|v|)); W = 0 where nothing within R is there.
alias EstimatorValue = vec2<f32>;

struct EstimatorAccum {
    occlusion: f32,
    sin_horizon: f32,
    direction: u32,
    // The debug image only: the finished directions' horizon elevations, radians.
    horizons: f32,
}

struct Occluder {
    value: vec2<f32>,
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
    p.v = toward_camera(view, p.pos);
    p.normal = base.normal;
    let pattern = params.pattern[pattern_index(id)];
    p.rotation = pattern.xy;
    // Algorithm 2, line 4: r'/(N_s + 1).
    p.step_px = select(0.0, base.radius_px / f32(params.steps + 1u), base.radius_px >= 1.0);
    p.start_px = pattern.z * p.step_px + 1.0;
    p.inv_radius = params.inv_radius / base.radius_scale;
    return p;
}

// sin of the starting horizon of screen direction `dir` (view-space xy): the elevation of the
// tangent t_p in the direction's slice, plus the bias, at most π/2. The slice is spanned by V and
// the direction made orthogonal to it, D; t_p ∝ D·(n·V) − V·(n·D) lies in the surface, and its
// elevation has sin t = −n·D/|(n·V, n·D)|.
fn starting_horizon(p: EstimatorPixel, dir: vec2<f32>) -> f32 {
    let d = vec3<f32>(dir, 0.0);
    let slice_dir = normalize(d - p.v * dot(d, p.v));
    let n_v = dot(p.normal, p.v);
    let n_d = dot(p.normal, slice_dir);
    let sin_t = -n_d * inverseSqrt(max(n_v * n_v + n_d * n_d, 1e-12));
    let cos_t = sqrt(max(1.0 - sin_t * sin_t, 0.0));
    // sin(t + bias), or 1 where t + bias passes π/2 (cos(t + bias) < 0).
    let cos_start = cos_t * params.cos_bias - sin_t * params.sin_bias;
    return select(1.0, sin_t * params.cos_bias + cos_t * params.sin_bias, cos_start > 0.0);
}

fn estimator_sample(p: EstimatorPixel, i: u32) -> EstimatorSample {
    var s: EstimatorSample;
    s.on = p.step_px > 0.0;
    s.direction = i / STEPS;
    let step_index = i % STEPS;
    let step = f32(step_index);
    let dir = rotate_by(params.direction_table[s.direction].xy, p.rotation);
    // View y is up, framebuffer y down.
    s.px = vec2<f32>(p.pixel) + 0.5 + vec2<f32>(dir.x, -dir.y) * (p.start_px + step * p.step_px);
    // The direction's starting horizon: the accumulator reads it on a direction's first sample
    // only (every active sample reaches it, in order), so only step 0 pays for it.
    s.sin_start = 1.0;
    if (step_index == 0u) {
        s.sin_start = starting_horizon(p, dir);
    }
    return s;
}

fn estimator_unoccluded(p: EstimatorPixel, s: EstimatorSample) -> vec2<f32> {
    return vec2<f32>(-1.0, 0.0);
}

fn estimator_occluder(p: EstimatorPixel, s: EstimatorSample, pos: vec3<f32>) -> Occluder {
    let v = pos - p.pos;
    let distance = length(v);
    let sin_phi = dot(v, p.v) / max(distance, 1e-20);
    // A surface on or below the tangent plane occludes nothing (see the top comment).
    let above = dot(v, p.normal) > 1e-3 * distance;
    let w = select(0.0, max(1.0 - distance * p.inv_radius, 0.0), above);
    var o: Occluder;
    o.value = vec2<f32>(sin_phi, w);
    o.hidden = above && w <= 0.0;
    return o;
}

// Several depths for one sample: the one that occludes most against the lowest horizon, −π/2
// (the running horizon is the accumulator's, which then compares the pick with it).
fn estimator_combine(a: vec2<f32>, b: vec2<f32>) -> vec2<f32> {
    return select(a, b, b.y * (b.x + 1.0) > a.y * (a.x + 1.0));
}

// Missing-occlusion compensation (seed 001 §4; read.wgsl's SD_COMPENSATION): a stochastic
// sample's contribution W·(sin φ − sin h) counts `factor` times, so its weight W does; the
// horizon it raises is its own.
fn estimator_compensate(p: EstimatorPixel, s: EstimatorSample, value: vec2<f32>, factor: f32) -> vec2<f32> {
    return vec2<f32>(value.x, value.y * factor);
}

fn estimator_accum_init() -> EstimatorAccum {
    return EstimatorAccum(0.0, 1.0, 0xffffffffu, 0.0);
}

fn estimator_accum_sample(acc: EstimatorAccum, s: EstimatorSample) -> EstimatorAccum {
    return acc;
}

// Algorithm 2, lines 10 and 15–19: a new direction starts at its tangent horizon; a surface within
// R above the horizon raises it.
fn estimator_accum_value(acc: EstimatorAccum, s: EstimatorSample, value: vec2<f32>) -> EstimatorAccum {
    var a = acc;
    if (s.direction != a.direction) {
        if (ESTIMATOR_DEBUG && a.direction != 0xffffffffu) {
            a.horizons += asin(clamp(a.sin_horizon, -1.0, 1.0));
        }
        a.direction = s.direction;
        a.sin_horizon = s.sin_start;
    }
    if (value.y > 0.0 && value.x > a.sin_horizon) {
        a.occlusion += value.y * (value.x - a.sin_horizon);
        a.sin_horizon = value.x;
    }
    return a;
}

fn estimator_finish(p: EstimatorPixel, acc: EstimatorAccum) -> f32 {
    return pow(saturate(1.0 - acc.occlusion / f32(params.directions)), params.exponent);
}

// The debug image (`render --debug-out`): the mean final horizon elevation over the directions
// walked, −π/2 black … π/2 white (the tangent's elevation plus the bias where nothing rose above
// it).
fn estimator_debug(p: EstimatorPixel, acc: EstimatorAccum) -> f32 {
    if (acc.direction == 0xffffffffu) {
        return 0.5;
    }
    let mean = (acc.horizons + asin(clamp(acc.sin_horizon, -1.0, 1.0))) / f32(acc.direction + 1u);
    return saturate(mean / 3.141592653589793 + 0.5);
}
