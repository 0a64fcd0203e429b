// GTAO: ground-truth-based AO (Jimenez, Wu, Pesce, Jarabo, "Practical Real-Time Strategies for
// Accurate Indirect Occlusion", 2016), the baseline seed 003 modifies. Per pixel, `slices` planes
// through the view vector V; in each, `steps` samples on either side find the two horizon angles
// h₀ ≤ 0 ≤ h₁ (measured from V), clamped to the hemisphere around the normal projected onto the
// slice (angle γ, length |n_p|); the cosine-weighted visibility of the slice is then analytic:
//     â = |n_p| · Σ_{h ∈ {h₀, h₁}} ¼ (−cos(2h − γ) + cos γ + 2h sin γ)    (slice_visibility.wgsl).
// Distance falloff as XeGTAO (Intel, 2021): samples reach 1.457·R (its radius multiplier) and a
// sample's horizon cosine is blended towards the side's lowest horizon by the weight
// w = saturate((1.457·R − d)/(0.615·1.457·R)): full weight up to 0.56·R, none beyond 1.457·R.
// Thickness heuristic (Jimenez et al. §4): walking a side outwards, a sample below the current
// horizon pulls it down, h ← max(h_s, mix(h, h_s, β)); β = 0 (the default, XeGTAO's) keeps the
// plain maximum, larger β lets light pass behind thin occluders.
//
// Estimator contract (docs/ARCHITECTURE.md), per-sample form: sample i is slice i / (2·steps),
// side + then −, step i % steps outwards. The accumulator holds only the current slice's two
// horizons and folds a slice into the running sums when the next begins, so samples must arrive
// slice by slice with ascending steps: the single-pass schedule does, and the table keeps GTAO off
// the two-phase schedules (Estimator::order_independent). A sample's value is (cos h_s, w).
//
// Ours, where the papers leave it open:
// - AO = Σ â / Σ â_open, with â_open a slice's visibility with its horizons on the tangent plane,
//   instead of Σ â / slices. Both have the same limit (the mean of â_open over slice angles is 1),
//   but ours is exactly 1 on every unoccluded plane, as VAO's clipped normalisation;
// - step distances ((step + jitter)/steps)²·r' + 1.3 px (XeGTAO's quadratic distribution and its
//   minimum offset), with the per-pixel slice rotation and jitter of the 4×4 Bayer pattern;
// - a surface on or below the shading point's tangent plane (within 1e-3 rad) occludes nothing:
//   samples snap to pixel centres, off the slice, where a tilted plane lies above the slice's
//   lowest horizon (the same rule as gtao_vb.wgsl);
// - exponent 1 by default (XeGTAO ships 2.2 as an artistic power; the ground truth has none).

struct GtaoParams {
    // The reach, 1.457·R.
    radius: f32,
    // w = saturate(d · falloff_mul + falloff_add).
    falloff_mul: f32,
    falloff_add: f32,
    thickness_blend: f32,
    exponent: f32,
    slices: u32,
    steps: u32,
    _pad0: u32,
    // Index x % 4 + 4 * (y % 4): xy (cos, sin) of the slice rotation, z the step jitter in [0, 1).
    pattern: array<vec4<f32>, 16>,
    // Slice j: xy the unrotated slice direction at angle π·j/slices (view-space x right, y up).
    slice_table: array<vec4<f32>, 16>,
}

@group(GROUP_ESTIMATOR) @binding(ESTIMATOR_PARAMS) var<uniform> params: GtaoParams;

// slices × 2 × steps, and steps (constants: the per-sample divisions are multiplications).
override SAMPLE_COUNT: u32 = 8u;
override STEPS: u32 = 2u;

const HALF_PI: f32 = 1.5707963267948966;

struct EstimatorPixel {
    pos: vec3<f32>,
    // Unit vector to the camera.
    v: vec3<f32>,
    normal: vec3<f32>,
    pixel: vec2<u32>,
    rotation: vec2<f32>,
    jitter: f32,
    radius_px: f32,
    // XeGTAO's minimum offset, 1.3 px, as a fraction of the radius.
    min_fraction: f32,
    // The falloff's slope per world unit, for R capped on screen (screen_space.wgsl).
    falloff_mul: f32,
    valid: bool,
}

struct EstimatorSample {
    px: vec2<f32>,
    slice: u32,
    // 0: side +, towards the slice direction; 1: side −.
    side: u32,
    // The projected normal in the slice, on the slice's first sample: its angle γ from V and its
    // length (0 on later samples, unread).
    gamma: f32,
    projected_length: f32,
    // Bent normals only: the slice plane's tangent (⟂ V, towards side +) and (sin γ, cos γ), on
    // the slice's first sample.
    tangent: vec3<f32>,
    gamma_sc: vec2<f32>,
    on: bool,
}

// (cos of the sample's angle from V, falloff weight w); w = 0 where nothing is there.
alias EstimatorValue = vec2<f32>;

struct EstimatorAccum {
    // The slice being walked (0xffffffff before the first) and its horizon cosines, side + and −.
    slice: u32,
    horizon_cos: vec2<f32>,
    gamma: f32,
    projected_length: f32,
    visible: f32,
    open: f32,
    // The debug image only: the finished slices' angles between their horizons, radians.
    angles: f32,
    // Bent normals only (BENT_NORMALS): the current slice's tangent and (sin γ, cos γ), and the
    // finished slices' visible and open bent vectors (slice_visibility.wgsl), tangent parts as
    // view-space vectors and V parts as scalars (V is the pixel's, the same in every slice).
    tangent: vec3<f32>,
    gamma_sc: vec2<f32>,
    bent_tangent: vec3<f32>,
    bent_v: f32,
    open_tangent: vec3<f32>,
    open_v: f32,
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
    p.jitter = pattern.z;
    p.radius_px = select(0.0, base.radius_px, base.radius_px >= 1.0);
    p.min_fraction = 1.3 / max(base.radius_px, 1.0);
    p.falloff_mul = params.falloff_mul / base.radius_scale;
    return p;
}

fn estimator_sample(p: EstimatorPixel, i: u32) -> EstimatorSample {
    var s: EstimatorSample;
    s.on = p.radius_px > 0.0;
    s.slice = i / (2u * STEPS);
    s.side = (i / STEPS) % 2u;
    let step = f32(i % STEPS);
    let dir = rotate_by(params.slice_table[s.slice].xy, p.rotation);
    let fraction = (step + p.jitter) / f32(STEPS);
    let distance = (fraction * fraction + p.min_fraction) * p.radius_px;
    let sign = select(1.0, -1.0, s.side == 1u);
    // View y is up, framebuffer y down.
    s.px = vec2<f32>(p.pixel) + 0.5 + sign * vec2<f32>(dir.x, -dir.y) * distance;
    // The slice's projected normal: the accumulator reads it on a slice's first sample only
    // (every active sample reaches it, in order), so only that sample pays for it.
    s.gamma = 0.0;
    s.projected_length = 0.0;
    if (i % (2u * STEPS) == 0u) {
        // The slice plane: V and the slice direction made orthogonal to V (its tangent).
        let d = vec3<f32>(dir, 0.0);
        let tangent = normalize(d - p.v * dot(d, p.v));
        let axis = cross(tangent, p.v);
        let projected = p.normal - axis * dot(p.normal, axis);
        s.projected_length = length(projected);
        s.gamma = atan2(dot(projected, tangent), dot(projected, p.v));
        if (BENT_NORMALS) {
            s.tangent = tangent;
            s.gamma_sc = vec2<f32>(dot(projected, tangent), dot(projected, p.v))
                * (1.0 / max(s.projected_length, 1e-20));
        }
    }
    return s;
}

fn estimator_unoccluded(p: EstimatorPixel, s: EstimatorSample) -> vec2<f32> {
    return vec2<f32>(-1.0, 0.0);
}

fn estimator_occluder(p: EstimatorPixel, s: EstimatorSample, pos: vec3<f32>) -> Occluder {
    let delta = pos - p.pos;
    let distance = length(delta);
    // A surface on or below the tangent plane occludes nothing (see the top comment).
    let above = dot(delta, p.normal) > 1e-3 * distance;
    var o: Occluder;
    o.value = vec2<f32>(
        dot(delta, p.v) / max(distance, 1e-20),
        select(0.0, saturate(distance * p.falloff_mul + params.falloff_add), above),
    );
    // GTAO has no hidden-depth rows (table): nothing deeper is consulted.
    o.hidden = false;
    return o;
}

// Several depths for one sample: the higher weighted horizon.
fn estimator_combine(a: vec2<f32>, b: vec2<f32>) -> vec2<f32> {
    return select(a, b, b.y * (b.x + 1.0) > a.y * (a.x + 1.0));
}

// Missing-occlusion compensation (seed 001 §4; read.wgsl's SD_COMPENSATION), for a GTAO over a
// stochastic source (no row has one yet): the sample's falloff weight, which pulls the horizon up
// from the tangent, counts `factor` times (at most 1).
fn estimator_compensate(p: EstimatorPixel, s: EstimatorSample, value: vec2<f32>, factor: f32) -> vec2<f32> {
    return vec2<f32>(value.x, min(value.y * factor, 1.0));
}

// Side horizon cosines at the tangent plane: cos(γ + π/2) = −sin γ and cos(γ − π/2) = sin γ.
fn lowest_horizon_cos(gamma: f32) -> vec2<f32> {
    let s = sin(gamma);
    return vec2<f32>(-s, s);
}

// Adds the finished slice of `acc` (if any) to its sums.
fn fold_slice(acc: EstimatorAccum) -> EstimatorAccum {
    var a = acc;
    if (a.slice == 0xffffffffu) {
        return a;
    }
    let g = a.gamma;
    let h1 = g + min(acos(clamp(a.horizon_cos.x, -1.0, 1.0)) - g, HALF_PI);
    let h0 = g + max(-acos(clamp(a.horizon_cos.y, -1.0, 1.0)) - g, -HALF_PI);
    a.visible += a.projected_length * (side_visibility(h0, g) + side_visibility(h1, g));
    if (ESTIMATOR_DEBUG) {
        a.angles += h1 - h0;
    }
    a.open += a.projected_length * open_slice_visibility(g);
    if (BENT_NORMALS) {
        // The horizons as (sin, cos) without trigonometry: from their cosines (h₁ ≥ 0 ≥ h₀), or
        // the hemisphere's edges where clamped (cos h₁ < cos(γ + π/2) = −sin γ; cos h₀ < sin γ).
        let sg = a.gamma_sc;
        let edges = hemisphere_edges(sg);
        let c1 = clamp(a.horizon_cos.x, -1.0, 1.0);
        let c0 = clamp(a.horizon_cos.y, -1.0, 1.0);
        let sc1 = select(vec2<f32>(sqrt(1.0 - c1 * c1), c1), edges[1], c1 < -sg.x);
        let sc0 = select(vec2<f32>(-sqrt(1.0 - c0 * c0), c0), edges[0], c0 < sg.x);
        let visible = a.projected_length * span_bent(sc0, sc1, sg);
        let open = a.projected_length * open_slice_bent(sg);
        a.bent_tangent += visible.x * a.tangent;
        a.bent_v += visible.y;
        a.open_tangent += open.x * a.tangent;
        a.open_v += open.y;
    }
    return a;
}

fn estimator_accum_init() -> EstimatorAccum {
    var a: EstimatorAccum;
    a.slice = 0xffffffffu;
    a.horizon_cos = vec2<f32>(-1.0);
    a.gamma = 0.0;
    a.projected_length = 0.0;
    a.visible = 0.0;
    a.open = 0.0;
    a.angles = 0.0;
    a.tangent = vec3<f32>(0.0);
    a.gamma_sc = vec2<f32>(0.0, 1.0);
    a.bent_tangent = vec3<f32>(0.0);
    a.bent_v = 0.0;
    a.open_tangent = vec3<f32>(0.0);
    a.open_v = 0.0;
    return a;
}

fn estimator_accum_sample(acc: EstimatorAccum, s: EstimatorSample) -> EstimatorAccum {
    return acc;
}

fn estimator_accum_value(acc: EstimatorAccum, s: EstimatorSample, value: vec2<f32>) -> EstimatorAccum {
    var a = acc;
    if (s.slice != a.slice) {
        a = fold_slice(a);
        a.slice = s.slice;
        a.gamma = s.gamma;
        a.projected_length = s.projected_length;
        a.tangent = s.tangent;
        a.gamma_sc = s.gamma_sc;
        a.horizon_cos = lowest_horizon_cos(s.gamma);
    }
    // Recomputed per sample: keeping it in the accumulator measured 1 % slower (BENCHMARKS.md).
    let lowest = lowest_horizon_cos(a.gamma)[s.side];
    let sample_cos = mix(lowest, value.x, value.y);
    let current = a.horizon_cos[s.side];
    a.horizon_cos[s.side] = max(sample_cos, mix(current, sample_cos, params.thickness_blend));
    return a;
}

fn estimator_finish(p: EstimatorPixel, acc: EstimatorAccum) -> f32 {
    let a = fold_slice(acc);
    if (a.open <= 0.0) {
        return 1.0;
    }
    return pow(saturate(a.visible / a.open), params.exponent);
}

// The debug image (`render --debug-out`): the mean angle between each slice's two horizons,
// 0 black … π (an open slice) white.
fn estimator_debug(p: EstimatorPixel, acc: EstimatorAccum) -> f32 {
    let a = fold_slice(acc);
    if (a.slice == 0xffffffffu) {
        return 1.0;
    }
    return saturate(a.angles / (3.141592653589793 * f32(a.slice + 1u)));
}

// The bent normal (`bent_normals`, seed 001 §4): the cosine-weighted mean visible direction over
// the slices (common/bent.wgsl's bent_from_sums), view space.

fn estimator_bent_normal(
    p: EstimatorPixel,
    acc: EstimatorAccum,
    sample_visible: vec3<f32>,
    sample_open: vec3<f32>,
) -> vec3<f32> {
    let a = fold_slice(acc);
    return bent_from_sums(
        p.normal,
        a.bent_tangent + a.bent_v * p.v,
        a.open_tangent + a.open_v * p.v,
    );
}
