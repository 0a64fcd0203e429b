// Half resolution, step 1 (src/filter/half_resolution.rs): the frame's depth, normals and second
// layer reduced 2×2 → 1 for a technique that runs at half the width and height (seed 001 Tab. 1–2
// report every stochastic-depth variant at 960×540 for 1080p; the paper does not say how its
// half-resolution inputs were made, so this rule is ours).
//
// A half-resolution pixel's centre is the corner its 2×2 full-resolution pixels share. Where the
// four lie on one plane (each within PLANE_SLOPE of the plane through the first, with the mean
// normal), the plane's depth at that corner is exact: 1/z is affine in screen position on a
// plane, so the corner's 1/z is the mean of the four. Elsewhere (an edge, a silhouette, the
// background) one of the four is kept with its normal, never a depth between two surfaces: the
// nearest where x + y is even, the farthest (the background, if any of the four is) where it is
// odd. This checkerboard keeps both sides of every edge in the half frame, so the upsample finds
// texels of the pixel's own surface on either side (the nearest alone would hand the background
// pixels along a silhouette only foreground AO). The second layer follows the same choice (the
// nearest second layer of the four on a plane).

@group(0) @binding(0) var<uniform> view: View;
@group(0) @binding(1) var full_depth: texture_2d<f32>;
@group(0) @binding(2) var full_normals: texture_2d<f32>;
// The frame's second layer, or a 1×1 empty texture for rows without one.
@group(0) @binding(3) var full_second: texture_2d<f32>;
@group(0) @binding(4) var half_depth: texture_storage_2d<r32float, write>;
@group(0) @binding(5) var half_normals: texture_storage_2d<rgba16float, write>;
@group(0) @binding(6) var half_second: texture_storage_2d<r32float, write>;

// Largest |n·(P_k − P_0)| / |P_k − P_0| for four points to count as one plane: about 3°, far above
// the half-float normals' error (~5e-4) and far below any step or crease.
const PLANE_SLOPE: f32 = 0.05;

@compute @workgroup_size(32, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(half_depth);
    if (any(id.xy >= size)) {
        return;
    }
    let second_size = textureDimensions(full_second);
    var z: array<f32, 4>;
    var n: array<vec3<f32>, 4>;
    var p: array<vec3<f32>, 4>;
    var second: array<f32, 4>;
    var nearest = 4u;
    var farthest = 4u;
    var valid = 0u;
    for (var k = 0u; k < 4u; k++) {
        let q = id.xy * 2u + vec2<u32>(k & 1u, k >> 1u);
        z[k] = textureLoad(full_depth, q, 0).r;
        n[k] = textureLoad(full_normals, q, 0).xyz;
        second[k] = textureLoad(full_second, min(q, second_size - 1u), 0).r;
        if (!is_background(z[k])) {
            p[k] = pixel_to_view(view, vec2<f32>(q) + 0.5, z[k]);
            valid += 1u;
            if (nearest == 4u || z[k] < z[nearest]) {
                nearest = k;
            }
            if (farthest == 4u || z[k] > z[farthest]) {
                farthest = k;
            }
        }
    }
    let odd = ((id.x + id.y) & 1u) == 1u;
    if (nearest == 4u || (odd && valid < 4u)) {
        textureStore(half_depth, id.xy, vec4<f32>(0.0));
        textureStore(half_normals, id.xy, vec4<f32>(0.0, 0.0, 1.0, 0.0));
        textureStore(half_second, id.xy, vec4<f32>(0.0));
        return;
    }
    let kept = select(nearest, farthest, odd);
    var depth = z[kept];
    var normal = n[kept];
    var behind = second[kept];
    if (valid == 4u) {
        let mean_normal = normalize(n[0] + n[1] + n[2] + n[3]);
        var planar = true;
        for (var k = 1u; k < 4u; k++) {
            let d = p[k] - p[0];
            planar = planar && abs(dot(mean_normal, d)) <= PLANE_SLOPE * length(d)
                && dot(n[k], mean_normal) >= 1.0 - PLANE_SLOPE;
        }
        if (planar) {
            depth = 4.0 / (1.0 / z[0] + 1.0 / z[1] + 1.0 / z[2] + 1.0 / z[3]);
            normal = mean_normal;
            behind = 0.0;
            for (var k = 0u; k < 4u; k++) {
                if (second[k] > depth && (behind == 0.0 || second[k] < behind)) {
                    behind = second[k];
                }
            }
        }
    }
    textureStore(half_depth, id.xy, vec4<f32>(depth));
    textureStore(half_normals, id.xy, vec4<f32>(normal, 0.0));
    textureStore(half_second, id.xy, vec4<f32>(behind));
}
