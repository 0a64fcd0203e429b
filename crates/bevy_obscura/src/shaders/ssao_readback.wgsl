// Copies a camera's SSAO texture (obscura's R32Float output, or Bevy's own R16Float/R32Float
// texture, which cannot be a copy source) into an R32Float texture that can be read back
// (src/readback.rs).

@group(0) @binding(0) var ao: texture_2d<f32>;
@group(0) @binding(1) var readable: texture_storage_2d<r32float, write>;

@compute @workgroup_size(8, 8)
fn copy_ao(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(readable);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    textureStore(readable, id.xy, vec4(textureLoad(ao, id.xy, 0).r, 0.0, 0.0, 1.0));
}
