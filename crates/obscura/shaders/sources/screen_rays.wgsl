// Hidden-depth source "screen rays" (`hemisphere`): each hemisphere ray marched in screen space
// over the first depth layer, the screen-space ray-traced AO engines ship. `steps` points evenly
// spaced along the ray within R (a per-pixel jitter shifts them) are projected to the frame; the
// ray is blocked at the first point that lies inside a surface: behind the tangent plane of the
// surface the depth buffer shows there, and less than `thickness` behind it (the depth buffer
// says nothing of what lies farther behind, so a thickness stands in for it). A ray that leaves
// the frame or passes behind the near plane is free from there on. Reads the hemisphere
// estimator's rays: a hemisphere-only source (src/technique.rs says so).
// What lies behind the first layer is the variant's, in front of this file:
// screen_rays_first.wgsl (`hemisphere`: nothing known), screen_rays_dual.wgsl (`hemisphere-dual`:
// a second layer) and screen_rays_stochastic.wgsl (`sd-hemisphere`, `ray-sd-hemisphere`: every
// depth of a stochastic depth map). Each defines `screen_rays_inside(q, cell, z)`, whether `q`
// lies inside a surface at framebuffer pixel `cell` whose first layer is at linear depth `z`,
// and `screen_rays_band_inside(q, pixel)` for a pixel off the framebuffer: 1 inside, 0 free,
// −1 where it knows nothing there (the ray is free from there on).
// The source contract: see first_layer.wgsl.

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
            // Clamped first: a point near the camera plane projects arbitrarily far.
            let pixel = vec2<i32>(floor(clamp(px, vec2<f32>(-1.0e6), vec2<f32>(1.0e6))));
            let band = screen_rays_band_inside(q, pixel);
            if (band < 0) {
                break;
            }
            if (band > 0) {
                l.value = hemisphere_blocked_at(t);
                l.px = vec2<f32>(pixel) + 0.5;
                break;
            }
            continue;
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
