// The engine's depth buffer into linear view depth (src/engine_input.rs), for a frame whose
// normals are reconstructed from that depth (normals.wgsl's `main` reads it next; with the
// engine's own normals, normals.wgsl's `main_fused` writes the depth itself). Needs
// common/view.wgsl and engine_input/linear_depth.wgsl in front.

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
    let z = engine_linear_depth(params, view, id.xy, textureLoad(depth_in, id.xy, 0).r);
    textureStore(depth_out, id.xy, vec4<f32>(z, 0.0, 0.0, 0.0));
}
