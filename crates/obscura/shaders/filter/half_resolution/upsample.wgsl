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

// The half-resolution texels a workgroup of 32×8 output pixels reads, loaded once into workgroup
// memory with their view-space positions: 16×4 nearest texels and one more on each side. Each
// pixel reads 9 of them, so loading them per pixel read each texel about 20 times and made the
// pass twice as slow as the AO pass it upsamples (H100, BENCHMARKS.md).
const TILE_WIDTH: u32 = 18u;
const TILE_HEIGHT: u32 = 6u;
var<workgroup> tile_position: array<vec3<f32>, 108>;
// The texel's AO, or −1 where it is background.
var<workgroup> tile_ao: array<f32, 108>;

@compute @workgroup_size(32, 8)
fn main(
    @builtin(global_invocation_id) id: vec3<u32>,
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(local_invocation_index) local: u32,
) {
    let half_guard = view.guard_band / 2u;
    let half_visible = textureDimensions(half_ao);
    // The guard band is even (HalfResolution::new), so the workgroup's first pixel is even and
    // its nearest texel is half its position; the tile starts one texel before.
    let origin = vec2<i32>((group.xy * vec2<u32>(32u, 8u) + view.guard_band) / 2u) - 1;
    if (local < TILE_WIDTH * TILE_HEIGHT) {
        let cell = origin + vec2<i32>(i32(local % TILE_WIDTH), i32(local / TILE_WIDTH));
        // Clamped to the visible half image (the AO has no guard band).
        let texel = vec2<u32>(clamp(
            cell,
            vec2<i32>(vec2<u32>(half_guard)),
            vec2<i32>(half_guard + half_visible - 1u),
        ));
        let zt = textureLoad(half_depth, texel, 0).r;
        var ao = -1.0;
        var position = vec3<f32>(0.0);
        if (!is_background(zt)) {
            ao = textureLoad(half_ao, texel - half_guard, 0).r;
            position = pixel_to_view(view, 2.0 * (vec2<f32>(texel) + 0.5), zt);
        }
        tile_position[local] = position;
        tile_ao[local] = ao;
    }
    workgroupBarrier();
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
    // The pixel centre in half-resolution framebuffer pixels, texel centres at i + 0.5, and the
    // texel nearest to it (q / 2: t is q / 2 − 1/4 for even q, (q − 1) / 2 + 1/4 for odd).
    let t = (vec2<f32>(q) + 0.5) * 0.5 - 0.5;
    let base = vec2<i32>(q / 2u);
    var sum = 0.0;
    var weight = 0.0;
    var closest = 1e30;
    var closest_ao = 1.0;
    for (var k = 0u; k < 9u; k++) {
        // Texels base − 1 … base + 1 in each axis, tent weights 1 − d/2 over their distance d.
        let offset = vec2<i32>(i32(k % 3u), i32(k / 3u)) - 1;
        let tent = max(1.0 - 0.5 * abs(vec2<f32>(base + offset) - t), vec2<f32>(0.0));
        let cell = base + offset - origin;
        let i = u32(cell.y) * TILE_WIDTH + u32(cell.x);
        let ao = tile_ao[i];
        if (ao < 0.0) {
            continue;
        }
        let distance = abs(dot(normal, tile_position[i] - pos)) / (PLANE_TOLERANCE * z);
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
