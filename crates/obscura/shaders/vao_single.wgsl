// The single-pass VAO kernel (`vao`, `rt-vao`): every sample of a pixel in one invocation, its
// occluder from the hidden-depth source in front (sample_free_length).

@compute @workgroup_size(32, 8)
fn main(@builtin(global_invocation_id) global_id: vec3<u32>) {
    let id = global_id.xy;
    if (any(id >= view.visible_size)) {
        return;
    }
    let p = vao_pixel(id);
    if (!p.valid) {
        textureStore(ao_out, id, vec4<f32>(1.0));
        return;
    }
    var sum = 0.0;
    var clipped_sum = 0.0;
    for (var i = 0u; i < SAMPLE_COUNT; i++) {
        let s = vao_sample(p, i);
        if (s.h == 0.0) {
            continue;
        }
        let inv_2h = 0.5 / s.h;
        sum += sample_free_length(p.frame, s.column) * inv_2h;
        clipped_sum += (s.column.start - s.column.end) * inv_2h;
    }
    textureStore(ao_out, id, vec4<f32>(vao_finish(sum, clipped_sum)));
}
