// Hidden-depth source "BVH rays" (`rtao`): each hemisphere ray traced through the scene's BVH in
// world space from the pixel's surface point, as the ground truth traces its rays
// (reference/reference.wgsl: the same offset along the normal, the same any-hit or closest-hit
// query), so nothing the depth buffer hides is missed. Reads the hemisphere estimator's rays: a
// hemisphere-only source (src/technique.rs says so).
//
// Two phases (`rtao-two-phase`): phase 1 proves rays free or blocked in screen space
// (bvh_rays_proof.wgsl, composed after this file into phase 1 only) and phase 2 traces the
// others; every other pass is composed with bvh_rays_no_proof.wgsl and traces every ray.
//
// Needs common/material.wgsl, common/bvh.wgsl and sources/ray_camera.wgsl in front. The source
// contract: see first_layer.wgsl.

// The built-in closest-hit and any-hit queries serve these rays.
fn bvh_on_hit(hit: BvhHit) -> u32 {
    return BVH_STOP;
}

// What phase 1 proved of a ray (`screen_proof`).
const PROOF_NONE: u32 = 0u;
const PROOF_FREE: u32 = 1u;
const PROOF_BLOCKED: u32 = 2u;

fn source_lookup(p: EstimatorPixel, s: EstimatorSample) -> DepthLookup {
    var l: DepthLookup;
    let proof = screen_proof(p, s);
    l.trace = proof == PROOF_NONE;
    l.value = select(1.0, 0.0, proof == PROOF_BLOCKED);
    l.px = s.px;
    l.t_after = 0.0;
    return l;
}

// The world-space ray of sample `s` as the BVH traces it: from the pixel's surface point, offset
// along the normal as the ground truth offsets it (reference/reference.wgsl).
struct WorldRay {
    start: vec3<f32>,
    dir: vec3<f32>,
}

fn world_ray(p: EstimatorPixel, s: EstimatorSample) -> WorldRay {
    let to_world = ray_camera.camera_to_world;
    let world = (to_world * vec4<f32>(p.pos, 1.0)).xyz;
    let n = normalize((to_world * vec4<f32>(p.normal, 0.0)).xyz);
    var r: WorldRay;
    r.dir = (to_world * vec4<f32>(s.dir, 0.0)).xyz;
    r.start = world + n * max(1e-4 * params.radius, 1e-6 * max(max(abs(world.x), abs(world.y)), abs(world.z)));
    return r;
}

// The ray traced: its visibility over [0, R].
fn source_resolve(p: EstimatorPixel, s: EstimatorSample, l: DepthLookup) -> EstimatorValue {
    let w = world_ray(p, s);
    let start = w.start;
    let dir = w.dir;
    let radius = params.radius;
    bvh_stack_overflow = false;
    var value = 1.0;
    if (params.falloff != 0u) {
        let hit = bvh_closest_hit(start, dir, 0.0, radius);
        if (hit.t >= 0.0) {
            value = hemisphere_blocked_at(hit.t);
        }
    } else if (bvh_any_hit(start, dir, 0.0, radius)) {
        value = 0.0;
    }
    if (bvh_stack_overflow) {
        atomicAdd(&stack_overflows, 1u);
    }
    return value;
}

// Two-phase phase 1: rays need nothing prepared.
fn source_request(l: DepthLookup) {}
