// Separable depth-aware (cross) bilateral blur of the AO image, as HBAO+ and the seed 000 §3.4
// use it (docs/AUTHORS_CODE.md §1.8): radius 4, Gaussian spatial weight with
// sigma = (radius + 1) / 2, and a depth weight exp2(-(dz * sharpness)^2) on the linear depth
// difference in world units, after removing the local depth slope so that tilted planes blur like
// flat ones.
// Only visible pixels are read: the AO image has no guard band, so taps outside it are skipped.
// Mirrored on the CPU by src/reference/cpu_blur.rs.
//
// Each workgroup blurs a run of 64 pixels along the blur direction in 8 neighbouring lines; the run
// plus `radius` pixels on each side is loaded once into workgroup memory, so each texel is read
// from memory about once instead of 2 * radius + 1 times. Its 64 × 4 invocations take two lines
// each, with all their loads in flight before the barrier: with one line each (4 lines a
// workgroup) the pass took 6 % longer on an H200, waiting on memory with too few loads
// outstanding; four lines each, or the two written as a loop over an array, were slower
// (BENCHMARKS.md).

struct BlurParams {
    // (1, 0) for the horizontal pass, (0, 1) for the vertical one.
    direction: vec2<i32>,
    // The spatial weight is exp2(-d² · falloff) (BlurSettings::falloff: HBAO+'s σ = (R + 1)/2 in
    // exp2 units, or a natural Gaussian of `blur.sigma`); RADIUS is the pipeline constant.
    falloff: f32,
    sharpness: f32,
}

@group(0) @binding(0) var<uniform> view: View;
@group(0) @binding(1) var<uniform> params: BlurParams;
@group(0) @binding(2) var depth_tex: texture_2d<f32>;
@group(0) @binding(3) var ao_in: texture_2d<f32>;
@group(0) @binding(4) var ao_out: texture_storage_2d<r32float, write>;

// Taps on each side: a pipeline constant, so the tap loop unrolls with constant spatial weights
// (the taps are about a third of the pass at radius 4 on an H200, BENCHMARKS.md).
override RADIUS: i32 = 4;

const RUN: i32 = 64;
const LINES: u32 = 8u;
const MAX_RADIUS: i32 = 16;
const TILE: i32 = 96; // RUN + 2 * MAX_RADIUS

var<workgroup> tile_ao: array<f32, 768>; // LINES * TILE
var<workgroup> tile_depth: array<f32, 768>;

// Image position of (distance along the blur direction, line index across it).
fn pixel_at(along: i32, across: i32) -> vec2<i32> {
    return select(vec2<i32>(along, across), vec2<i32>(across, along), params.direction.y != 0);
}

// (depth, AO) of the tile texel at `along` on line `across`.
fn tile_texel(along: i32, across: i32) -> vec2<f32> {
    let size = vec2<i32>(view.visible_size);
    let full = vec2<i32>(view.full_size);
    let q = pixel_at(along, across);
    // Depth exists in the guard band too; AO only inside the visible image (-1 = none).
    let zq = clamp(q + i32(view.guard_band), vec2<i32>(0), full - 1);
    let inside = all(q >= vec2<i32>(0)) && all(q < size);
    let ao = select(-1.0, textureLoad(ao_in, clamp(q, vec2<i32>(0), size - 1), 0).r, inside);
    return vec2<f32>(textureLoad(depth_tex, zq, 0).r, ao);
}

// Stores texel `t` (depth, AO) at index `k` of the tile's line `line`.
fn tile_store(line: i32, k: i32, t: vec2<f32>) {
    tile_depth[line * TILE + k] = t.x;
    tile_ao[line * TILE + k] = t.y;
}

// Blurs the texel at index `k` of the tile's line `line` (image line `across`, the tile starting
// at `start` along the blur direction) into the output image.
fn blur_texel(line: i32, k: i32, across: i32, start: i32) {
    let size = vec2<i32>(view.visible_size);
    let r = RADIUS;
    let p = pixel_at(start + k, across);
    if (any(p >= size)) {
        return;
    }
    let c = line * TILE + k;
    let center_ao = tile_ao[c];
    let z = tile_depth[c];
    if (is_background(z)) {
        textureStore(ao_out, p, vec4<f32>(center_ao));
        return;
    }
    // Depth slope along the blur direction: the smaller of the one-sided differences, so a depth
    // edge on one side does not masquerade as slope.
    let forward = tile_depth[c + 1] - z;
    let backward = z - tile_depth[c - 1];
    let slope = select(backward, forward, abs(forward) < abs(backward));

    let falloff = params.falloff;
    var sum = center_ao;
    var weight_sum = 1.0;
    for (var d = -r; d <= r; d++) {
        let ao = tile_ao[c + d];
        let zq = tile_depth[c + d];
        if (d == 0) {
            continue;
        }
        let dz = (zq - z - slope * f32(d)) * params.sharpness;
        // Taps outside the image (AO −1) or on the background weigh 0 by a select rather than a
        // branch (4 % faster on an H200, BENCHMARKS.md); w · ao is then ±0, the sums unchanged.
        let w = select(exp2(-f32(d * d) * falloff - dz * dz), 0.0, ao < 0.0 || is_background(zq));
        sum += w * ao;
        weight_sum += w;
    }
    // The normalised sum of values in [0, 1] can round past 1 (seen on an H200, RELIABILITY.md).
    textureStore(ao_out, p, vec4<f32>(min(sum / weight_sum, 1.0)));
}

// 64 × 4 invocations blur 8 lines, two each (lines local.y and local.y + 4), so that each has
// four loads in flight before the barrier rather than two. The two are written out: as a loop
// over an array they were slower (BENCHMARKS.md).
@compute @workgroup_size(64, 4)
fn main(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_id) local: vec3<u32>) {
    let r = RADIUS;
    let start = i32(group.x) * RUN - r;
    let line0 = i32(local.y);
    let line1 = line0 + i32(LINES / 2u);
    let across0 = i32(group.y * LINES) + line0;
    let across1 = i32(group.y * LINES) + line1;
    let k0 = i32(local.x);
    let k1 = k0 + RUN;
    let second = k1 < RUN + 2 * r;
    let a0 = tile_texel(start + k0, across0);
    let a1 = tile_texel(start + k0, across1);
    var b0 = vec2<f32>(0.0);
    var b1 = vec2<f32>(0.0);
    if (second) {
        b0 = tile_texel(start + k1, across0);
        b1 = tile_texel(start + k1, across1);
    }
    tile_store(line0, k0, a0);
    tile_store(line1, k0, a1);
    if (second) {
        tile_store(line0, k1, b0);
        tile_store(line1, k1, b1);
    }
    workgroupBarrier();
    blur_texel(line0, r + k0, across0, start);
    blur_texel(line1, r + k0, across1, start);
}
