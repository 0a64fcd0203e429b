// The edge-avoiding à-trous denoiser for AO: Dammertz, Sewtz, Hanika and Lensch, "Edge-Avoiding
// À-Trous Wavelet Transform for fast Global Illumination Filtering" (HPG 2010), with the edge
// stops and the variance guidance of Schied et al., "Spatiotemporal Variance-Guided Filtering"
// (HPG 2017, §4.4), for an image of one channel (AO) and its variance:
// - `moments`: each pixel's AO and the variance of the AO over its 5×5 neighbours on the same
//   surface (Schied et al. estimate it spatially where a pixel's history is short). Behind
//   temporal accumulation of hemisphere rays (RAYS > 0) a pixel's own variance is also known
//   from its history: its mean over n frames of N rays of visibility varies by at most
//   a(1 − a)/(nN) (common/visibility_variance.wgsl), and the smaller of the two is taken, so the
//   filter's reach across AO differences falls as the history grows (issue 58: its strength
//   falls with the history) while flat surfaces stay smoothed;
// - `main`, then `main_last` for the last iteration: a 3×3 binomial kernel with taps
//   `step` = 1, 2, 4, … pixels apart (as far as each pixel's reach, `within_reach`: set by its
//   rays and history and by the AO radius on screen, so its strength falls as its history grows),
//   each tap weighted by
//     w_z = exp(−|(Q − P)·n_p| / (0.02 z_p))   (distance from the pixel's tangent plane,
//                                               relative to its depth: scale-free),
//     w_n = max(0, n_p·n_q)^64                  (SVGF's normal stop, σ_n between 32 and 128),
//     w_l = exp(−|a_p − a_q| / (σ √var_p + ε))  (σ = `denoise.sigma`; SVGF's is 4),
//   the variance carried with the squared weights (Schied et al. Eq. 5).
// Background pixels keep their value (1).

struct AtrousParams {
    step: i32,
    sigma: f32,
    // The AO radius R, world units: the reach's cap on screen (`within_reach`).
    radius: f32,
    // M, the samples of visibility a pixel's filtered value should rest on (`within_reach`).
    samples: f32,
}

@group(0) @binding(0) var<uniform> view: View;
@group(0) @binding(1) var<uniform> params: AtrousParams;
@group(0) @binding(2) var depth_tex: texture_2d<f32>;
@group(0) @binding(3) var normal_tex: texture_2d<f32>;
// (AO, variance); an R32Float input reads variance 0.
@group(0) @binding(4) var ao_in: texture_2d<f32>;
@group(0) @binding(5) var moments_out: texture_storage_2d<rg32float, write>;
@group(0) @binding(6) var ao_out: texture_storage_2d<r32float, write>;
// Temporal accumulation's history this frame (temporal_accumulation.wgsl: the frame count n in
// the low byte of x), read when HISTORY is set.
@group(0) @binding(7) var history: texture_2d<u32>;

// N, the hemisphere rays a pixel casts each frame; 0 for the other estimators (spatial variance
// only, and no reach from the sample count).
override RAYS: u32 = 0u;
// Whether temporal accumulation runs before (`history` holds each pixel's frame count).
override HISTORY: bool = false;

// The binomial kernel 1/4 (1 2 1), where Dammertz et al. use the 5×5 B3 spline: per tap it cuts
// the noise more (a 3×3 pass 7× for 9 taps, a B3 pass 13× for 25), and an iteration cost
// 0.185 ms at 1080p on an H100 with the B3 (BENCHMARKS.md). On Sponza at 960×540 after 16
// frames of one ray (lavapipe) it ends at 0.0161 MAE against the B3's 0.0149, for about half
// the taps.
const KERNEL = array<f32, 3>(0.25, 0.5, 0.25);

struct Surface {
    pos: vec3<f32>,
    normal: vec3<f32>,
    depth: f32,
    valid: bool,
}

// The surface at visible pixel `p` (the frame's depth and normals carry the guard band).
fn surface_at(p: vec2<i32>) -> Surface {
    var s: Surface;
    let pixel = vec2<u32>(p) + vec2<u32>(view.guard_band);
    s.depth = textureLoad(depth_tex, pixel, 0).r;
    s.valid = !is_background(s.depth);
    if (s.valid) {
        s.pos = pixel_to_view(view, vec2<f32>(pixel) + 0.5, s.depth);
        s.normal = normalize(textureLoad(normal_tex, pixel, 0).xyz);
    }
    return s;
}

// The geometric part of a tap's weight: same tangent plane, same facing.
fn surface_weight(p: Surface, q: Surface) -> f32 {
    if (!q.valid) {
        return 0.0;
    }
    let plane = abs(dot(q.pos - p.pos, p.normal)) / (0.02 * p.depth);
    return exp(-plane) * pow(max(dot(p.normal, q.normal), 0.0), 64.0);
}

fn inside(q: vec2<i32>) -> bool {
    return all(q >= vec2<i32>(0)) && all(q < vec2<i32>(view.visible_size));
}

@compute @workgroup_size(8, 8)
fn moments(@builtin(global_invocation_id) id: vec3<u32>) {
    let p = vec2<i32>(id.xy);
    if (!inside(p)) {
        return;
    }
    let a = textureLoad(ao_in, p, 0).r;
    let sp = surface_at(p);
    if (!sp.valid) {
        textureStore(moments_out, p, vec4<f32>(a, 0.0, 0.0, 0.0));
        return;
    }
    var sum = vec2<f32>(a, a * a);
    var weight = 1.0;
    for (var k = 0; k < 25; k++) {
        let q = p + vec2<i32>(k % 5 - 2, k / 5 - 2);
        if (k == 12 || !inside(q)) {
            continue;
        }
        let w = surface_weight(sp, surface_at(q));
        let b = textureLoad(ao_in, q, 0).r;
        sum += w * vec2<f32>(b, b * b);
        weight += w;
    }
    let mean = sum / weight;
    var variance = max(mean.y - mean.x * mean.x, 0.0);
    if (RAYS > 0u && HISTORY) {
        let frames = textureLoad(history, p, 0).x & 255u;
        if (frames > 0u) {
            variance = min(variance, visibility_variance(a, f32(frames * RAYS)));
        }
    }
    textureStore(moments_out, p, vec4<f32>(a, variance, 0.0, 0.0));
}

// Whether this iteration's taps are within pixel `p`'s reach (ours; its strength falls as its
// history grows, issue 58). Two caps, each a pixel count, so the rule holds at any resolution:
// - the sample count: each iteration widens the kernel's footprint about four times, so
//   ⌈log4(M / (n N))⌉ iterations average about M samples of visibility for n frames of N rays
//   (none once a pixel's own history holds M; with the 3×3 kernel the footprint of k
//   iterations holds about 2(4^k − 1) pixels' worth, so M counts rays generously);
// - the AO radius on screen: the kernel's half-width after this iteration, `step`, stays within
//   R_px / 4, so the filter averages over less than the distance across which the AO itself
//   changes (an occluder's influence reaches R) at any resolution and distance. R/4 rather than
//   R/2: in tests/it/hemisphere.rs's room at one ray a pixel, with the B3 kernel, R/2 cut the
//   squared error 14× but its mean error over the box's silhouette band was 0.020 (contact
//   shadows averaged along the floor), R/4 9× and 0.007 (with this kernel R/4: 14× and 0.011);
//   on Sponza (960×540, lavapipe) R/2 and R/4 differed by 0.002 MAE.
fn within_reach(p: vec2<i32>, s: Surface) -> bool {
    let r_px = params.radius * pixels_per_unit(view, s.depth).y;
    if (f32(params.step) > 0.25 * r_px) {
        return false;
    }
    if (RAYS == 0u) {
        return true;
    }
    var frames = 1u;
    if (HISTORY) {
        frames = max(textureLoad(history, p, 0).x & 255u, 1u);
    }
    let iterations = ceil(log2(params.samples / f32(frames * RAYS)) * 0.5);
    return f32(params.step) < exp2(iterations);
}

// One iteration at pixel `p`: (AO, variance).
fn filtered(p: vec2<i32>) -> vec2<f32> {
    let centre = textureLoad(ao_in, p, 0).rg;
    let sp = surface_at(p);
    if (!sp.valid || !within_reach(p, sp)) {
        return centre;
    }
    let reach = params.sigma * sqrt(centre.y) + 1e-4;
    var sum = KERNEL[1] * KERNEL[1] * centre.x;
    var variance = KERNEL[1] * KERNEL[1] * KERNEL[1] * KERNEL[1] * centre.y;
    var weight = KERNEL[1] * KERNEL[1];
    for (var k = 0; k < 9; k++) {
        let offset = vec2<i32>(k % 3 - 1, k / 3 - 1);
        let q = p + offset * params.step;
        if (k == 4 || !inside(q)) {
            continue;
        }
        let b = textureLoad(ao_in, q, 0).rg;
        let w = KERNEL[offset.x + 1] * KERNEL[offset.y + 1] * surface_weight(sp, surface_at(q))
            * exp(-abs(centre.x - b.x) / reach);
        sum += w * b.x;
        variance += w * w * b.y;
        weight += w;
    }
    return vec2<f32>(min(sum / weight, 1.0), variance / (weight * weight));
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let p = vec2<i32>(id.xy);
    if (inside(p)) {
        textureStore(moments_out, p, vec4<f32>(filtered(p), 0.0, 0.0));
    }
}

@compute @workgroup_size(8, 8)
fn main_last(@builtin(global_invocation_id) id: vec3<u32>) {
    let p = vec2<i32>(id.xy);
    if (!inside(p)) {
        return;
    }
    let ao = filtered(p).x;
    textureStore(ao_out, p, vec4<f32>(ao));
}
