// Separable depth-aware (cross) bilateral blur of the AO image, as HBAO+ and the seed 000 §3.4
// use it (seed-code-notes §1.8): radius 4, Gaussian spatial weight with sigma = (radius + 1) / 2,
// and a depth weight exp2(-(dz * sharpness)^2) on the linear depth difference in world units,
// after removing the local depth slope so that tilted planes blur like flat ones.
// Only visible pixels are read: the AO image has no guard band, so taps outside it are skipped.

struct BlurParams {
    // (1, 0) for the horizontal pass, (0, 1) for the vertical one.
    direction: vec2<i32>,
    radius: i32,
    sharpness: f32,
}

@group(0) @binding(0) var<uniform> view: View;
@group(0) @binding(1) var<uniform> params: BlurParams;
@group(0) @binding(2) var depth_tex: texture_2d<f32>;
@group(0) @binding(3) var ao_in: texture_2d<f32>;
@group(0) @binding(4) var ao_out: texture_storage_2d<r32float, write>;

fn depth_at(p: vec2<i32>) -> f32 {
    return textureLoad(depth_tex, p + i32(view.guard_band), 0).r;
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<i32>(view.visible_size);
    let p = vec2<i32>(id.xy);
    if (any(p >= size)) {
        return;
    }
    let center_ao = textureLoad(ao_in, p, 0).r;
    let z = depth_at(p);
    if (is_background(z)) {
        textureStore(ao_out, p, vec4<f32>(center_ao));
        return;
    }
    // Depth slope along the blur direction: the smaller of the one-sided differences, so a depth
    // edge on one side does not masquerade as slope.
    let forward = depth_at(p + params.direction) - z;
    let backward = z - depth_at(p - params.direction);
    let slope = select(backward, forward, abs(forward) < abs(backward));

    let sigma = (f32(params.radius) + 1.0) * 0.5;
    let falloff = 1.0 / (2.0 * sigma * sigma);
    var sum = center_ao;
    var weight_sum = 1.0;
    for (var d = -params.radius; d <= params.radius; d++) {
        let q = p + params.direction * d;
        if (d == 0 || any(q < vec2<i32>(0)) || any(q >= size)) {
            continue;
        }
        let zq = depth_at(q);
        if (is_background(zq)) {
            continue;
        }
        let dz = (zq - z - slope * f32(d)) * params.sharpness;
        let w = exp2(-f32(d * d) * falloff - dz * dz);
        sum += w * textureLoad(ao_in, q, 0).r;
        weight_sum += w;
    }
    textureStore(ao_out, p, vec4<f32>(sum / weight_sum));
}
