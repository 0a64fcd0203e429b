// Debug read-back of the stochastic depth map (multisampled textures cannot be copied to a
// buffer): one sample layer (map `layer.x`, sample `layer.y`) of the whole framebuffer as linear
// depth, 0 = empty. Preceded by the generated bindings of src/sources/stochastic_depth/mod.rs; the
// map binds as the source group, this pass's own layer and output as the schedule group.

@group(GROUP_SOURCE) @binding(SOURCE_SD_NEAR) var<uniform> sd_near: vec4<f32>;
@group(GROUP_SCHEDULE) @binding(UNPACK_LAYER) var<uniform> layer: vec4<u32>;
@group(GROUP_SCHEDULE) @binding(UNPACK_OUT) var<storage, read_write> unpacked: array<f32>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(sd_map_0);
    if (any(id.xy >= size)) {
        return;
    }
    let v = sd_load(layer.x, id.xy, layer.y);
    unpacked[id.y * size.x + id.x] = select(0.0, sd_near.x / v, v > 0.0);
}
