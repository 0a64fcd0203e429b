// GTAO with visibility bitmasks (Therrien, Levesque, Gilet, "Screen Space Indirect Lighting with
// Visibility Bitmask", seed 003): per slice through the view vector, a 32-sector bit field over the
// hemisphere around the normal projected onto the slice replaces GTAO's two horizon angles. Every
// sample marks the sectors between its front face and its back face, the front pushed away from
// the camera by a constant thickness, so light passes behind thin surfaces; no falloff. AO = the
// mean over slices of 1 − occluded sectors / 32 (uniform sectors; seed 003 leaves out the cosine
// weight too).
//
// Per-sample form of the estimator contract (docs/ARCHITECTURE.md): sample i belongs to slice
// i / (2·steps), side ±1 and step i % steps; its value is its slice's sector bits (`u32`), values
// of several depths combine by OR (every stochastic-depth sample marks its own span), and the
// accumulator ORs each sample into its slice's mask, one 32-bit word per slice (so at most three
// slices: the two-phase schedule carries three words). The order of samples never matters, as
// the two-phase schedule needs.
//
// Ours, where seed 003 (a blog post on Unity's GTAO) is silent or engine-specific:
// - angles are measured with atan2 in the slice plane (basis V and the slice direction made
//   orthogonal to V), both sides alike, instead of GTAO's acos with a side-dependent sign;
// - a sample whose front face lies on or below the shading point's tangent plane (within 1e-3 rad)
//   marks nothing: geometrically its span lies below the hemisphere, and without the rule float
//   rounding and the half-float normals made every unoccluded plane occlude itself a little;
// - the per-pixel slice rotation and step jitter come from the 4×4 Bayer matrix (as our HBAO+);
// - optionally (`gtao_vb.cosine_weighted`) every free sector weighs its share of the slice's
//   cosine-weighted visibility, GTAO's analytic integral over the sector's angles, with AO the
//   free weight over the whole hemisphere's, summed over slices (as our GTAO normalises): the
//   cosine-weighted ambient occlusion of the ground truth rather than seed 003's uniform count.

struct GtaoVbParams {
    radius: f32,
    thickness: f32,
    exponent: f32,
    // 0 ceil, 1 round, 2 floor (seed 003: touch, half, whole sector).
    activation: u32,
    // As set; the shader reads the constants SLICES and STEPS instead (unrolled loops).
    slices: u32,
    steps: u32,
    _pad0: u32,
    _pad1: u32,
    // Index x % 4 + 4 * (y % 4): xy (cos, sin) of the slice rotation, z the step jitter in [0, 1).
    pattern: array<vec4<f32>, 16>,
    // Sample i: xy the unrotated slice direction (view space), z the side (±1), w the step.
    samples: array<vec4<f32>, 32>,
}

@group(GROUP_ESTIMATOR) @binding(ESTIMATOR_PARAMS) var<uniform> params: GtaoVbParams;

// slices × 2 × steps, at most 32.
override SAMPLE_COUNT: u32 = 8u;
// Steps per slice side (`steps`): with the sample loop unrolled, a sample's slice i / (2 STEPS) is
// a constant, so its slice's state is read without a choice among the slices, and its direction
// from the table entry of the slice's first sample, made once per slice.
override STEPS: u32 = 2u;
// Slices (`slices`; SAMPLE_COUNT = slices × 2 × STEPS): a constant, so the per-slice loops over the
// pixel's and the accumulator's arrays unroll and those arrays stay in registers. With the
// uniform `params.slices` as their bound they were indexed at run time (`gtao-vb` 18 % slower
// at its defaults on an H100, BENCHMARKS.md).
override SLICES: u32 = SAMPLE_COUNT / (2u * STEPS);
// Weigh free sectors by the cosine to the normal (`gtao_vb.cosine_weighted`, ours): a constant, so
// that seed 003's uniform count compiles without it.
override COSINE_WEIGHTED: bool = false;
// Skip hidden-depth reads no deeper surface can change (estimator_occluder; the default query,
// "needed"). Off for `stochastic_depth.query = "first-layer"` (seed 001 §3.3 as worded, to
// measure the test) and with `compensation` ≠ 1, whose widened runs can reach sectors the test
// counts as covered.
override EXACT_QUERY: bool = true;

struct EstimatorPixel {
    pos: vec3<f32>,
    // Unit vector to the camera.
    v: vec3<f32>,
    normal: vec3<f32>,
    pixel: vec2<u32>,
    rotation: vec2<f32>,
    jitter: f32,
    step_px: f32,
    // Per slice (made once per pixel, shared by its 2 × steps samples): the slice plane's tangent
    // (⟂ V, towards the slice direction) and the projected normal's angle from V towards it.
    tangents: array<vec3<f32>, 3>,
    normal_angles: array<f32, 3>,
    // The projected normal's length (cosine-weighted sectors only).
    projected_lengths: array<f32, 3>,
    valid: bool,
}

struct EstimatorSample {
    px: vec2<f32>,
    slice: u32,
    on: bool,
}

// A sample's value: the sectors of its slice it occludes.
alias EstimatorValue = u32;

struct EstimatorAccum {
    masks: array<u32, 3>,
}

struct Occluder {
    value: u32,
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
    p.step_px = select(0.0, base.radius_px / f32(STEPS), base.radius_px >= 1.0);
    for (var j = 0u; j < SLICES; j++) {
        let k = params.samples[j * 2u * STEPS];
        let d = vec3<f32>(rotate_by(k.xy, p.rotation), 0.0);
        let tangent = normalize(d - p.v * dot(d, p.v));
        let slice_normal = cross(tangent, p.v);
        let projected = p.normal - slice_normal * dot(p.normal, slice_normal);
        p.tangents[j] = tangent;
        p.normal_angles[j] = slice_angle(dot(projected, tangent), dot(projected, p.v));
        if (COSINE_WEIGHTED) {
            p.projected_lengths[j] = length(projected);
        }
    }
    return p;
}

fn estimator_sample(p: EstimatorPixel, i: u32) -> EstimatorSample {
    var s: EstimatorSample;
    s.on = p.step_px > 0.0;
    let k = params.samples[i];
    s.slice = i / (2u * STEPS);
    let dir = rotate_by(params.samples[s.slice * 2u * STEPS].xy, p.rotation);
    // View y is up, framebuffer y down.
    s.px = vec2<f32>(p.pixel) + 0.5 + k.z * vec2<f32>(dir.x, -dir.y) * ((p.jitter + 1.0 + k.w) * p.step_px);
    return s;
}

fn estimator_unoccluded(p: EstimatorPixel, s: EstimatorSample) -> u32 {
    return 0u;
}

// Slice j's tangent and projected normal angle. Selects over the three slices keep the arrays in
// registers where an index into them may not; with the slice a constant (STEPS) they fold away.
fn slice_tangent(p: EstimatorPixel, j: u32) -> vec3<f32> {
    return select(select(p.tangents[0], p.tangents[1], j == 1u), p.tangents[2], j == 2u);
}

fn slice_normal_angle(p: EstimatorPixel, j: u32) -> f32 {
    return select(select(p.normal_angles[0], p.normal_angles[1], j == 1u), p.normal_angles[2], j == 2u);
}

// atan2(y, x) within 1.2e-5 rad: Abramowitz and Stegun 4.4.49's polynomial for atan on [0, 1]
// (|error| ≤ 1e-5) after folding the other octants onto it. Why not the built-in: every sample
// takes two (its front and back face), and the angle only picks one of 32 sectors (π/32 rad
// each), so 1.2e-5 rad moves a sector edge by 4e-4 of a sector.
fn slice_angle(y: f32, x: f32) -> f32 {
    let ax = abs(x);
    let ay = abs(y);
    let t = min(ax, ay) / max(max(ax, ay), 1e-30);
    let t2 = t * t;
    var a = t * (0.9998660 + t2 * (-0.3302995 + t2 * (0.1801410 + t2 * (-0.0851330 + t2 * 0.0208351))));
    a = select(a, 1.5707963267948966 - a, ay > ax);
    a = select(a, 3.141592653589793 - a, x < 0.0);
    return select(a, -a, y < 0.0);
}

// Position in the hemisphere around the projected normal, 0 to 1, of slice-plane vector `w`.
fn hemisphere_position(p: EstimatorPixel, s: EstimatorSample, w: vec3<f32>) -> f32 {
    let angle = slice_angle(dot(w, slice_tangent(p, s.slice)), dot(w, p.v));
    return saturate((angle - slice_normal_angle(p, s.slice) + 1.5707963267948966) / 3.141592653589793);
}

// The sectors between hemisphere positions a and b (seed 003's UpdateSectors).
fn sector_bits(a: f32, b: f32) -> u32 {
    let lo = min(a, b);
    let width = (max(a, b) - lo) * 32.0;
    var count: f32;
    switch params.activation {
        case 1u: { count = round(width); }
        case 2u: { count = floor(width); }
        default: { count = ceil(width); }
    }
    let start = min(u32(lo * 32.0), 32u);
    let n = min(u32(max(count, 0.0)), 32u - start);
    if (n == 0u) {
        return 0u;
    }
    return (0xffffffffu >> (32u - n)) << start;
}

fn estimator_occluder(p: EstimatorPixel, s: EstimatorSample, pos: vec3<f32>) -> Occluder {
    let front = pos - p.pos;
    var o: Occluder;
    // A front face on or below the tangent plane occludes nothing (its back face lies lower
    // still), nor can a deeper surface at that pixel (it lies lower along the view ray). The
    // margin, 1e-3 rad, absorbs the G-buffer's half-float normals (~5e-4 rad).
    if (dot(front, p.normal) <= 1e-3 * length(front)) {
        o.value = 0u;
        o.hidden = false;
        return o;
    }
    let back = front - p.v * params.thickness;
    let b = hemisphere_position(p, s, back);
    o.value = sector_bits(hemisphere_position(p, s, front), b);
    // A deeper surface may cover sectors this one leaves free, unless none can (ours, exact, as
    // ssao.wgsl's query test). Every deeper surface at this pixel lies on the camera ray beyond
    // `pos`; seen from the shading point, that ray runs from the camera (angle 0 from V) away
    // from it, on one side of V only, so its points, and their back faces (moved along −V), lie
    // between this front face and the hemisphere's edge on that side. When this back face
    // reaches the edge and its run of sectors reaches the edge sector, every sector a deeper
    // surface could mark is marked already. The image is the same either way.
    let toward_one = dot(front, slice_tangent(p, s.slice)) > 0.0;
    let edge_bit = select(1u, 0x80000000u, toward_one);
    let at_edge = select(b <= 0.0, b >= 1.0, toward_one);
    o.hidden = !(EXACT_QUERY && at_edge && (o.value & edge_bit) != 0u);
    return o;
}

// Several depths for one sample: every one marks its own sectors.
fn estimator_combine(a: u32, b: u32) -> u32 {
    return a | b;
}

// Missing-occlusion compensation (seed 001 §4; read.wgsl's SD_COMPENSATION), ours for the
// bitmask: one surface's sectors are one run (sector_bits); a stochastic sample's run is widened
// about its centre to `factor` times its sectors (at most 32, kept inside the hemisphere).
fn estimator_compensate(p: EstimatorPixel, s: EstimatorSample, value: u32, factor: f32) -> u32 {
    let n = countOneBits(value);
    if (n == 0u) {
        return 0u;
    }
    let wide = min(u32(round(f32(n) * factor)), 32u);
    if (wide == 0u || wide == 32u) {
        return select(0u, 0xffffffffu, wide == 32u);
    }
    let grow = i32(wide) - i32(n);
    let start = clamp(i32(firstTrailingBit(value)) - grow / 2, 0, 32 - i32(wide));
    return (0xffffffffu >> (32u - wide)) << u32(start);
}

fn estimator_accum_init() -> EstimatorAccum {
    return EstimatorAccum(array<u32, 3>(0u, 0u, 0u));
}

fn estimator_accum_sample(acc: EstimatorAccum, s: EstimatorSample) -> EstimatorAccum {
    return acc;
}

fn estimator_accum_value(acc: EstimatorAccum, s: EstimatorSample, value: u32) -> EstimatorAccum {
    var a = acc;
    a.masks[0] |= select(0u, value, s.slice == 0u);
    a.masks[1] |= select(0u, value, s.slice == 1u);
    a.masks[2] |= select(0u, value, s.slice == 2u);
    return a;
}

// The cosine-weighted visibility of slice j's free sectors over its whole hemisphere's
// (slice_visibility.wgsl), one run of free sectors at a time.
fn cosine_weighted_visible(p: EstimatorPixel, j: u32, mask: u32) -> vec2<f32> {
    let g = p.normal_angles[j];
    var free = ~mask;
    var visible = 0.0;
    while (free != 0u) {
        let start = countTrailingZeros(free);
        // The run of free sectors from `start`: the ones of free >> start up to its first zero.
        let run = countTrailingZeros(~(free >> start));
        let end = start + run;
        visible += span_visibility(
            g + 3.141592653589793 * (f32(start) / 32.0 - 0.5),
            g + 3.141592653589793 * (f32(end) / 32.0 - 0.5),
            g,
        );
        free &= select(0xffffffffu << end, 0u, end >= 32u);
    }
    return p.projected_lengths[j] * vec2<f32>(visible, open_slice_visibility(g));
}

fn estimator_finish(p: EstimatorPixel, acc: EstimatorAccum) -> f32 {
    var visible = 0.0;
    var open = 0.0;
    for (var j = 0u; j < SLICES; j++) {
        if (COSINE_WEIGHTED) {
            let v = cosine_weighted_visible(p, j, acc.masks[j]);
            visible += v.x;
            open += v.y;
        } else {
            visible += 1.0 - f32(countOneBits(acc.masks[j])) / 32.0;
            open += 1.0;
        }
    }
    return pow(saturate(visible / max(open, 1e-20)), params.exponent);
}

// The debug image (`render --debug-out`): the bitmask occupancy, occupied sectors over all of
// the pixel's slices' sectors.
fn estimator_debug(p: EstimatorPixel, acc: EstimatorAccum) -> f32 {
    var occupied = 0u;
    for (var j = 0u; j < SLICES; j++) {
        occupied += countOneBits(acc.masks[j]);
    }
    return f32(occupied) / (32.0 * f32(SLICES));
}

// The bent normal (`bent_normals`, seed 001 §4; ours for the bitmask): per slice, the mean
// direction of its free sectors, weighted as its AO weighs them (uniformly in angle, or by the
// cosine with `cosine_weighted`), summed over slices against the whole hemispheres' and made
// exact on unoccluded planes by common/bent.wgsl's bent_from_sums; view space. Sector
// boundary k lies at θ = γ + x, x = π(k/32 − 1/2): (sin x, cos x) = (−cos πk/32, sin πk/32),
// turned by γ. The uniform weight is linear in those pairs, so a slice's free sectors are summed
// before the one turn, from the table of marked_sector_sum; the open hemisphere's vector is
// (2 sin γ, 2 cos γ).

// GTAO-VB's table (bindings.rs, ESTIMATOR_TABLE; estimators/gtao_vb.rs makes it): per byte of a
// mask, 2 sin(π/64) Σ (cos φ_j, sin φ_j) over its set bits j, φ_j = (j + ½)π/32.
@group(GROUP_ESTIMATOR) @binding(ESTIMATOR_TABLE) var sector_directions: texture_2d<f32>;

// 2 sin(π/64) Σ (cos φ_k, sin φ_k) over the sectors k `mask` marks, φ_k = (k + ½)π/32: the four
// bytes' table entries, byte b's turned by bπ/4 (its first sector's offset). One sector's ∫ω in
// the local (sin x, cos x) frame is the pair of boundaries' difference, 2 sin(π/64) (cos φ_k,
// −sin φ_k) (the sum-to-product identities), and all 32 sum to (0, 2), so the free sectors'
// ∫ω is (m.x, 2 − m.y) for m this sum: the same as a loop over the runs of free sectors, with
// four loads instead of a loop as long as the warp's most broken mask.
fn marked_sector_sum(mask: u32) -> vec2<f32> {
    let t0 = textureLoad(sector_directions, vec2<u32>(mask & 255u, 0u), 0).xy;
    let t1 = textureLoad(sector_directions, vec2<u32>((mask >> 8u) & 255u, 0u), 0).xy;
    let t2 = textureLoad(sector_directions, vec2<u32>((mask >> 16u) & 255u, 0u), 0).xy;
    let t3 = textureLoad(sector_directions, vec2<u32>(mask >> 24u, 0u), 0).xy;
    let h = 0.7071067811865476;
    return t0 + h * vec2<f32>(t1.x - t1.y, t1.x + t1.y) + vec2<f32>(-t2.y, t2.x)
        + h * vec2<f32>(-t3.x - t3.y, t3.x - t3.y);
}

// The cosine-weighted bent vector of a slice's free sectors in its (tangent, V) frame, one run of
// free sectors at a time (the cosine weight turns with γ, so no table serves it).
fn cosine_weighted_free_bent(mask: u32, g: vec2<f32>) -> vec2<f32> {
    let step = 3.141592653589793 / 32.0;
    let turn = mat2x2<f32>(g.y, -g.x, g.x, g.y);
    var free = ~mask;
    var sum = vec2<f32>(0.0);
    while (free != 0u) {
        let start = countTrailingZeros(free);
        let end = start + countTrailingZeros(~(free >> start));
        let a = vec2<f32>(-cos(step * f32(start)), sin(step * f32(start)));
        let b = vec2<f32>(-cos(step * f32(end)), sin(step * f32(end)));
        sum += span_bent(turn * a, turn * b, g);
        free &= select(0xffffffffu << end, 0u, end >= 32u);
    }
    return sum;
}

fn estimator_bent_normal(
    p: EstimatorPixel,
    acc: EstimatorAccum,
    sample_visible: vec3<f32>,
    sample_open: vec3<f32>,
) -> vec3<f32> {
    var visible = vec3<f32>(0.0);
    var open = vec3<f32>(0.0);
    for (var j = 0u; j < SLICES; j++) {
        let g = vec2<f32>(sin(p.normal_angles[j]), cos(p.normal_angles[j]));
        var sum: vec2<f32>;
        var whole: vec2<f32>;
        if (COSINE_WEIGHTED) {
            sum = p.projected_lengths[j] * cosine_weighted_free_bent(acc.masks[j], g);
            whole = p.projected_lengths[j] * open_slice_bent(g);
        } else {
            let m = marked_sector_sum(acc.masks[j]);
            let local = vec2<f32>(m.x, 2.0 - m.y);
            // ∫ω over θ = γ + x: the local (t, v) sums turned by γ.
            sum = vec2<f32>(g.y * local.x + g.x * local.y, g.y * local.y - g.x * local.x);
            whole = 2.0 * g;
        }
        visible += sum.x * p.tangents[j] + sum.y * p.v;
        open += whole.x * p.tangents[j] + whole.y * p.v;
    }
    return bent_from_sums(p.normal, visible, open);
}
