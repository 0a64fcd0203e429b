// Hidden-depth source "BVH rays" (`rtao`): each hemisphere ray traced through the scene's BVH in
// world space from the pixel's surface point, as the ground truth traces its rays
// (reference/reference.wgsl: the same offset along the normal, the same any-hit or closest-hit
// query), so nothing the depth buffer hides is missed. Reads the hemisphere estimator's rays: a
// hemisphere-only source (src/technique.rs says so).
//
// Needs common/material.wgsl, common/bvh.wgsl and sources/ray_camera.wgsl in front. The source
// contract: see first_layer.wgsl.

// The built-in closest-hit and any-hit queries serve these rays.
fn bvh_on_hit(hit: BvhHit) -> u32 {
    return BVH_STOP;
}

fn source_lookup(p: EstimatorPixel, s: EstimatorSample) -> DepthLookup {
    var l: DepthLookup;
    l.value = 1.0;
    l.trace = true;
    l.px = s.px;
    l.t_after = 0.0;
    return l;
}

// The ray traced: its visibility over [0, R].
fn source_resolve(p: EstimatorPixel, s: EstimatorSample, l: DepthLookup) -> EstimatorValue {
    let to_world = ray_camera.camera_to_world;
    let world = (to_world * vec4<f32>(p.pos, 1.0)).xyz;
    let n = normalize((to_world * vec4<f32>(p.normal, 0.0)).xyz);
    let dir = (to_world * vec4<f32>(s.dir, 0.0)).xyz;
    let radius = params.radius;
    let start = world + n * max(1e-4 * radius, 1e-6 * max(max(abs(world.x), abs(world.y)), abs(world.z)));
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
