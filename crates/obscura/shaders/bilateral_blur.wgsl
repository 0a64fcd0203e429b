// Separable depth-aware (cross) bilateral blur of the AO image, as HBAO+ and the seed 000 §3.4
// use it (seed-code-notes §1.8): radius 4, Gaussian spatial weight with sigma = (radius + 1) / 2,
// and a depth weight exp2(-(dz * sharpness)^2) on the linear depth difference in world units,
// after removing the local depth slope so that tilted planes blur like flat ones.
// Only visible pixels are read: the AO image has no guard band, so taps outside it are skipped.
// Mirrored on the CPU by src/reference/cpu_blur.rs.
//
// Each workgroup blurs a run of 64 pixels along the blur direction in 4 neighbouring lines; the run
// plus `radius` pixels on each side is loaded once into workgroup memory, so each texel is read
// from memory about once instead of 2 * radius + 1 times.

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
// (measured: the loop's arithmetic, not memory, bounds this pass).
override RADIUS: i32 = 4;

const RUN: i32 = 64;
const LINES: u32 = 4u;
const MAX_RADIUS: i32 = 16;
const TILE: i32 = 96; // RUN + 2 * MAX_RADIUS

var<workgroup> tile_ao: array<f32, 384>; // LINES * TILE
var<workgroup> tile_depth: array<f32, 384>;

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

@compute @workgroup_size(64, 4)
fn main(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_id) local: vec3<u32>) {
    let size = vec2<i32>(view.visible_size);
    let r = RADIUS;
    let start = i32(group.x) * RUN - r;
    let across = i32(group.y * LINES + local.y);
    let row = i32(local.y) * TILE;
    // RUN + 2r ≤ 2 RUN texels per line: each invocation loads its one or two texels before
    // storing either, so both loads are in flight together (a loop over them waited for each in
    // turn: 5 % slower on an H200, BENCHMARKS.md).
    let k0 = i32(local.x);
    let k1 = k0 + RUN;
    let second = k1 < RUN + 2 * r;
    let a = tile_texel(start + k0, across);
    var b = vec2<f32>(0.0);
    if (second) {
        b = tile_texel(start + k1, across);
    }
    tile_depth[row + k0] = a.x;
    tile_ao[row + k0] = a.y;
    if (second) {
        tile_depth[row + k1] = b.x;
        tile_ao[row + k1] = b.y;
    }
    workgroupBarrier();

    let p = pixel_at(start + r + i32(local.x), across);
    if (any(p >= size)) {
        return;
    }
    let c = row + r + i32(local.x);
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
        if (d == 0 || ao < 0.0 || is_background(zq)) {
            continue;
        }
        let dz = (zq - z - slope * f32(d)) * params.sharpness;
        let w = exp2(-f32(d * d) * falloff - dz * dz);
        sum += w * ao;
        weight_sum += w;
    }
    // The normalised sum of values in [0, 1] can round past 1 (seen on an H200, RELIABILITY.md).
    textureStore(ao_out, p, vec4<f32>(min(sum / weight_sum, 1.0)));
}
