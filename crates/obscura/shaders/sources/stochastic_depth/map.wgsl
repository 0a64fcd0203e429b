// Stratified stochastic depth map (seed 001 §3.1, Alg. 1; the authors' raster pass as recorded in
// seed-code-notes §1.5). Appended to gbuffer.wgsl (same vertices, alpha test and culling) and
// common/hash.wgsl.
//
// The target is a multisampled depth buffer of S samples per pixel. Every fragment behind the
// first layer (more than `separation` behind the G-buffer's linear depth, the same rule as depth
// peeling) draws xi from a hash of its pixel, triangle, depth and the map's seed, is stored in
// R = floor(alpha * S + xi) samples (mean alpha * S), chosen uniformly among the S-bit masks with R
// bits set (`sd_lut`: all masks sorted by popcount), and writes `@builtin(sample_mask)`; the depth
// test keeps the nearest fragment per sample.
//
// Depth: the shader writes the fragment's linear depth at the pixel centre (so the map stores
// positions, as the authors' code does, seed-code-notes §1.5), encoded as reversed-Z near / depth
// in a 32-bit float target: float precision at any distance, no far plane needed, 0 = empty.
//
// Sample positions: the paper puts all samples at the pixel centre (programmable sample
// positions), which WebGPU cannot. Here the rasteriser's standard pattern decides coverage, while
// the depth written is the pixel centre's for every sample (the shader runs once per pixel, at its
// centre). Inside a triangle a sample stores its pixel's fragment as in the paper; at a triangle
// edge it may take the neighbouring triangle of the same surface, which keeps every sample's
// chance of storing the surface at alpha but not the exact count R of one fragment.
//
// A shader-written depth turns the hardware's early depth test off. Measured on the H100
// (BENCHMARKS.md) the rasteriser's own depth (at the sample positions) made the map 9 % faster on
// Sponza and its errors larger (colonnade, MSE against the ground truth 2.1e-6 to 3.4e-6 instead
// of 0.9e-6 to 2.0e-6); we keep the positions exact.

struct SdRaster {
    // The projection's near plane: stored depth = near / linear depth (readers invert it).
    near: f32,
    alpha: f32,
    // Minimum distance behind the first layer (world units).
    separation: f32,
    seed: u32,
    // Samples per pixel of this map.
    samples: u32,
    // Non-zero: store every layer, the first visible one included (the multi-view schedule's
    // second map, seed 001 §3.4; its view has no first layer of its own).
    all_layers: u32,
    _pad1: u32,
    _pad2: u32,
}

@group(0) @binding(6) var first_layer: texture_2d<f32>;
@group(0) @binding(7) var<uniform> sd: SdRaster;
// [0, S + 1]: index in the mask list of the first mask with R bits (R = 0..S, then 2^S);
// from S + 2 on: all 2^S masks sorted by popcount.
@group(0) @binding(8) var<storage, read> sd_lut: array<u32>;

// The fragment's hash: pixel, triangle and depth (seed 001 §3.1: "using the pixel location,
// sample index, and sample depth"), and the map's seed.
fn sd_fragment_hash(pixel: vec2<u32>, triangle: u32, depth: f32) -> u32 {
    let h = pcg_hash(pixel.x ^ pcg_hash(pixel.y ^ pcg_hash(triangle ^ pcg_hash(bitcast<u32>(depth)))));
    return pcg_hash(h ^ sd.seed);
}

// Alg. 1 for one fragment: the samples it is stored in (0: none).
fn sd_coverage(in: VertexOut) -> u32 {
    let material = materials[in.material];
    if (!material_passes_alpha(material, textures, in.uv)) {
        return 0u;
    }
    let pixel = vec2<u32>(in.clip.xy);
    let depth = -in.view_pos.z;
    let first = textureLoad(first_layer, pixel, 0).r;
    // Alg. 1 stores hidden layers only: the first layer (and anything within `separation` behind
    // it) is skipped; without a first layer the pixel shows no geometry at all.
    if (sd.all_layers == 0u && (!(first > 0.0) || depth <= first + sd.separation)) {
        return 0u;
    }
    let h = sd_fragment_hash(pixel, in.triangle, depth);
    let xi = hash_to_unit(h);
    let count = min(u32(floor(sd.alpha * f32(sd.samples) + xi)), sd.samples);
    if (count == 0u) {
        return 0u;
    }
    // Uniform choice among the masks with `count` bits.
    let first_mask = sd_lut[count];
    let choices = sd_lut[count + 1u] - first_mask;
    return sd_lut[sd.samples + 2u + first_mask + pcg_hash(h) % choices];
}

struct SdOut {
    @builtin(frag_depth) depth: f32,
    @builtin(sample_mask) mask: u32,
}

// The stored samples with the pixel centre's depth.
fn sd_out(in: VertexOut, mask: u32) -> SdOut {
    var out: SdOut;
    out.depth = sd.near / -in.view_pos.z;
    out.mask = mask;
    return out;
}

@fragment
fn fs_stochastic_depth(in: VertexOut) -> SdOut {
    let mask = sd_coverage(in);
    if (mask == 0u) {
        discard;
    }
    return sd_out(in, mask);
}

// SD-SVAO without the stencil (`--sd-mask discard`): the fragment reads the SD-request mask itself
// and is dropped where it is not set, so no full-screen copy pass is needed (see
// sd_reset.wgsl for the paper's stencil). One u32 per framebuffer pixel, non-zero = requested.
@group(0) @binding(9) var<storage, read> sd_request: array<u32>;

@fragment
fn fs_stochastic_depth_requested(in: VertexOut) -> SdOut {
    let pixel = vec2<u32>(in.clip.xy);
    if (sd_request[pixel.y * textureDimensions(first_layer).x + pixel.x] == 0u) {
        discard;
    }
    let mask = sd_coverage(in);
    if (mask == 0u) {
        discard;
    }
    return sd_out(in, mask);
}
