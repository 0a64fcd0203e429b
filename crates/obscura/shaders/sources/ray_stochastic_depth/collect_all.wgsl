// Entry point of the ray-traced map's collection (collect.wgsl) where every texel is traced (the
// one-pass rows): one invocation per texel in 8×8 workgroups. (Packed tiles measured 4–9 %
// slower here, where there is nothing to pack.)

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if (any(id.xy >= params.map_size)) {
        return;
    }
    // Rows with requests run collect_requested.wgsl; the test keeps this entry point right for
    // any caller (and the request binding in its layout, which both pipelines share).
    if (params.requested_only != 0u && sd_request[id.y * params.map_size.x + id.x] == 0u) {
        return;
    }
    collect_texel(id.xy);
}
