// Hidden-depth source "BVH rays" (`rtao`): each hemisphere ray traced through the scene's BVH in
// world space from the pixel's surface point, as the ground truth traces its rays
// (reference/reference.wgsl: the same offset along the normal, the same any-hit or closest-hit
// query), so nothing the depth buffer hides is missed. Reads the hemisphere estimator's rays: a
// hemisphere-only source (src/technique.rs says so).
//
// Two phases (`rtao-two-phase`, SCREEN_PROOF; ours, seed 000 §3.8's division of labour carried
// from VAO's columns to hemisphere rays): phase 1 marches each ray in screen space and leaves out
// of the BVH every ray it proves free; phase 2 traces the others.
//
// The rule. A ray is proven free when its far end (t = R) lies inside the framebuffer (guard band
// included) and in front of the near plane, and over every pixel its image on screen crosses
// (other than its own) the pixel shows background, or the part of the ray over that pixel lies on
// the camera's side of the tangent plane of the surface the pixel shows (by a margin) and nearer
// than that pixel's depth. Anything the ray could meet would then lie in front of the surfaces
// the frame shows, i.e. be shown itself. The rule is exact but for what a pixel centre does not
// show: within a pixel, a surface that covers part of it but not its centre, or a surface that
// bends away from the centre's tangent plane (tests/it/hemisphere.rs measures how often that
// changes a pixel). Phase 1 never proves a ray blocked: a ray behind the surface a pixel centre
// shows may pass behind that surface rather than through it, which only the BVH can tell.
//
// Needs common/material.wgsl, common/bvh.wgsl and sources/ray_camera.wgsl in front. The source
// contract: see first_layer.wgsl.

override SCREEN_PROOF: bool = false;

// The built-in closest-hit and any-hit queries serve these rays.
fn bvh_on_hit(hit: BvhHit) -> u32 {
    return BVH_STOP;
}

fn source_lookup(p: EstimatorPixel, s: EstimatorSample) -> DepthLookup {
    var l: DepthLookup;
    l.value = 1.0;
    l.trace = !(SCREEN_PROOF && proven_free(p, s));
    l.px = s.px;
    l.t_after = 0.0;
    return l;
}

// Phase 1 walks at most this many pixels of a ray's image; a longer ray is left to the BVH (a
// bound on phase 1's cost per ray, ours).
const PROOF_MAX_PIXELS: u32 = 256u;

// Phase 1's rule above: the ray's image on screen walked pixel by pixel (Amanatides and Woo's
// grid traversal), the part of the ray over each pixel tested at both of its ends (its height over
// a plane and its depth are affine along the ray, so the ends bound them).
fn proven_free(p: EstimatorPixel, s: EstimatorSample) -> bool {
    let end = p.pos + s.dir * params.radius;
    let a = view_to_pixel(view, p.pos);
    let b = view_to_pixel(view, end);
    let in_front = ORTHOGRAPHIC || -end.z > view.near;
    if (!in_front || any(b < vec2<f32>(0.0)) || any(b >= vec2<f32>(view.full_size))) {
        return false;
    }
    let d = b - a;
    let forward = d > vec2<f32>(0.0);
    let step = select(vec2<i32>(-1), vec2<i32>(1), forward);
    // Screen parameter u (0 at a, 1 at b) of the next pixel edge along each axis, and per pixel.
    let per_pixel = 1.0 / max(abs(d), vec2<f32>(1e-12));
    var cell = vec2<i32>(floor(a));
    let last = vec2<i32>(floor(b));
    var edge = (select(a - floor(a), floor(a) + 1.0 - a, forward)) * per_pixel;
    var u0 = 0.0;
    for (var i = 0u; i < PROOF_MAX_PIXELS; i++) {
        let u1 = min(min(edge.x, edge.y), 1.0);
        if (any(vec2<u32>(cell) != p.pixel) && !free_over_pixel(p, s, end, vec2<u32>(cell), u0, u1)) {
            return false;
        }
        if (all(cell == last) || u1 >= 1.0) {
            return true;
        }
        if (edge.x < edge.y) {
            cell.x += step.x;
            edge.x += per_pixel.x;
        } else {
            cell.y += step.y;
            edge.y += per_pixel.y;
        }
        u0 = u1;
    }
    return false;
}

// Whether the part of ray `s` whose image runs from screen parameter u0 to u1 lies in front of
// the surface pixel `cell` shows (or the pixel shows background), and in front of the tangent
// plane of each side neighbour that shows a nearer surface: such a surface may cover part of
// `cell` beside its centre (a silhouette's edge). A screen parameter u is the ray fraction
// λ = u·w₀ / ((1 − u)·w₁ + u·w₀) (w the linear depths of the ray's ends: perspective maps a
// line's points to its image that way).
fn free_over_pixel(p: EstimatorPixel, s: EstimatorSample, end: vec3<f32>, cell: vec2<u32>, u0: f32, u1: f32) -> bool {
    let z = textureLoad(depth_tex, cell, 0).r;
    let w0 = select(-p.pos.z, 1.0, ORTHOGRAPHIC);
    let w1 = select(-end.z, 1.0, ORTHOGRAPHIC);
    let l0 = u0 * w0 / ((1.0 - u0) * w1 + u0 * w0);
    let l1 = u1 * w0 / ((1.0 - u1) * w1 + u1 * w0);
    let q0 = p.pos + s.dir * (params.radius * l0);
    let q1 = p.pos + s.dir * (params.radius * l1);
    let open = is_background(z);
    if (!open && !(in_front_of_surface(q0, cell, z) && in_front_of_surface(q1, cell, z))) {
        return false;
    }
    for (var k = 0u; k < 4u; k++) {
        let offset = select(vec2<i32>(0, 1 - 2 * i32(k & 1u)), vec2<i32>(1 - 2 * i32(k & 1u), 0), k < 2u);
        let side = vec2<i32>(cell) + offset;
        if (any(side < vec2<i32>(0)) || any(side >= vec2<i32>(view.full_size)) || all(vec2<u32>(side) == p.pixel)) {
            continue;
        }
        let zs = textureLoad(depth_tex, vec2<u32>(side), 0).r;
        let nearer = !is_background(zs) && (open || zs < z * 0.99);
        if (nearer && !(in_front_of_plane(q0, vec2<u32>(side), zs) && in_front_of_plane(q1, vec2<u32>(side), zs))) {
            return false;
        }
    }
    return true;
}

// Whether `q` lies on the camera's side of the tangent plane of the surface at pixel `cell`.
fn in_front_of_plane(q: vec3<f32>, cell: vec2<u32>, z: f32) -> bool {
    let side = surface_side(q, cell, z);
    return side.height > side.slack;
}

// Whether view-space point `q` lies on the camera's side of the surface at framebuffer pixel
// `cell` (depth `z`), beyond the slack, and nearer than that pixel's depth.
fn in_front_of_surface(q: vec3<f32>, cell: vec2<u32>, z: f32) -> bool {
    return in_front_of_plane(q, cell, z) && -q.z < z;
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
