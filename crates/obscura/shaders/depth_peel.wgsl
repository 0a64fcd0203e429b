// Depth peeling (seed 000 §2.1; seed-code-notes §2.1): the scene again, keeping per pixel the
// nearest surface that lies more than `separation` behind the first layer (linear depth compare, as
// the authors' 2024 code). Appended to gbuffer.wgsl: same vertices, alpha test and culling.

struct PeelParams {
    separation: f32,
    _pad0: f32,
    _pad1: f32,
    _pad2: f32,
}

@group(0) @binding(6) var first_layer: texture_2d<f32>;
@group(0) @binding(7) var<uniform> peel: PeelParams;

@fragment
fn fs_peel(in: VertexOut) -> @location(0) f32 {
    let material = materials[in.material];
    if (!material_passes_alpha(material, textures, in.uv)) {
        discard;
    }
    let depth = -in.view_pos.z;
    let first = textureLoad(first_layer, vec2<u32>(in.clip.xy), 0).r;
    // Background in the first layer means nothing is there at all; the first layer itself and
    // anything within `separation` behind it is peeled away.
    if (!(first > 0.0) || depth <= first + peel.separation) {
        discard;
    }
    return depth;
}
