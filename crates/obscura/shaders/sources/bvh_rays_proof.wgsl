// Phase 1 of two-phase BVH rays (`rtao-two-phase`; ours, seed 000 §3.8's division of labour
// carried from VAO's columns to hemisphere rays): `screen_proof` walks each ray's image on screen
// and proves it free or blocked, which leaves it out of the BVH; phase 2 traces the others.
// Composed after bvh_rays.wgsl into phase 1 only (the bindings below are phase 1's).
//
// Free. A ray is proven free when its far end (t = R) lies inside the framebuffer (guard band
// included) and in front of the near plane, and over every pixel its image on screen crosses
// (other than its own) the pixel shows background, or the part of the ray over that pixel lies on
// the camera's side of the tangent plane of the surface the pixel shows (by a margin) and nearer
// than that pixel's depth. Anything the ray could meet would then lie in front of the surfaces
// the frame shows, i.e. be shown itself. The rule is exact but for what a pixel centre does not
// show: within a pixel, a surface that covers part of it but not its centre, or a surface that
// bends away from the centre's tangent plane (tests/it/hemisphere.rs measures how often that
// changes a pixel).
//
// Blocked. Depths alone never prove a ray blocked: a ray behind the surface a pixel centre shows
// may pass behind that surface rather than through it. The triangle the pixel shows can: where
// the walk first finds the ray behind (or below the tangent plane of) what a pixel or its side
// neighbours show, the ray is tested against each of those pixels' visible triangles (the G-buffer's
// visibility buffer) with the BVH's own watertight test and the scene's rules (back faces,
// alpha). A hit within [0, R] is a hit the BVH's any-hit query finds too, so the ray is blocked,
// exactly: the value is the one phase 2 would trace. Only without falloff (with it the value
// needs the nearest hit, which one triangle does not tell), and only where the frame's visible
// triangles are bound (crate::Renderer's own G-buffer: an engine's frame has none, and its
// 1×1 stand-in turns the proof off). The walk then also goes on for a ray whose far end leaves the
// framebuffer, up to the frame's edge: it cannot be proven free, but it can be proven blocked.
//
// Phase 1's blocked proof: per framebuffer pixel the drawn triangle it shows + 1 (0: none), and
// the drawn triangles (vertex 0, vertex 1, vertex 2, material) those indices name.
@group(GROUP_SOURCE) @binding(SOURCE_VISIBLE_TRIANGLES) var visible_triangles: texture_2d<u32>;
@group(GROUP_SOURCE) @binding(SOURCE_DRAWN_TRIANGLES) var<storage, read> drawn_triangles: array<vec4<u32>>;

// Cells where the walk finds the ray behind what the frame shows, whose triangles it tests,
// before it leaves the ray to the BVH (ours, tests/it/hemisphere.rs).
const BLOCKED_TRIES: u32 = 16u;

// Whether phase 1 may prove rays blocked this frame: no falloff, and the frame's visible
// triangles bound.
fn blocked_proof_on() -> bool {
    return params.falloff == 0u && all(textureDimensions(visible_triangles) == view.full_size);
}

// Phase 1's rules above: the ray's image on screen walked pixel by pixel (Amanatides and Woo's
// grid traversal), the part of the ray over each pixel tested at both of its ends (its height over
// a plane and its depth are affine along the ray, so the ends bound them).
fn screen_proof(p: EstimatorPixel, s: EstimatorSample) -> u32 {
    let end = p.pos + s.dir * params.radius;
    let a = view_to_pixel(view, p.pos);
    let b = view_to_pixel(view, end);
    let in_front = ORTHOGRAPHIC || -end.z > view.near;
    if (!in_front) {
        return PROOF_NONE;
    }
    let end_inside = all(b >= vec2<f32>(0.0)) && all(b < vec2<f32>(view.full_size));
    let blocked_on = blocked_proof_on();
    if (!end_inside && !blocked_on) {
        return PROOF_NONE;
    }
    let d = b - a;
    // The walk crosses about |dx| + |dy| pixels: a longer one costs more than tracing the ray
    // (`hemisphere.proof_pixels`, a bound on phase 1's cost per ray, ours).
    if (abs(d.x) + abs(d.y) > f32(params.proof_pixels)) {
        return PROOF_NONE;
    }
    let forward = d > vec2<f32>(0.0);
    let step = select(vec2<i32>(-1), vec2<i32>(1), forward);
    // Screen parameter u (0 at a, 1 at b) of the next pixel edge along each axis, and per pixel.
    let per_pixel = 1.0 / max(abs(d), vec2<f32>(1e-12));
    var cell = vec2<i32>(floor(a));
    let last = vec2<i32>(floor(b));
    var edge = (select(a - floor(a), floor(a) + 1.0 - a, forward)) * per_pixel;
    var u0 = 0.0;
    var free = true;
    var tries = 0u;
    var r: BvhRay;
    // Every crossed cell but the last adds one edge: |dx| + |dy| + 2 steps cover the image.
    for (var i = 0u; i < params.proof_pixels + 2u; i++) {
        // A ray whose far end leaves the frame is walked to the frame's edge (blocked proof).
        if (any(cell < vec2<i32>(0)) || any(cell >= vec2<i32>(view.full_size))) {
            return PROOF_NONE;
        }
        let u1 = min(min(edge.x, edge.y), 1.0);
        if (any(vec2<u32>(cell) != p.pixel) && !free_over_pixel(p, s, end, vec2<u32>(cell), u0, u1)) {
            free = false;
            if (!blocked_on) {
                return PROOF_NONE;
            }
            // The world-space ray once per ray, at its first failure (not per try).
            if (tries == 0u) {
                let w = world_ray(p, s);
                r = bvh_ray(w.start, w.dir);
            }
            if (shows_blocker(r, vec2<u32>(cell))) {
                return PROOF_BLOCKED;
            }
            tries += 1u;
            if (tries >= BLOCKED_TRIES) {
                return PROOF_NONE;
            }
        }
        if (all(cell == last) || u1 >= 1.0) {
            return select(PROOF_NONE, PROOF_FREE, free && end_inside);
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
    return PROOF_NONE;
}

// Whether ray `r` (world_ray's, set up for the BVH's test) hits, within [0, R] and by the scene's rules, the triangle that pixel `cell` or
// one of its side neighbours shows (the neighbours: free_over_pixel also fails on a neighbour's
// tangent plane, and a ray that passes behind one pixel's surface may meet it over the next).
// Each distinct triangle is tested once, in the order met.
fn shows_blocker(r: BvhRay, cell: vec2<u32>) -> bool {
    var tested = array<u32, 5>(0u, 0u, 0u, 0u, 0u);
    for (var k = 0u; k < 5u; k++) {
        var offset = vec2<i32>(0);
        if (k > 0u) {
            let sign = 1 - 2 * i32(k & 1u);
            offset = select(vec2<i32>(0, sign), vec2<i32>(sign, 0), k < 3u);
        }
        let at = vec2<i32>(cell) + offset;
        if (any(at < vec2<i32>(0)) || any(at >= vec2<i32>(view.full_size))) {
            continue;
        }
        let id = textureLoad(visible_triangles, vec2<u32>(at), 0).r;
        var seen = id == 0u;
        for (var j = 0u; j < k; j++) {
            seen = seen || tested[j] == id;
        }
        tested[k] = id;
        if (seen) {
            continue;
        }
        let tri = drawn_triangles[id - 1u];
        let hit = bvh_intersect_triangle(r, tri, 0.0, params.radius);
        if (hit.t >= 0.0 && bvh_triangle_passes_rules(tri, hit)) {
            return true;
        }
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
