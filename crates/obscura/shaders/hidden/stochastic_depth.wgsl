// Hidden-depth source "stochastic depth" (SD-VAO, seed 000 §3.7; seed-code-notes §1.2/1.3): as
// dual_depth.wgsl, but a sample whose first surface is occluded (beyond the constant area) reads
// every sample of the stochastic depth map at the sample's pixel (seed 001 §3.1; made by
// shaders/stochastic_depth.wgsl) and keeps the lowest visibility of all of them.
//
// Preceded by bindings generated in src/raster/stochastic_depth.rs (WGSL cannot index an array of
// multisampled textures): the SD_MAPS maps of SD_SAMPLES samples each, read by
// `fn sd_load(map: u32, pixel: vec2<u32>, s: u32) -> f32` (reversed-Z: near / linear depth,
// 0 = empty).

// The projection's near plane (the first member of stochastic_depth.wgsl's SdRaster).
@group(0) @binding(5) var<uniform> sd_near: vec4<f32>;

// `trace` = read the stochastic depth map at pixel `px`; the two-phase kernel's phase 1 flags
// exactly these samples.
fn depth_lookup(f: VaoFrame, c: VaoColumn) -> DepthLookup {
    return depth_buffer_lookup(f, c);
}

// The lowest visibility over the first surface (`l.free`) and every stored stochastic sample.
fn resolve_hidden(f: VaoFrame, c: VaoColumn, l: DepthLookup) -> f32 {
    let pixel = vec2<u32>(l.px);
    var visibility = l.free;
    for (var m = 0u; m < SD_MAPS; m++) {
        for (var s = 0u; s < SD_SAMPLES; s++) {
            let v = sd_load(m, pixel, s);
            if (v > 0.0) {
                let p = pixel_to_view(view, l.px, sd_near.x / v);
                visibility = min(visibility, column_visibility(column_height(f, c, p), c.start, c.end));
            }
        }
    }
    return visibility;
}

fn sample_free_length(f: VaoFrame, c: VaoColumn) -> f32 {
    let l = depth_lookup(f, c);
    if (!l.trace) {
        return l.free;
    }
    return resolve_hidden(f, c, l);
}

// Two-phase kernel, phase 1: mark the sample's pixel (not the shading pixel) so the map is
// rasterised there (seed 000 §3.9). One u32 per framebuffer pixel; every writer stores 1.
@group(2) @binding(3) var<storage, read_write> sd_request: array<u32>;

fn request_hidden(l: DepthLookup) {
    let pixel = vec2<u32>(l.px);
    sd_request[pixel.y * view.full_size.x + pixel.x] = 1u;
}
