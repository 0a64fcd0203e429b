// Temporal accumulation of the AO image (issue 13; the temporal filters engines ship, e.g. the
// history reprojection of TAA, applied to AO alone). It runs on the raw AO, before the bilateral
// blur, so it averages the estimators' rotation noise itself. Every visible pixel is reprojected into the
// previous frame by its depth and the camera motion (the scene is static), the history there is
// read bilinearly from the texels that hold the same surface (depth within `depth_tolerance` of
// the reprojected depth, world normal within `normal_cos`), and the new AO is the running mean
// of up to `max_frames` frames: ao = mix(history, current, 1 / n), n = min(n_history + 1,
// max_frames), the history first clipped to the spread of the current pixel and its neighbours (`clamp`).
// With the estimators' 4×4 pattern turned by one entry per frame (View
// pattern_offset), a still camera converges to the mean over all 16 rotations in 16 frames.
// Pixels with no matching history (disocclusion, off screen, first frame) restart at n = 1.
// Under a ray budget (ray_budget.wgsl) a pixel granted no rays this frame has a negative AO
// (NO_RAYS of estimators/hemisphere.wgsl): it keeps its history as it is (n unchanged), or, with
// none, shows 1 and stores n = 0, which the budget serves first next frame.
//
// History (rg32uint, visible size, ping-pong; 8 bytes, as the pass is bound by memory traffic):
// x = AO as 24-bit fixed point << 8 | n (n ≤ 255); y = linear depth in 16 bits (low half, see
// `pack_history_depth`) | the world normal, octahedral, two snorm bytes (high half).
//
// Needs common/view.wgsl and common/vertex_normal.wgsl in front.

// Variance clipping (Salvi, "An Excursion in Temporal Supersampling", GDC 2016): the history is
// clamped to mean ± GAMMA·σ of the current pixel and its 4 neighbours; 1 is the usual choice.
const GAMMA: f32 = 1.0;
// Within this many pixels of a texel centre, the history is read from that texel alone.
const SNAP: f32 = 0.01;
// The history's AO in 24-bit fixed point.
const AO_SCALE: f32 = 16777215.0;
// The history's depth keeps f32's exponent less this bias in 7 bits (depths 2^-64 to 2^64).
const DEPTH_EXPONENT_BIAS: u32 = 63u;

// Linear depth `z` > 0 in 16 bits: a float of 7 exponent and 9 mantissa bits, rounded (relative
// error ≤ 2^-10 ≈ 0.1 %, against a tolerance of at least 0.2 %: settings/validate.rs). An f16
// held 0.05 % but overflowed at 65,504 world units (a large scene in millimetres lost its whole
// history) and lost precision below 6e-5; 9 bits of mantissa cover every depth a scene may have.
fn pack_history_depth(z: f32) -> u32 {
    let code = i32((bitcast<u32>(z) + 0x2000u) >> 14u) - i32(DEPTH_EXPONENT_BIAS << 9u);
    return u32(clamp(code, 0, 65535));
}

fn unpack_history_depth(code: u32) -> f32 {
    return bitcast<f32>(((code & 0xffffu) + (DEPTH_EXPONENT_BIAS << 9u)) << 14u);
}

struct TemporalParams {
    // View space of this frame to view space of the previous frame.
    current_to_previous: mat4x4<f32>,
    // View space of this frame to world space (the normals' rotation).
    current_to_world: mat4x4<f32>,
    depth_tolerance: f32,
    normal_cos: f32,
    max_frames: f32,
    // 1: clip the history to the spread of this frame's AO around the pixel.
    clamp: u32,
    // 0: no previous frame (the first, or after a reset): every pixel restarts.
    history_valid: u32,
    // The hemisphere rows: each pixel's AO is the mean of this many ray visibilities a frame
    // (0 for the other estimators, whose pixels are not such means).
    sample_rays: u32,
    pad1: u32,
    pad2: u32,
}

@group(0) @binding(0) var<uniform> view: View;
@group(0) @binding(1) var<uniform> params: TemporalParams;
@group(0) @binding(2) var depth_tex: texture_2d<f32>;
@group(0) @binding(3) var normal_tex: texture_2d<f32>;
@group(0) @binding(4) var ao_in: texture_2d<f32>;
@group(0) @binding(5) var history_in: texture_2d<u32>;
@group(0) @binding(6) var ao_out: texture_storage_2d<r32float, write>;
@group(0) @binding(7) var history_out: texture_storage_2d<rg32uint, write>;

// The history's AO and frame count at visible position `q` (texel centres at integers), from the
// texels that hold the surface at linear depth `z` with world normal `n`; count 0 when none.
fn read_history(q_in: vec2<f32>, z: f32, n: vec3<f32>) -> vec2<f32> {
    let size = vec2<i32>(view.visible_size);
    // Within 1/100 px of a texel centre (a still camera, up to the rounding of the matrices):
    // that texel alone, so a still image is not resampled, and blurred, every frame.
    let q = select(q_in, round(q_in), all(abs(q_in - round(q_in)) < vec2<f32>(SNAP)));
    let base = vec2<i32>(floor(q));
    let f = q - floor(q);
    var ao = 0.0;
    var count = 0.0;
    var total = 0.0;
    for (var k = 0; k < 4; k++) {
        let offset = vec2<i32>(k & 1, k >> 1u);
        let texel = base + offset;
        let w = select(1.0 - f.x, f.x, offset.x == 1) * select(1.0 - f.y, f.y, offset.y == 1);
        if (any(texel < vec2<i32>(0)) || any(texel >= size) || !(w > 0.0)) {
            continue;
        }
        let h = textureLoad(history_in, texel, 0).xy;
        let h_count = h.x & 255u;
        let h_depth = unpack_history_depth(h.y);
        if (h_count == 0u || abs(h_depth - z) > params.depth_tolerance * z) {
            continue;
        }
        // The normal only where the depth matched (most rejections are by depth).
        if (dot(decode_vertex_normal(unpack4x8snorm(h.y >> 16u).xy), n) < params.normal_cos) {
            continue;
        }
        ao += w * f32(h.x >> 8u) * (1.0 / AO_SCALE);
        count += w * f32(h_count);
        total += w;
    }
    if (total < 1e-4) {
        return vec2<f32>(0.0);
    }
    return vec2<f32>(ao, count) / total;
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {
    if (any(gid.xy >= view.visible_size)) {
        return;
    }
    let id = gid.xy;
    let full = id + vec2<u32>(view.guard_band);
    let current = textureLoad(ao_in, id, 0).x;
    let z = textureLoad(depth_tex, full, 0).x;
    if (is_background(z)) {
        textureStore(ao_out, id, vec4<f32>(current));
        textureStore(history_out, id, vec4<u32>(0u));
        return;
    }
    let p = pixel_to_view(view, vec2<f32>(full) + 0.5, z);
    // Unit already (the G-buffer's normals; a rotation keeps the length).
    let n_view = textureLoad(normal_tex, full, 0).xyz;
    let n_world = (params.current_to_world * vec4<f32>(n_view, 0.0)).xyz;
    var history = vec2<f32>(0.0);
    if (params.history_valid != 0u) {
        let p_prev = (params.current_to_previous * vec4<f32>(p, 1.0)).xyz;
        let z_prev = -p_prev.z;
        if (z_prev > 0.0) {
            let q = view_to_pixel(view, p_prev) - vec2<f32>(f32(view.guard_band) + 0.5);
            history = read_history(q, z_prev, n_world);
        }
    }
    if (current < 0.0) {
        let kept = select(1.0, history.x, history.y > 0.0);
        textureStore(ao_out, id, vec4<f32>(kept));
        store_history(id, kept, round(history.y), z, n_world);
        return;
    }
    let n = min(round(history.y) + 1.0, params.max_frames);
    var past = history.x;
    if (params.clamp != 0u) {
        // Neighbourhood clamp (as engines' TAA does): the history may not leave the spread of
        // this frame's unfiltered AO around the pixel. Its neighbours hold other rotations of the
        // pattern, so rotation noise passes and is averaged, while occlusion the view no longer
        // has (the halos move with parallax) cannot linger for `max_frames` frames.
        // The pixel and its four edge neighbours (the "plus" of TAA implementations): 5 loads
        // instead of a 3×3 block's 9 (BENCHMARKS.md has both timings).
        var m1 = current;
        var m2 = current * current;
        var taps = 1.0;
        let last = vec2<i32>(view.visible_size) - 1;
        for (var k = 0; k < 4; k++) {
            let step = select(vec2<i32>(0, 1 - 2 * (k & 1)), vec2<i32>(1 - 2 * (k & 1), 0), k < 2);
            let v = textureLoad(ao_in, clamp(vec2<i32>(id) + step, vec2<i32>(0), last), 0).x;
            // A neighbour with no rays this frame (ray budget) says nothing of the spread.
            let fresh = v >= 0.0;
            m1 += select(0.0, v, fresh);
            m2 += select(0.0, v * v, fresh);
            taps += select(0.0, 1.0, fresh);
        }
        let mean = m1 / taps;
        var sigma = sqrt(max(m2 / taps - mean * mean, 0.0));
        if (params.sample_rays > 0u) {
            // A mean of k visibilities in [0, 1] with expectation a varies by at most
            // a(1 − a)/k: that much spread is sampling noise, not a change of the view. The five
            // taps' own spread is five such samples: at a = 0.8 and one ray all five agree a
            // third of the time, which closed the box onto them and reset the history to one
            // frame's noise (the flicker of issue 58's path measurements). So the box is at
            // least the noise's width, taken at the history's AO, the better estimate of a.
            let a = clamp(past, 0.0, 1.0);
            sigma = max(sigma, sqrt(a * (1.0 - a) / f32(params.sample_rays)));
        }
        past = clamp(past, mean - GAMMA * sigma, mean + GAMMA * sigma);
    }
    let ao = select(current, mix(past, current, 1.0 / n), history.y > 0.0);
    textureStore(ao_out, id, vec4<f32>(ao));
    store_history(id, ao, n, z, n_world);
}

// The history texel of visible pixel `id`: AO `ao` over `n` frames of the surface at linear depth
// `z` with world normal `n_world`.
fn store_history(id: vec2<u32>, ao: f32, n: f32, z: f32, n_world: vec3<f32>) {
    let packed_ao = (u32(round(saturate(ao) * AO_SCALE)) << 8u) | u32(n);
    let packed_surface = pack_history_depth(z)
        | (pack4x8snorm(vec4<f32>(encode_octahedral(n_world), 0.0, 0.0)) << 16u);
    textureStore(history_out, id, vec4<u32>(packed_ao, packed_surface, 0u, 0u));
}
