// Stratified stochastic depth map (seed 001 §3.1, Alg. 1; the authors' raster pass,
// docs/AUTHORS_CODE.md §1.5). Appended to gbuffer.wgsl (same vertices, alpha test and culling) and
// common/hash.wgsl; reset.wgsl follows it.
//
// The map is a storage buffer of S depths per pixel (`sd_depths`, pixel-major, the layout the
// ray-traced map of seed 002 uses too): every fragment behind the first layer (more than
// `separation` behind the G-buffer's linear depth, the same rule as depth peeling) draws xi from a
// hash of its pixel pair, triangle and the map's seed (sd_fragment_hash says why a pair), is
// stored in R = floor(alpha * S + xi) samples (mean alpha * S), chosen by the pixel's own hash
// uniformly among the S-bit masks with R bits set (`sd_lut`: all masks sorted by popcount),
// and each chosen sample keeps the nearest fragment (`atomicMax` of the depth's bits: positive
// floats order as their bits do). That is Alg. 1's depth test per sample with every sample at
// the pixel centre, as the paper places them (programmable sample positions, which WebGPU
// lacks; the rasteriser runs at one sample per pixel, so the fragment is the pixel centre's).
//
// With `stochastic_depth.selection = "nearest"` (ours) the S depths are instead the pixel's S
// nearest hidden depths, by a k-buffer of atomics (sd_store_nearest): no hash, no α.
//
// Depth: the fragment's linear depth at the pixel centre (so the map stores positions, as the
// authors' code does, docs/AUTHORS_CODE.md §1.5), encoded as reversed-Z near / depth: float
// precision at any distance, no far plane needed, 0 = empty.
//
// Why not the multisampled depth target the paper draws into (our first map, BENCHMARKS.md,
// issue 16): a shader that writes depth and `sample_mask` is never depth- or stencil-tested before
// it runs, so the stencil of SD-SVAO saved nothing, and emptying a 4x target cost more than
// drawing colonnade into it. Here the pass writes no depth: reset.wgsl first writes, per pixel,
// the hardware depth of "first layer + separation" (for SD-SVAO the far plane, or the stencil,
// at the pixels nobody requested), and the map's fragment shaders run with forced early tests
// against it (`@early_depth_test(force)`, wgpu's SHADER_EARLY_DEPTH_TEST; removed from the source
// where the device lacks it), so fragments in front of the first layer and at unrequested
// pixels are never shaded. The shaders make every other decision themselves as well (the first
// layer, and the request mask where the early tests do not hold it): the early tests only skip
// work.

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
    // The map's width in pixels (`sd_depths` is row-major), its own guard band included.
    width: u32,
    // That band (`stochastic_depth.guard_band`, ours after seed 002 §3.5): the map's pixel p is
    // the framebuffer's p − band; in the band there is no first layer and every layer is kept.
    band: u32,
    // The framebuffer's size (the first layer's): a uniform read rather than a texture query
    // in every fragment of the band's reset and map.
    first_size: vec2<u32>,
    _pad: vec2<u32>,
}

@group(0) @binding(6) var first_layer: texture_2d<f32>;
@group(0) @binding(7) var<uniform> sd: SdRaster;
// [0, S + 1]: index in the mask list of the first mask with R bits (R = 0..S, then 2^S);
// from S + 2 on: all 2^S masks sorted by popcount.
@group(0) @binding(8) var<storage, read> sd_lut: array<u32>;
// S depths per pixel, pixel-major (reversed-Z bits, 0 = empty).
@group(0) @binding(9) var<storage, read_write> sd_depths: array<atomic<u32>>;
// SD-SVAO's request mask: one u32 per pixel of the map, row-major, non-zero = requested.
@group(0) @binding(10) var<storage, read> sd_request: array<u32>;

// Index of the first of `pixel`'s S depths in `sd_depths`.
fn sd_base(pixel: vec2<u32>) -> u32 {
    return (pixel.y * sd.width + pixel.x) * sd.samples;
}

// The fragment's hash: its pixel pair and triangle, and the map's seed. Seed 001 §3.1 hashes "the
// pixel location, sample index, and sample depth", and the authors' code the world position
// (docs/AUTHORS_CODE.md §1.5): both change with every move of the camera, so every hidden fragment
// drew new samples each frame and the map flickered in motion (BENCHMARKS.md, issue 13). The
// triangle tells the fragments of one pixel apart as the depth did (one fragment per triangle
// and pixel; instances have their own triangles), and it stays the same while a surface slides
// under the pixel, as the ray-traced map's hash of texel and triangle does. The pixel is the
// framebuffer's (map pixel − band), so the map's own band leaves the choices inside unchanged.
// One PCG round of a key, not a PCG round per input nested four deep: the fragments wait on
// that chain, and one round made the map pass 4.5 % faster on an H200 (BENCHMARKS.md, issue 16).
// The key, pixel index + triangle · 0x9E3779B9 (odd), differs for any two triangles at one
// pixel and any two pixels of one triangle, which is all the choices must tell apart (below,
// the index of the pair's left pixel, and the mask's hash tells the pair's pixels apart).
//
// The key is the pixel pair (x rounded down to even, y): both pixels of a pair draw the same ξ,
// so a triangle is stored in as many samples at both (sd_coverage; each pixel still draws its
// own samples, from sd_mask_hash). Why: on an H200 how the map's cost varies with its stores
// follows the 32-byte sectors a warp's atomic instruction touches (BENCHMARKS.md, issue 16). At
// S = 4 a sector holds a pixel pair's depths (where the map's width and band are even), and
// the second atomic of the fragments stored twice touches about half as many sectors when both
// pixels of a pair agree on it: whole maps 5-6 % faster. Each pixel's ξ is as uniform as
// before, so each pixel's map has Alg. 1's distribution; only neighbours' counts are tied.
// The sector count is a fit of this pixel-major map, not a law: a map in 2×2 quads with the
// quad's pixels choosing together halved the sectors and was slower, and without any atomics
// the pass still took 92 % of its time: the fragments are the cost (BENCHMARKS.md).
fn sd_fragment_hash(map_pixel: vec2<u32>, triangle: u32) -> u32 {
    let pixel = sd_frame_pixel(map_pixel) & vec2<u32>(~1u, ~0u);
    return pcg_hash((pixel.y * sd.first_size.x + pixel.x + triangle * 0x9E3779B9u) ^ sd.seed);
}

// The hash that picks the samples of the fragment of pixel pair hash `h` at map pixel
// `map_pixel`: another PCG round, of `h` for the pair's left pixel and of h ^ 1 for its right.
fn sd_mask_hash(map_pixel: vec2<u32>, h: u32) -> u32 {
    return pcg_hash(h ^ (sd_frame_pixel(map_pixel).x & 1u));
}

// The framebuffer pixel of map pixel `map_pixel` (they differ by the map's own band).
fn sd_frame_pixel(map_pixel: vec2<u32>) -> vec2<u32> {
    return select(map_pixel, map_pixel - vec2<u32>(sd.band), SD_MAP_BAND);
}

// What the map's triangles without an alpha test hand to their fragments: the linear depth and
// the triangle, as little as the G-buffer's visibility pass hands on. Why: with nothing shaded,
// the map pass drawing every triangle through `vs_main` (position, view position, texture
// coordinates, material, triangle) cost 1.21 ms on Sponza at 1080p on the H200, most of the
// pass (BENCHMARKS.md, issue 16). The alpha-tested triangles keep `vs_main`.
struct DepthVertex {
    @builtin(position) clip: vec4<f32>,
    // −z in view space, interpolated as `vs_main`'s view position is (perspective-correct): the
    // same linear depth at the pixel centre.
    @location(0) depth: f32,
    @location(1) @interpolate(flat) triangle: u32,
}

@vertex
fn vs_depth(@builtin(vertex_index) vertex: u32) -> DepthVertex {
    let t = drawn_triangle(vertex);
    let tri = triangles[t];
    let view_pos = to_view(positions[corner_index(tri, vertex)].xyz);
    var out: DepthVertex;
    out.clip = view_to_clip(view_pos);
    out.depth = -view_pos.z;
    out.triangle = t;
    return out;
}

// The G-buffer's linear depth at map pixel `pixel`, or −1 in the map's band (no first layer).
// SD_MAP_BAND (generated by src/sources/stochastic_depth/mod.rs: whether the map has a band)
// compiles the band's tests out of a map without one, whose shaders stay as they were.
fn sd_first_layer(pixel: vec2<u32>) -> f32 {
    if (!SD_MAP_BAND) {
        return textureLoad(first_layer, pixel, 0).r;
    }
    // Unsigned: a pixel left of or above the frame wraps past `first_size` too.
    let p = pixel - vec2<u32>(sd.band);
    if (any(p >= sd.first_size)) {
        return -1.0;
    }
    return textureLoad(first_layer, p, 0).r;
}

// Alg. 1 for one fragment that passed its alpha test, at map pixel `pixel` with linear
// `depth`: the samples it is stored in (0: none).
fn sd_coverage(pixel: vec2<u32>, depth: f32, triangle: u32) -> u32 {
    if (!sd_hidden(pixel, depth)) {
        return 0u;
    }
    let h = sd_fragment_hash(pixel, triangle);
    let xi = hash_to_unit(h);
    let count = min(u32(floor(sd.alpha * f32(sd.samples) + xi)), sd.samples);
    if (count == 0u) {
        return 0u;
    }
    // Uniform choice among the masks with `count` bits, from the pixel's own second hash's
    // 24-bit unit (a multiply rather than an integer division; at most C(16, 8) = 12,870
    // choices, so each is within 12,870 / 2^24 < 0.08 % of its share).
    let first_mask = sd_lut[count];
    let choices = sd_lut[count + 1u] - first_mask;
    let choice = min(u32(hash_to_unit(sd_mask_hash(pixel, h)) * f32(choices)), choices - 1u);
    return sd_lut[sd.samples + 2u + first_mask + choice];
}

// Alg. 1's depth test: each sample of `mask` keeps the nearest fragment.
fn sd_store(pixel: vec2<u32>, depth: f32, mask: u32) {
    let base = sd_base(pixel);
    let stored = bitcast<u32>(sd.near / depth);
    var left = mask;
    while (left != 0u) {
        atomicMax(&sd_depths[base + firstTrailingBit(left)], stored);
        left &= left - 1u;
    }
}

// `stochastic_depth.selection = "nearest"` (ours; SD_NEAREST, generated by
// src/sources/stochastic_depth/mod.rs): the pixel's S depths hold its S nearest distinct hidden
// depths, nearest first, instead of Alg. 1's stochastic choice. A k-buffer kept with atomics
// alone: the fragment's depth goes in at the first slot by `atomicMax`, and whatever it pushes
// out (the smaller, i.e. farther, of the two) goes on to the next slot, until an empty slot or
// an equal depth takes it or it falls off the last. Every step keeps each slot the larger of what
// was there and what arrives, so after all fragments the slots hold the S largest values in
// order whatever order the fragments came in: the map is deterministic, and exact where a pixel
// hides at most S layers. The last slot is read first: once it holds a nearer depth than the
// fragment's, no slot can take it (slots only grow), which spares most deep fragments the chain.
fn sd_store_nearest(pixel: vec2<u32>, depth: f32) {
    let base = sd_base(pixel);
    var v = bitcast<u32>(sd.near / depth);
    if (atomicLoad(&sd_depths[base + sd.samples - 1u]) >= v) {
        return;
    }
    for (var k = 0u; k < sd.samples; k++) {
        let previous = atomicMax(&sd_depths[base + k], v);
        if (previous == 0u || previous == v) {
            return;
        }
        v = min(previous, v);
    }
}

// Alg. 1 stores hidden layers only: the first layer (and anything within `separation` behind
// it) is skipped; without a first layer the pixel shows no geometry at all. In the map's own
// band every layer is kept, the first one included (read.wgsl reads it as the only layers).
fn sd_hidden(pixel: vec2<u32>, depth: f32) -> bool {
    let first = sd_first_layer(pixel);
    let in_band = SD_MAP_BAND && first < 0.0;
    return sd.all_layers != 0u || in_band || (first > 0.0 && depth > first + sd.separation);
}

fn sd_fragment(pixel: vec2<u32>, depth: f32, triangle: u32) {
    if (SD_NEAREST) {
        if (sd_hidden(pixel, depth)) {
            sd_store_nearest(pixel, depth);
        }
        return;
    }
    sd_store(pixel, depth, sd_coverage(pixel, depth, triangle));
}

// Whether SD-SVAO (seed 000 §3.9) asked for `pixel`. With the stencil or the depth mask
// (reset.wgsl) the early tests drop the other pixels before a shader runs; `--sd-mask discard`
// leaves it to this test.
fn sd_requested(pixel: vec2<u32>) -> bool {
    return sd_request[pixel.y * sd.width + pixel.x] != 0u;
}

@fragment @early_depth_test(force)
fn fs_stochastic_depth(in: DepthVertex) {
    sd_fragment(vec2<u32>(in.clip.xy), in.depth, in.triangle);
}

@fragment @early_depth_test(force)
fn fs_stochastic_depth_requested(in: DepthVertex) {
    let pixel = vec2<u32>(in.clip.xy);
    if (sd_requested(pixel)) {
        sd_fragment(pixel, in.depth, in.triangle);
    }
}

// Alpha-tested triangles: the texel decides first.
@fragment @early_depth_test(force)
fn fs_stochastic_depth_masked(in: VertexOut) {
    if (material_passes_alpha(materials[in.material], textures, in.uv)) {
        sd_fragment(vec2<u32>(in.clip.xy), -in.view_pos.z, in.triangle);
    }
}

@fragment @early_depth_test(force)
fn fs_stochastic_depth_masked_requested(in: VertexOut) {
    let pixel = vec2<u32>(in.clip.xy);
    if (sd_requested(pixel) && material_passes_alpha(materials[in.material], textures, in.uv)) {
        sd_fragment(pixel, -in.view_pos.z, in.triangle);
    }
}
