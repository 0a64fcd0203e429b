// Resetting the stochastic depth map for a frame (src/raster/sd_reset.rs). A full-screen triangle
// at reversed-Z depth 0 (= empty) is drawn with the depth test off and depth writes on:
// - `fs_reset_all`: every pixel (`sd-vao`'s full map);
// - `fs_reset_requested`: only the pixels phase 1 requested (`sd-svao`, seed 000 §3.9), which
//   also writes the frame's stencil value there when the map is stenciled (seed-code-notes §1.5:
//   the authors copy the request mask into the stencil with a full-screen pass too).
// Unrequested pixels keep what earlier frames left: nothing reads them (phase 2 reads the map only
// at requested pixels) and the stencil value changes every frame, so they are not drawn into. A
// depth-stencil clear would reset everything, but on the H100 clearing a 4x target costs more
// than drawing the whole map into it (BENCHMARKS.md).

// One u32 per framebuffer pixel (guard band included), row-major; non-zero = requested.
@group(0) @binding(0) var<storage, read> sd_request: array<u32>;
@group(0) @binding(1) var<uniform> full_width: vec4<u32>;

@vertex
fn vs_full_screen(@builtin(vertex_index) vertex: u32) -> @builtin(position) vec4<f32> {
    // One triangle over the whole target, at depth 0.
    let uv = vec2<f32>(f32((vertex << 1u) & 2u), f32(vertex & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0);
}

@fragment
fn fs_reset_all() {}

@fragment
fn fs_reset_requested(@builtin(position) position: vec4<f32>) {
    let pixel = vec2<u32>(position.xy);
    if (sd_request[pixel.y * full_width.x + pixel.x] == 0u) {
        discard;
    }
}
