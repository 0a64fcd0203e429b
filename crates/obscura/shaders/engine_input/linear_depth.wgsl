// An engine's hardware depth (NDC z in [0, 1], reversed-Z or not, finite or infinite far plane,
// perspective or orthographic) as the linear view depth every AO pass reads
// (src/engine_input.rs). The projection is undone per pixel through its inverse, so every one of
// those conventions is the same code. Included by depth.wgsl and normals.wgsl; needs
// common/view.wgsl in front.

struct EngineDepth {
    // Inverse of the engine's projection: clip space to view space.
    clip_to_view: mat4x4<f32>,
    // The depth the engine clears to (1, or 0 with reversed-Z): no geometry.
    far_clear: f32,
    _pad0: f32,
    _pad1: f32,
    _pad2: f32,
}

// The linear view depth of `pixel` whose engine depth is `d`; 0 = background.
fn engine_linear_depth(params: EngineDepth, view: View, pixel: vec2<u32>, d: f32) -> f32 {
    if (d == params.far_clear) {
        return 0.0;
    }
    let px = vec2<f32>(pixel) + 0.5;
    let ndc = vec2<f32>(px.x * view.ndc_per_pixel.x - 1.0, 1.0 - px.y * view.ndc_per_pixel.y);
    let p = params.clip_to_view * vec4<f32>(ndc, d, 1.0);
    let linear = -p.z / p.w;
    // Behind the camera, at infinity or NaN: background (NaN fails both comparisons).
    return select(0.0, linear, linear > 0.0 && linear < 3.0e38);
}
