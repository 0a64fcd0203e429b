// Resetting the stochastic depth map for a frame (src/sources/stochastic_depth/reset.rs). Appended
// to map.wgsl (its bindings). Two passes (timed `sd_clear` and `sd_reset`):
// - a compute pass (the shared zero fill, common/zero_fill.wgsl) empties every pixel's S depths
//   in `sd_depths`;
// - a full-screen triangle, one fragment per pixel, writes the depth the map's early depth test
//   compares with: the hardware depth of the point `separation` behind the first layer, so that
//   only fragments behind it are shaded (0 where the pixel shows no surface: nothing is stored
//   there). `fs_reset_requested` (SD-SVAO with the stencil, seed 000 §3.9) writes it, and the
//   frame's stencil value, only at the pixels phase 1 requested, as the authors copy the request
//   mask into the stencil with a full-screen pass (docs/AUTHORS_CODE.md §1.5).
//   `fs_reset_requested_by_depth` (`--sd-mask depth`) puts the mask into the depth instead: the far
//   plane where nobody requested the pixel, so the same early test that skips the first layer skips
//   those pixels, with no stencil and no `discard` (a shader that may discard writes its depth
//   late, and costs more).
// A map that keeps every layer needs no depth: its pass clears the target to 1 (all pass).
// Emptying the map in the fragment pass too measured 1.0 ms on the H200 at 1080p + 64 px
// (BENCHMARKS.md, issue 16); compute does it in a fraction.

// The early test may only skip fragments the shader would drop: the written depth is moved this
// far (relative) towards the camera, past any difference between this expression and the
// rasteriser's interpolated depth (a few ulps).
const SD_CULL_MARGIN: f32 = 1.0e-5;
// Two steps of a fixed-point target's depth (0 for a float target): whatever way the written
// value and the fragments' depths are rounded to it, a fragment behind the point still tests
// behind what is stored.
override SD_CULL_QUANTUM: f32 = 0.0;

@vertex
fn vs_full_screen(@builtin(vertex_index) vertex: u32) -> @builtin(position) vec4<f32> {
    let uv = vec2<f32>(f32((vertex << 1u) & 2u), f32(vertex & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0);
}

// The depth the map's fragments at map pixel `pixel` must lie behind: in the map's own band, the
// near plane (1: every layer is kept there).
fn sd_cull_depth(pixel: vec2<u32>) -> f32 {
    let first = sd_first_layer(pixel);
    if (SD_MAP_BAND && first < 0.0) {
        return 1.0;
    }
    if (!(first > 0.0)) {
        return 0.0;
    }
    // view_to_clip's depth for a point `separation` behind the first layer (the projection's z and
    // w rows do not depend on x and y).
    let clip = camera.projection * vec4<f32>(0.0, 0.0, -(first + sd.separation), 1.0);
    return min(clip.z / clip.w * (1.0 + SD_CULL_MARGIN) + SD_CULL_QUANTUM, 1.0);
}

@fragment
fn fs_reset_all(@builtin(position) position: vec4<f32>) -> @builtin(frag_depth) f32 {
    return sd_cull_depth(vec2<u32>(position.xy));
}

// Both loads before the test, as in fs_reset_requested_by_depth below.
@fragment
fn fs_reset_requested(@builtin(position) position: vec4<f32>) -> @builtin(frag_depth) f32 {
    let pixel = vec2<u32>(position.xy);
    let requested = sd_requested(pixel);
    let depth = sd_cull_depth(pixel);
    if (!requested) {
        discard;
    }
    return depth;
}

// Reversed Z: no fragment's depth is less than the far plane's 0, so the map's early test
// (`Less`) rejects every fragment at a pixel that holds it.
// Both loads are issued before either is tested: a branch on the mask before the first layer's
// load made the pass 0.298 ms against `fs_reset_all`'s 0.190 on Sponza (BENCHMARKS.md, issue 16).
@fragment
fn fs_reset_requested_by_depth(@builtin(position) position: vec4<f32>) -> @builtin(frag_depth) f32 {
    let pixel = vec2<u32>(position.xy);
    let requested = sd_requested(pixel);
    return select(0.0, sd_cull_depth(pixel), requested);
}
