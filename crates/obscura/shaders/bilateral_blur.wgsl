// Separable depth-aware (cross) bilateral blur of the AO image, as HBAO+ and the seed 000 §3.4
// use it (seed-code-notes §1.8): radius 4, Gaussian spatial weight with sigma = (radius + 1) / 2,
// and a depth weight exp2(-(dz * sharpness)^2) on the linear depth difference in world units,
// after removing the local depth slope so that tilted planes blur like flat ones. A horizontal
// pass, then a vertical pass over its result.
// Only visible pixels are read: the AO image has no guard band, so taps outside it are skipped.
// Mirrored on the CPU by src/reference/cpu_blur.rs.
//
// Both passes run in one dispatch (ours): each workgroup loads a block of 16×16 output pixels
// plus `RADIUS` on every side into workgroup memory once, runs the horizontal pass over the
// block's rows and the rows above and below it that the vertical taps reach, and the vertical pass
// over those results. The two passes each launched over the whole image and went through an
// intermediate image; the horizontal results of a block's top and bottom margins are made twice
// (by this block and its neighbour), which costs less at the default radius (BENCHMARKS.md). The
// result is the same as the two passes', bit for bit: each tap's arithmetic is unchanged.

struct BlurParams {
    // The spatial weight is exp2(-d² · falloff) (BlurSettings::falloff: HBAO+'s σ = (R + 1)/2 in
    // exp2 units, or a natural Gaussian of `blur.sigma`); RADIUS is the pipeline constant.
    falloff: f32,
    sharpness: f32,
    _pad0: f32,
    _pad1: f32,
}

@group(0) @binding(0) var<uniform> view: View;
@group(0) @binding(1) var<uniform> params: BlurParams;
@group(0) @binding(2) var depth_tex: texture_2d<f32>;
@group(0) @binding(3) var ao_in: texture_2d<f32>;
@group(0) @binding(4) var ao_out: texture_storage_2d<r32float, write>;

// Taps on each side: a pipeline constant, so the tap loops unroll with constant spatial weights
// (measured: the loop's arithmetic, not memory, bounds this pass).
override RADIUS: i32 = 4;

// Output block side; the workgroup has one invocation per output pixel.
const BLOCK: i32 = 16;
const MAX_RADIUS: i32 = 16;
// Tile side for the largest radius: BLOCK + 2 * MAX_RADIUS.
const MAX_TILE: i32 = 48;

// The loaded tile, row-major with row length MAX_TILE: depth (guard band included) and AO (-1
// outside the visible image).
var<workgroup> tile_depth: array<f32, 2304>; // MAX_TILE * MAX_TILE
var<workgroup> tile_ao: array<f32, 2304>;
// The horizontal pass's results for the block's BLOCK columns over all tile rows, row-major with
// row length BLOCK (-1 outside the visible image).
var<workgroup> tile_horizontal: array<f32, 768>; // BLOCK * MAX_TILE

// The weight of the tap `d` texels from the centre at depth `z` (depth slope `slope` along the
// pass's direction) whose depth is `zq`; the same in both passes.
fn tap_weight(d: i32, zq: f32, z: f32, slope: f32) -> f32 {
    let dz = (zq - z - slope * f32(d)) * params.sharpness;
    return exp2(-f32(d * d) * params.falloff - dz * dz);
}

// A tap is skipped outside the visible image (AO < 0) and on background.
fn tap_used(d: i32, ao: f32, zq: f32) -> bool {
    return d != 0 && ao >= 0.0 && !is_background(zq);
}

// The normalised sum of values in [0, 1] can round past 1 (seen on an H200, RELIABILITY.md).
fn blur_mean(sum: f32, weight_sum: f32) -> f32 {
    return min(sum / weight_sum, 1.0);
}

// The depth slope along a direction from the depths before, at and after the centre: the smaller
// of the one-sided differences, so a depth edge on one side does not masquerade as slope.
fn depth_slope(before: f32, z: f32, after: f32) -> f32 {
    let forward = after - z;
    let backward = z - before;
    return select(backward, forward, abs(forward) < abs(backward));
}

@compute @workgroup_size(16, 16)
fn main(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(local_invocation_id) local: vec3<u32>,
    @builtin(local_invocation_index) index: u32,
) {
    let size = vec2<i32>(view.visible_size);
    let full = vec2<i32>(view.full_size);
    let r = RADIUS;
    let tile_side = BLOCK + 2 * r;
    // Visible position of tile texel (0, 0).
    let origin = vec2<i32>(group.xy) * BLOCK - r;

    // Load the tile: all loads of an invocation are issued before any is stored (a loop that
    // stored each load before the next waited for each in turn: 5 % slower in the separable
    // blur on an H200, BENCHMARKS.md).
    let texels = tile_side * tile_side;
    for (var k = i32(index); k < texels; k += BLOCK * BLOCK) {
        let t = vec2<i32>(k % tile_side, k / tile_side);
        let q = origin + t;
        // Depth exists in the guard band too; AO only inside the visible image (-1 = none).
        let zq = clamp(q + i32(view.guard_band), vec2<i32>(0), full - 1);
        let inside = all(q >= vec2<i32>(0)) && all(q < size);
        let ao = select(-1.0, textureLoad(ao_in, clamp(q, vec2<i32>(0), size - 1), 0).r, inside);
        let i = t.y * MAX_TILE + t.x;
        tile_depth[i] = textureLoad(depth_tex, zq, 0).r;
        tile_ao[i] = ao;
    }
    workgroupBarrier();

    // The horizontal pass over the block's columns on every tile row (those outside the visible
    // image are -1, as the separable blur's intermediate image had no texels there).
    for (var k = i32(index); k < BLOCK * tile_side; k += BLOCK * BLOCK) {
        let t = vec2<i32>(k % BLOCK + r, k / BLOCK);
        let q = origin + t;
        let c = t.y * MAX_TILE + t.x;
        var result = -1.0;
        if (all(q >= vec2<i32>(0)) && all(q < size)) {
            let z = tile_depth[c];
            result = tile_ao[c];
            if (!is_background(z)) {
                let slope = depth_slope(tile_depth[c - 1], z, tile_depth[c + 1]);
                var sum = result;
                var weight_sum = 1.0;
                for (var d = -r; d <= r; d++) {
                    let ao = tile_ao[c + d];
                    let zq = tile_depth[c + d];
                    if (tap_used(d, ao, zq)) {
                        let w = tap_weight(d, zq, z, slope);
                        sum += w * ao;
                        weight_sum += w;
                    }
                }
                result = blur_mean(sum, weight_sum);
            }
        }
        tile_horizontal[k] = result;
    }
    workgroupBarrier();

    // The vertical pass over the horizontal results.
    let p = origin + vec2<i32>(local.xy) + r;
    if (any(p >= size)) {
        return;
    }
    let row = i32(local.y) + r;
    let h = row * BLOCK + i32(local.x);
    let c = row * MAX_TILE + i32(local.x) + r;
    let center_ao = tile_horizontal[h];
    let z = tile_depth[c];
    if (is_background(z)) {
        textureStore(ao_out, p, vec4<f32>(center_ao));
        return;
    }
    let slope = depth_slope(tile_depth[c - MAX_TILE], z, tile_depth[c + MAX_TILE]);
    var sum = center_ao;
    var weight_sum = 1.0;
    for (var d = -r; d <= r; d++) {
        let ao = tile_horizontal[h + d * BLOCK];
        let zq = tile_depth[c + d * MAX_TILE];
        if (tap_used(d, ao, zq)) {
            let w = tap_weight(d, zq, z, slope);
            sum += w * ao;
            weight_sum += w;
        }
    }
    textureStore(ao_out, p, vec4<f32>(blur_mean(sum, weight_sum)));
}
