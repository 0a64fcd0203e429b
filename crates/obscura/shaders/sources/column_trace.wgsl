// Column rays (RT-VAO, seed 000 §3.6 and Fig. 6; docs/AUTHORS_CODE.md §1.6), the tracing half: when
// the depth buffer says a sample is occluded (its first surface lies beyond the constant area,
// i.e. in the falloff or above it; or anywhere, where the tangent-plane height correction makes
// deeper surfaces rise — see depth_lookup), or the sample falls outside the framebuffer, the camera ray
// through the sample's pixel is traced through the scene's BVH over the heights that can still
// lower the visibility, past the depth-buffer hit, and the sample takes the minimum of the
// per-hit visibilities. The result equals the `vao` ground-truth model (src/reference).
// Reads the VAO estimator's columns: a VAO-only source (src/technique.rs says so).
//
// Needs common/material.wgsl, common/bvh.wgsl and sources/ray_camera.wgsl in front. The source
// functions are in column_rays.wgsl (depth buffer first) or all_layers.wgsl (the ground truth).

// State of the ray being traced, read by bvh_on_hit.
var<private> trace_halo_start: f32;
var<private> trace_column: VaoColumn;
var<private> trace_height_at_0: f32;
var<private> trace_height_slope: f32;
var<private> trace_visibility: f32;

fn bvh_on_hit(hit: BvhHit) -> u32 {
    let height = trace_height_at_0 + trace_height_slope * hit.t;
    trace_visibility = min(trace_visibility, column_visibility(trace_halo_start, height, trace_column.start, trace_column.end));
    return select(BVH_CONTINUE, BVH_STOP, trace_visibility <= 0.0);
}

// Minimum visibility of `c` over the surfaces along the camera ray through framebuffer pixel
// coordinates `px`, beyond ray parameter `t_after` (the ray parameter is linear view depth).
fn trace_column_visibility(f: VaoFrame, c: VaoColumn, px: vec2<f32>, t_after: f32, start_vis: f32) -> f32 {
    let dir_view = pixel_to_view(view, px, 1.0);
    // Along the ray the view-space point is t * dir_view, so the column height is affine in t:
    // only heights in (end, halo end) can lower the visibility; that bounds the interval.
    let a = column_height(f, c, vec3<f32>(0.0));
    let b = column_height_slope(f, dir_view);
    let halo_end = halo_start(f) + (c.start - c.end);
    var t_min = max(ray_camera.near, t_after);
    var t_max = 3.4e38;
    if (abs(b) > 1e-12) {
        let t0 = (c.end - a) / b;
        let t1 = (halo_end - a) / b;
        t_min = max(t_min, min(t0, t1));
        t_max = max(t0, t1);
    }
    trace_halo_start = halo_start(f);
    trace_column = c;
    trace_height_at_0 = a;
    trace_height_slope = b;
    trace_visibility = start_vis;
    if (t_min < t_max && start_vis > 0.0) {
        let origin = ray_camera.camera_to_world[3].xyz;
        let dir = (ray_camera.camera_to_world * vec4<f32>(dir_view, 0.0)).xyz;
        bvh_stack_overflow = false;
        bvh_traverse(origin, dir, t_min, t_max);
        if (bvh_stack_overflow) {
            atomicAdd(&stack_overflows, 1u);
        }
    }
    return trace_visibility;
}

