// Resetting the stochastic depth map for a frame (src/sources/stochastic_depth/reset.rs). Appended
// to map.wgsl (its bindings). A full-screen triangle, one fragment per pixel, that
// - empties the pixel's S depths in `sd_depths`;
// - writes the depth the map's early depth test compares with: the hardware depth of the point
//   `separation` behind the first layer, so that only fragments behind it are shaded (0 where the
//   pixel shows no surface: nothing is stored there; 1, everything passes, for a map that keeps
//   every layer);
// - `fs_reset_requested` (SD-SVAO with the stencil, seed 000 §3.9): writes the frame's stencil
//   value only at the pixels phase 1 requested (it discards the others after emptying them), as
//   the authors copy the request mask into the stencil with a full-screen pass
//   (seed-code-notes §1.5).

// The early test may only skip fragments the shader would drop: the written depth is moved this
// far (relative) towards the camera, past any difference between this expression and the
// rasteriser's interpolated depth (a few ulps).
const SD_CULL_MARGIN: f32 = 1.0e-5;

@vertex
fn vs_full_screen(@builtin(vertex_index) vertex: u32) -> @builtin(position) vec4<f32> {
    let uv = vec2<f32>(f32((vertex << 1u) & 2u), f32(vertex & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0);
}

// Empty the pixel's depths; the depth the map's fragments must lie behind.
fn sd_reset_pixel(pixel: vec2<u32>) -> f32 {
    let base = sd_base(pixel);
    for (var k = 0u; k < sd.samples; k++) {
        atomicStore(&sd_depths[base + k], 0u);
    }
    if (sd.all_layers != 0u) {
        return 1.0;
    }
    let first = textureLoad(first_layer, pixel, 0).r;
    if (!(first > 0.0)) {
        return 0.0;
    }
    // view_to_clip's depth for a point `separation` behind the first layer (the projection's z and
    // w rows do not depend on x and y).
    let clip = camera.projection * vec4<f32>(0.0, 0.0, -(first + sd.separation), 1.0);
    return min(clip.z / clip.w * (1.0 + SD_CULL_MARGIN), 1.0);
}

@fragment
fn fs_reset_all(@builtin(position) position: vec4<f32>) -> @builtin(frag_depth) f32 {
    return sd_reset_pixel(vec2<u32>(position.xy));
}

@fragment
fn fs_reset_requested(@builtin(position) position: vec4<f32>) -> @builtin(frag_depth) f32 {
    let pixel = vec2<u32>(position.xy);
    let depth = sd_reset_pixel(pixel);
    if (sd_request[pixel.y * sd.width + pixel.x] == 0u) {
        discard;
    }
    return depth;
}
