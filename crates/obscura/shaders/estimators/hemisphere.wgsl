// The hemisphere estimator: the AO of the hemisphere model itself, A = 1 − (1/N) Σ occlusion of
// N cosine-weighted rays within R from the shading point (occlusion 1 for a blocked ray, or
// W(t) = max(0, 1 − t/R) at its first hit with `falloff`), the ground truth's model
// (src/reference/ground_truth.rs) with its rays (common/hemisphere.wgsl). Over frames of temporal
// accumulation the seed is the frame number, so each frame draws new rays and the running mean
// converges to the ground truth wherever the source answers as the scene would.
//
// Estimator contract (docs/ARCHITECTURE.md): a sample is one ray; its value is the ray's
// visibility, 1 − occlusion (1 free; 0 blocked; t/R blocked at t with falloff). The sources for
// it (hemisphere-only: sources/screen_rays.wgsl, sources/bvh_rays.wgsl) decide the whole ray; the
// accumulator sums, so the order of rays never matters and two-phase schedules can run it.
// Several depths combine by the minimum (the ray is as blocked as its nearest blocker says).
//
// Its pixel set-up is its own (no radius cap); screen_space.wgsl, in front, gives the contract's
// accessors.
//
// Ours: rays start in view space at the pixel's surface point with its G-buffer normal; the world
// radius is never capped on screen (rays are world-space, and the screen march's cost does not
// grow with R: `steps` points per ray).

struct HemisphereParams {
    radius: f32,
    thickness: f32,
    falloff: u32,
    steps: u32,
    // rtao-two-phase's phase 1: the longest ray image it walks (sources/bvh_rays_proof.wgsl).
    proof_pixels: u32,
}

@group(GROUP_ESTIMATOR) @binding(ESTIMATOR_PARAMS) var<uniform> params: HemisphereParams;

// N, the rays per pixel, at most 32 (one bit per ray in the two-phase mask).
override SAMPLE_COUNT: u32 = 1u;

// Under a ray budget (`hemisphere.ray_budget`, filter/ray_budget.wgsl) each pixel casts the rays
// the budget granted it this frame, N or fewer (a set of that many rays), or none: then its AO
// is NO_RAYS, and temporal accumulation keeps its history as it is.
override RAY_BUDGET: bool = false;
@group(GROUP_FRAME) @binding(FRAME_RAY_GRANT) var ray_grant: texture_2d<u32>;
const NO_RAYS: f32 = -1.0;

struct EstimatorPixel {
    pixel: vec2<u32>,
    valid: bool,
    pos: vec3<f32>,
    normal: vec3<f32>,
    tangent: vec3<f32>,
    bitangent: vec3<f32>,
    rotation: vec2<f32>,
    // Screen rays: where in its first interval the march's first point lies, in [0, 1).
    jitter: f32,
    // The rays it casts this frame: N, or what a ray budget granted.
    rays: u32,
}

struct EstimatorSample {
    // Unit direction in view space.
    dir: vec3<f32>,
    // Framebuffer coordinates of the ray's far end (t = R).
    px: vec2<f32>,
    on: bool,
}

// The ray's visibility, 1 − its occlusion.
alias EstimatorValue = f32;

struct EstimatorAccum {
    visibility: f32,
    // The debug image only: the rays with any occlusion.
    blocked: f32,
    _pad0: f32,
}

struct Occluder {
    value: f32,
    hidden: bool,
}

fn estimator_pixel(id: vec2<u32>) -> EstimatorPixel {
    let point = frame_point(id);
    var p: EstimatorPixel;
    p.pixel = point.pixel;
    p.valid = point.valid;
    if (!p.valid) {
        return p;
    }
    p.pos = point.pos;
    p.normal = point.normal;
    let basis = orthonormal_basis(p.normal);
    p.tangent = basis[0];
    p.bitangent = basis[1];
    // The visible pixel and the frame seed the rays, as the ground truth's seed and pixel do.
    p.rotation = pixel_rotation_2d(view.frame, id.x, id.y);
    p.jitter = hash_to_unit(pcg_hash(pcg_hash(view.frame + 0x9e3779b9u) ^ (id.x + pcg_hash(id.y))));
    p.rays = SAMPLE_COUNT;
    if (RAY_BUDGET) {
        p.rays = min(textureLoad(ray_grant, id, 0).x, SAMPLE_COUNT);
    }
    return p;
}

fn estimator_sample(p: EstimatorPixel, i: u32) -> EstimatorSample {
    var s: EstimatorSample;
    s.on = i < p.rays;
    let count = max(p.rays, 1u);
    s.dir = hemisphere_direction(i, count, p.rotation, p.normal, array<vec3<f32>, 2>(p.tangent, p.bitangent));
    s.px = view_to_pixel(view, p.pos + s.dir * params.radius);
    return s;
}

fn estimator_unoccluded(p: EstimatorPixel, s: EstimatorSample) -> f32 {
    return 1.0;
}

// The visibility of a ray blocked at distance t.
fn hemisphere_blocked_at(t: f32) -> f32 {
    return select(0.0, clamp(t / params.radius, 0.0, 1.0), params.falloff != 0u);
}

// Where view-space point `q` lies against the surface seen at framebuffer pixel `cell` (linear
// depth `z`): its signed distance from that surface's tangent plane (the pixel's G-buffer normal
// turned to the camera), positive on the camera's side, and the slack a test allows it (relative,
// as the ground truth offsets its rays from the surface). The plane rather than the pixel
// centre's depth, so that points above a plane that the pixel centre misses by a fraction of a
// pixel are never taken for inside it.
struct SurfaceSide {
    height: f32,
    slack: f32,
}

fn surface_side(q: vec3<f32>, cell: vec2<u32>, z: f32) -> SurfaceSide {
    let surface = pixel_to_view(view, vec2<f32>(cell) + 0.5, z);
    var m = normalize(textureLoad(normal_tex, cell, 0).xyz);
    m = select(m, -m, dot(m, toward_camera(view, surface)) < 0.0);
    let slack = 1e-4 * params.radius + 1e-6 * max(max(abs(surface.x), abs(surface.y)), abs(surface.z));
    return SurfaceSide(dot(q - surface, m), slack);
}

// Whether `q` lies inside the surface at `cell`: behind its tangent plane and less than
// `thickness` behind its depth.
fn hemisphere_inside(q: vec3<f32>, cell: vec2<u32>, z: f32, thickness: f32) -> bool {
    let side = surface_side(q, cell, z);
    return side.height < -side.slack && -q.z - z < thickness;
}

// The surface at view-space point `pos` against the ray's far end (the contract's single-depth
// test, which frame.wgsl's first_layer_lookup makes through screen_space.wgsl's
// estimator_occluder_at; the hemisphere's own sources march the whole ray).
fn estimator_occluder(p: EstimatorPixel, s: EstimatorSample, pos: vec3<f32>) -> Occluder {
    var o: Occluder;
    let q = p.pos + s.dir * params.radius;
    let cell = vec2<u32>(view_to_pixel(view, pos));
    let inside = hemisphere_inside(q, cell, -pos.z, params.thickness);
    o.value = select(1.0, hemisphere_blocked_at(params.radius), inside);
    o.hidden = !inside;
    return o;
}

fn estimator_combine(a: f32, b: f32) -> f32 {
    return min(a, b);
}

// Missing-occlusion compensation (seed 001 §4): the ray's occlusion counts `factor` times.
fn estimator_compensate(p: EstimatorPixel, s: EstimatorSample, value: f32, factor: f32) -> f32 {
    return max(1.0 - (1.0 - value) * factor, 0.0);
}

fn estimator_accum_init() -> EstimatorAccum {
    return EstimatorAccum(0.0, 0.0, 0.0);
}

fn estimator_accum_sample(acc: EstimatorAccum, s: EstimatorSample) -> EstimatorAccum {
    return acc;
}

fn estimator_accum_value(acc: EstimatorAccum, s: EstimatorSample, value: f32) -> EstimatorAccum {
    var a = acc;
    a.visibility += value;
    if (ESTIMATOR_DEBUG && value < 1.0) {
        a.blocked += 1.0;
    }
    return a;
}

fn estimator_finish(p: EstimatorPixel, acc: EstimatorAccum) -> f32 {
    if (p.rays == 0u) {
        return NO_RAYS;
    }
    return acc.visibility / f32(p.rays);
}

// The debug image (`render --debug-out`): the fraction of the rays blocked, none black … all
// white.
fn estimator_debug(p: EstimatorPixel, acc: EstimatorAccum) -> f32 {
    return acc.blocked / f32(max(p.rays, 1u));
}
