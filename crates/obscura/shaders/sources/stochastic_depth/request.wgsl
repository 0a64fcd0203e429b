// The stochastic depth source's request (the source contract's `source_request`) for the
// rasterised map; the ray-traced map has its own (ray_stochastic_depth/request.wgsl).

// Two-phase phase 1: mark the sample's pixel (not the shading pixel) so the map is rasterised there
// (seed 000 §3.9). One u32 per framebuffer pixel; every writer stores 1.
@group(GROUP_SOURCE) @binding(SOURCE_SD_REQUEST) var<storage, read_write> sd_request: array<u32>;

fn source_request(l: DepthLookup) {
    let pixel = vec2<u32>(l.px);
    sd_request[pixel.y * view.full_size.x + pixel.x] = 1u;
}
