// The stochastic depth source's request (the source contract's `source_request`) for the
// rasterised map; the ray-traced map has its own (ray_stochastic_depth/request.wgsl).

// Two-phase phase 1: mark the sample's pixel (not the shading pixel) so the map is rasterised there
// (seed 000 §3.9). One u32 per pixel of the map (the framebuffer and the map's own band,
// `sd_request_cell` from the generated bindings); every writer stores 1.
@group(GROUP_SOURCE) @binding(SOURCE_SD_REQUEST) var<storage, read_write> sd_request: array<u32>;

fn source_request(l: DepthLookup) {
    sd_request[sd_request_cell(vec2<i32>(floor(l.px)))] = 1u;
}
