// The interleaved schedule's first pass (docs/AUTHORS_CODE.md §1.7: the authors' HBAO+
// "DeinterleaveTexture"): the framebuffer's linear depth split into 16 quarter-resolution layers,
// layer x % 4 + 4 (y % 4) holding the pixels (4u + x % 4, 4v + y % 4). A layer texel past the
// framebuffer is background. One invocation per layer texel position (u, v): it reads the 4×4 block
// at (4u, 4v), 16 bytes per row, and writes one texel of every layer, so reads and writes stay
// coalesced across a warp (one invocation per layer texel, reading with a stride of 4, took
// 0.031 ms at 1080p + 64 on an H200).

@group(0) @binding(0) var depth: texture_2d<f32>;
@group(0) @binding(1) var layers: texture_storage_2d_array<r32float, write>;

@compute @workgroup_size(32, 4, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if (any(id.xy >= textureDimensions(layers))) {
        return;
    }
    let size = textureDimensions(depth);
    for (var j = 0u; j < 4u; j++) {
        for (var i = 0u; i < 4u; i++) {
            let pixel = id.xy * 4u + vec2<u32>(i, j);
            var z = 0.0;
            if (all(pixel < size)) {
                z = textureLoad(depth, pixel, 0).r;
            }
            textureStore(layers, id.xy, i + 4u * j, vec4<f32>(z));
        }
    }
}
