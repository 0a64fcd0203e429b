// An engine's depth buffer (hardware depth: NDC z in [0, 1], reversed-Z or not, finite or
// infinite far plane, perspective or orthographic) into the linear view depth every AO pass reads
// (src/engine_input.rs). The projection is undone per pixel through its inverse, so every one of
// those conventions is the same code. Needs common/view.wgsl in front.

struct EngineDepth {
    // Inverse of the engine's projection: clip space to view space.
    clip_to_view: mat4x4<f32>,
    // The depth the engine clears to (1, or 0 with reversed-Z): no geometry.
    far_clear: f32,
    _pad0: f32,
    _pad1: f32,
    _pad2: f32,
}

@group(0) @binding(0) var<uniform> params: EngineDepth;
@group(0) @binding(1) var<uniform> view: View;
// Depth32Float, Depth24Plus, Depth16Unorm or R32Float holding NDC z.
@group(0) @binding(2) var depth_in: texture_2d<f32>;
@group(0) @binding(3) var depth_out: texture_storage_2d<r32float, write>;

@compute @workgroup_size(32, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if (any(id.xy >= view.full_size)) {
        return;
    }
    let d = textureLoad(depth_in, id.xy, 0).r;
    var z = 0.0;
    if (d != params.far_clear) {
        let px = vec2<f32>(id.xy) + 0.5;
        let ndc = vec2<f32>(px.x * view.ndc_per_pixel.x - 1.0, 1.0 - px.y * view.ndc_per_pixel.y);
        let p = params.clip_to_view * vec4<f32>(ndc, d, 1.0);
        let linear = -p.z / p.w;
        // Behind the camera, at infinity or NaN: background (NaN fails both comparisons).
        z = select(0.0, linear, linear > 0.0 && linear < 3.0e38);
    }
    textureStore(depth_out, id.xy, vec4<f32>(z, 0.0, 0.0, 0.0));
}
