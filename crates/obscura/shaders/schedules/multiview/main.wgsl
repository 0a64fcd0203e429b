// Multi-view (seed 001 §3.4, Algorithm 3, line 5), the second view's entry point: per visible pixel
// of the camera, the estimator's AO in the second view (single.wgsl's loop), and the output the
// lower of it and the camera's own AO: the larger occlusion of the two views (both sum the same
// N_d · N_s samples, so the maximum occlusion is the minimum AO).

@group(GROUP_SCHEDULE) @binding(0) var main_ao: texture_2d<f32>;

@compute @workgroup_size(32, 8)
fn main(@builtin(global_invocation_id) global_id: vec3<u32>) {
    let id = global_id.xy;
    if (any(id >= multiview.main.visible_size)) {
        return;
    }
    let own = textureLoad(main_ao, id, 0).r;
    let p = estimator_pixel(id);
    var second = 1.0;
    if (estimator_pixel_valid(p)) {
        second = estimator_finish(p, single_pass_accum(p));
    }
    textureStore(ao_out, id, vec4<f32>(min(own, second)));
}
