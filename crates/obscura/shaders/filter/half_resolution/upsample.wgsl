// Half resolution, step 2 (src/filter/half_resolution.rs): the half-resolution AO brought back to
// the full-resolution output by a depth-aware (joint bilateral) upsample: each output pixel blends
// the 3×3 half-resolution texels around the nearest one with a tent weight over two texels
// (bilinear interpolation's, twice as wide: the downsample's checkerboard keeps each side of an
// edge in every other texel only), each times a weight for how far the texel's surface point lies from
// the output pixel's tangent plane, so AO does not bleed across depth discontinuities (the halo
// the papers fight) while planes at any angle blend smoothly. Where no texel lies on the pixel's
// surface, the one nearest its plane is taken. Ours; the papers do not say how they upsample.

@group(0) @binding(0) var<uniform> view: View;
@group(0) @binding(1) var full_depth: texture_2d<f32>;
@group(0) @binding(2) var full_normals: texture_2d<f32>;
@group(0) @binding(3) var half_depth: texture_2d<f32>;
// The half-resolution AO, visible size (w/2 × h/2).
@group(0) @binding(4) var half_ao: texture_2d<f32>;
@group(0) @binding(5) var ao_out: texture_storage_2d<r32float, write>;

// Distance from the tangent plane, relative to the pixel's depth, at which a texel's weight has
// fallen to 1/2: 0.2 % (1 cm at 5 m). Tangent-plane distances of texels on the pixel's own plane
// are rounding only; on a sphere of radius r two full pixels away they are (2·pixel)²/(2r).
const PLANE_TOLERANCE: f32 = 0.002;

@compute @workgroup_size(32, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if (any(id.xy >= view.visible_size)) {
        return;
    }
    let q = id.xy + view.guard_band;
    let z = textureLoad(full_depth, q, 0).r;
    if (is_background(z)) {
        textureStore(ao_out, id.xy, vec4<f32>(1.0));
        return;
    }
    let pos = pixel_to_view(view, vec2<f32>(q) + 0.5, z);
    let normal = textureLoad(full_normals, q, 0).xyz;
    let half_guard = view.guard_band / 2u;
    let half_visible = textureDimensions(half_ao);
    // The pixel centre in half-resolution framebuffer pixels, texel centres at i + 0.5, and the
    // texel nearest to it.
    let t = (vec2<f32>(q) + 0.5) * 0.5 - 0.5;
    let base = round(t);
    var sum = 0.0;
    var weight = 0.0;
    var closest = 1e30;
    var closest_ao = 1.0;
    for (var k = 0u; k < 9u; k++) {
        // Texels base − 1 … base + 1 in each axis, tent weights 1 − d/2 over their distance d.
        let offset = vec2<f32>(f32(k % 3u), f32(k / 3u)) - 1.0;
        let tent = max(1.0 - 0.5 * abs(base + offset - t), vec2<f32>(0.0));
        // Clamped to the visible half image (the AO has no guard band).
        let cell = clamp(
            vec2<i32>(base + offset),
            vec2<i32>(vec2<u32>(half_guard)),
            vec2<i32>(half_guard + half_visible - 1u),
        );
        let texel = vec2<u32>(cell);
        let zt = textureLoad(half_depth, texel, 0).r;
        if (is_background(zt)) {
            continue;
        }
        let ao = textureLoad(half_ao, texel - half_guard, 0).r;
        let to_texel = pixel_to_view(view, 2.0 * (vec2<f32>(texel) + 0.5), zt) - pos;
        let distance = abs(dot(normal, to_texel)) / (PLANE_TOLERANCE * z);
        let w = tent.x * tent.y * exp2(-distance * distance);
        sum += w * ao;
        weight += w;
        if (distance < closest) {
            closest = distance;
            closest_ao = ao;
        }
    }
    let value = select(closest_ao, sum / weight, weight > 1e-4);
    textureStore(ao_out, id.xy, vec4<f32>(value));
}
