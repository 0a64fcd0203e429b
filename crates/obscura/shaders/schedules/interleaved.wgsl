// Schedule "interleaved" (docs/AUTHORS_CODE.md §1.7, the authors' HBAO+: NVIDIA's interleaved
// rendering): the AO runs layer by layer over the 16 quarter-resolution depth layers of
// interleaved_split.wgsl. A pixel's samples read only its own layer, the framebuffer pixels of its
// residue class (x % 4, y % 4): each sample takes the class's pixel nearest to where the estimator
// put it, so a workgroup's fetches stay within a quarter-size texture (the cache-friendliness the
// technique exists for), and sample offsets become multiples of 4 px. Every pixel of a layer shares
// the pattern entry of the 4×4 Bayer table, so "one jitter per layer" holds by construction.
//
// The sample loop and the store are single.wgsl's; this file is the source they consult in the
// first layer's place (the table allows no other source), reading the pixel's own layer, and the
// entry point that walks the layers (src/schedules/interleaved.rs composes it without the row's
// source file).

@group(GROUP_SCHEDULE) @binding(SCHEDULE_DEPTH_LAYERS) var depth_layers: texture_2d_array<f32>;

// The first layer's answer for sample `s` of pixel `p`, from the pixel's own layer.
fn source_lookup(p: EstimatorPixel, s: EstimatorSample) -> DepthLookup {
    var l: DepthLookup;
    l.value = estimator_unoccluded(p, s);
    l.trace = false;
    l.t_after = 0.0;
    let own = estimator_shading_pixel(p);
    let residue = own % 4u;
    let size = vec2<f32>(textureDimensions(depth_layers).xy);
    let cell = vec2<u32>(clamp(
        round((estimator_sample_px(p, s) - 0.5 - vec2<f32>(residue)) / 4.0),
        vec2<f32>(0.0),
        size - 1.0,
    ));
    let pixel = cell * 4u + residue;
    l.px = vec2<f32>(pixel) + 0.5;
    if (all(pixel == own)) {
        return l;
    }
    let z = textureLoad(depth_layers, cell, residue.x + 4u * residue.y, 0).r;
    if (!is_background(z)) {
        l.value = estimator_occluder_at(p, s, l.px, z).value;
    }
    return l;
}

fn source_resolve(p: EstimatorPixel, s: EstimatorSample, l: DepthLookup) -> EstimatorValue {
    return l.value;
}

fn source_request(l: DepthLookup) {}

// One invocation per framebuffer pixel of layer `id.z`, (4x, 4y) + its residue; the guard band
// and what lies past the visible image are skipped.
@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let pixel = gid.xy * 4u + vec2<u32>(gid.z % 4u, gid.z / 4u);
    let guard = vec2<u32>(view.guard_band);
    if (any(pixel < guard) || any(pixel - guard >= view.visible_size)) {
        return;
    }
    let id = pixel - guard;
    store_pixel(id, estimator_pixel(id));
}
