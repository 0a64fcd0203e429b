// The single-pass schedule's entry point (single.wgsl holds the loop).

@compute @workgroup_size(32, 8)
fn main(@builtin(global_invocation_id) global_id: vec3<u32>) {
    let id = global_id.xy;
    if (any(id >= view.visible_size)) {
        return;
    }
    let p = estimator_pixel(id);
    if (!estimator_pixel_valid(p)) {
        textureStore(ao_out, id, vec4<f32>(1.0));
        return;
    }
    let acc = single_pass_accum(p);
    if (ESTIMATOR_DEBUG) {
        textureStore(ao_out, id, vec4<f32>(estimator_debug(p, acc)));
    } else {
        textureStore(ao_out, id, vec4<f32>(estimator_finish(p, acc)));
    }
}
