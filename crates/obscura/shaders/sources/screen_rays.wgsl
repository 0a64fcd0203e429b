// Hidden-depth source "screen rays" (`hemisphere`): each hemisphere ray marched in screen space
// over the first depth layer, the screen-space ray-traced AO engines ship. `steps` points evenly
// spaced along the ray within R (a per-pixel jitter shifts them) are projected to the frame; the
// ray is blocked at the first point that lies inside a surface: behind the tangent plane of the
// surface the depth buffer shows there, and less than `thickness` behind it (the depth buffer
// says nothing of what lies farther behind, so a thickness stands in for it). A ray that leaves
// the frame or passes behind the near plane is free from there on. Reads the hemisphere
// estimator's rays: a hemisphere-only source (src/technique.rs says so).
// With a second depth layer ("screen rays dual", `hemisphere-dual`; screen_rays_dual.wgsl in
// front, screen_rays_first.wgsl without one) the first surface is no thicker than the gap to the
// second: a thin board before a wall no longer occludes all of `thickness` behind it. Only that:
// the second layer of a closed object is its back face, with air behind it, and a layer's
// facing is not stored, so no thickness is assumed behind the second layer.
// The source contract: see first_layer.wgsl.

// Whether `q` lies inside a surface at framebuffer pixel `cell`, whose first layer is at linear
// depth `z`.
fn screen_rays_inside(q: vec3<f32>, cell: vec2<u32>, z: f32) -> bool {
    let z2 = screen_rays_second_depth(cell);
    let thickness = select(min(params.thickness, z2 - z), params.thickness, is_background(z2));
    return hemisphere_inside(q, cell, z, thickness);
}

fn source_lookup(p: EstimatorPixel, s: EstimatorSample) -> DepthLookup {
    var l: DepthLookup;
    l.value = 1.0;
    l.trace = false;
    l.px = s.px;
    l.t_after = 0.0;
    let steps = f32(params.steps);
    for (var k = 0u; k < params.steps; k++) {
        let t = params.radius * (f32(k) + p.jitter) / steps;
        let q = p.pos + s.dir * t;
        if (!ORTHOGRAPHIC && q.z >= 0.0) {
            break;
        }
        let px = view_to_pixel(view, q);
        if (any(px < vec2<f32>(0.0)) || any(px >= vec2<f32>(view.full_size))) {
            break;
        }
        let cell = vec2<u32>(px);
        if (all(cell == p.pixel)) {
            continue;
        }
        let z = textureLoad(depth_tex, cell, 0).r;
        if (!is_background(z) && screen_rays_inside(q, cell, z)) {
            l.value = hemisphere_blocked_at(t);
            l.px = vec2<f32>(cell) + 0.5;
            break;
        }
    }
    return l;
}

// The march decides every ray.
fn source_resolve(p: EstimatorPixel, s: EstimatorSample, l: DepthLookup) -> EstimatorValue {
    return l.value;
}

fn source_request(l: DepthLookup) {}
