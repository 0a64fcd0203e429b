// The interleaved schedule's first pass (seed-code-notes §1.7: the authors' HBAO+ "DeinterleaveTexture"):
// the framebuffer's linear depth split into 16 quarter-resolution layers, layer x % 4 + 4 (y % 4)
// holding the pixels (4u + x % 4, 4v + y % 4). A layer texel past the framebuffer is background.

@group(0) @binding(0) var depth: texture_2d<f32>;
@group(0) @binding(1) var layers: texture_storage_2d_array<r32float, write>;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if (any(id.xy >= textureDimensions(layers))) {
        return;
    }
    let pixel = id.xy * 4u + vec2<u32>(id.z % 4u, id.z / 4u);
    var z = 0.0;
    if (all(pixel < textureDimensions(depth))) {
        z = textureLoad(depth, pixel, 0).r;
    }
    textureStore(layers, id.xy, id.z, vec4<f32>(z));
}
