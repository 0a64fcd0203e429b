// The ray-traced stochastic depth source's request (the source contract's `source_request`):
// phase 1 marks the sample's pixel, as for the rasterised map (stochastic_depth/request.wgsl),
// and with ray intervals (seed 002 §3.2) widens that pixel's depth interval to hold the sample's
// (`l.interval`, set by read.wgsl's source_lookup when SD_INTERVALS is on). Both per map texel
// (`sd_texel`, from the generated bindings; the map's guard band included, seed 002 §3.5), what
// the map's rays read. The interval is two u32: the complement of the nearest depth's bits (an
// atomic max of the complement is a min, and a cleared 0 means "none") and the farthest depth's
// bits; non-negative floats order as their bits do.

@group(GROUP_SOURCE) @binding(SOURCE_SD_REQUEST) var<storage, read_write> sd_request: array<u32>;
@group(GROUP_SOURCE) @binding(SOURCE_SD_INTERVAL) var<storage, read_write> sd_interval: array<atomic<u32>>;

fn source_request(l: DepthLookup) {
    let i = sd_texel(vec2<i32>(floor(l.px)));
    sd_request[i] = 1u;
    if (SD_INTERVALS) {
        atomicMax(&sd_interval[2u * i], ~bitcast<u32>(max(l.interval.x, 0.0)));
        atomicMax(&sd_interval[2u * i + 1u], bitcast<u32>(max(l.interval.y, 0.0)));
    }
}
