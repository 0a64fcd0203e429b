// Stenciled stochastic depth map (seed 000 §3.9, Fig. 8; seed-code-notes §1.3/1.5): a full-screen
// pass copies phase 1's SD-request mask into the stencil of the multisampled map (1 where a
// pixel was requested, every sample), so the scene is then rasterised only there. The authors
// copy with a pass rather than a resource copy because the latter "results in a slow stencil".

// One u32 per framebuffer pixel (guard band included), row-major; non-zero = requested.
@group(0) @binding(0) var<storage, read> sd_request: array<u32>;
@group(0) @binding(1) var<uniform> full_width: vec4<u32>;

@vertex
fn vs_full_screen(@builtin(vertex_index) vertex: u32) -> @builtin(position) vec4<f32> {
    // One triangle over the whole target.
    let uv = vec2<f32>(f32((vertex << 1u) & 2u), f32(vertex & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0);
}

@fragment
fn fs_stencil_copy(@builtin(position) position: vec4<f32>) {
    let pixel = vec2<u32>(position.xy);
    if (sd_request[pixel.y * full_width.x + pixel.x] == 0u) {
        discard;
    }
}
