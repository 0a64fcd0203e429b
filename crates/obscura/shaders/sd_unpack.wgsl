// Debug read-back of the stochastic depth map (multisampled textures cannot be copied to a
// buffer): one sample layer (map `layer.x`, sample `layer.y`) of the whole framebuffer as linear
// depth, 0 = empty. Preceded by the generated bindings of src/raster/stochastic_depth.rs.

@group(0) @binding(5) var<uniform> sd_near: vec4<f32>;
@group(1) @binding(0) var<uniform> layer: vec4<u32>;
@group(1) @binding(1) var<storage, read_write> unpacked: array<f32>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(sd_map_0);
    if (any(id.xy >= size)) {
        return;
    }
    let v = sd_load(layer.x, id.xy, layer.y);
    unpacked[id.y * size.x + id.x] = select(0.0, sd_near.x / v, v > 0.0);
}
