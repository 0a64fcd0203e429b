// Copies obscura's AO (r32float, 1 = unoccluded) into the texture Bevy's PBR lighting reads for
// screen-space ambient occlusion, whose format Bevy picks per adapter (r16float where it can be
// a storage texture, else r32float): `AO_FORMAT` is replaced by that format's name.

@group(0) @binding(0) var ao: texture_2d<f32>;
@group(0) @binding(1) var bevy_ao: texture_storage_2d<AO_FORMAT, write>;

@compute @workgroup_size(8, 8)
fn copy_ao(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(bevy_ao);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    textureStore(bevy_ao, id.xy, vec4(textureLoad(ao, id.xy, 0).r, 0.0, 0.0, 1.0));
}
