// The single-pass schedule's entry point (single.wgsl holds the loop and the store).

@compute @workgroup_size(32, 8)
fn main(@builtin(global_invocation_id) global_id: vec3<u32>) {
    let id = global_id.xy;
    if (any(id >= view.visible_size)) {
        return;
    }
    store_pixel(id, estimator_pixel(id));
}
