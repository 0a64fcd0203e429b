// View-space normals for the AO passes (src/engine_input.rs), from what the engine has:
// - `main`: none; reconstructed from the linear depth depth.wgsl wrote. Per axis, of the two
//   one-sided differences the one whose two taps extrapolate best to the centre depth is used
//   (J. Turánszki, "Improved normal reconstruction from depth", 2021), so silhouettes do not bend
//   normals of the surface they bound (the blocky edges of central differences).
// - `main_fused`: the engine's normals, view-space (WORLD false) or world-space (WORLD true,
//   turned into view space); BIASED: stored as n * 0.5 + 0.5 (unorm targets). Such a normal
//   needs no neighbour's depth, so this one dispatch also writes the linear depth (one pass and
//   one barrier instead of two, and the linear depth is not read back).
// Every normal is turned towards the camera.
// Needs common/view.wgsl and engine_input/linear_depth.wgsl in front.

override WORLD: bool = false;
override BIASED: bool = false;

struct EngineNormals {
    world_to_view: mat4x4<f32>,
}

@group(0) @binding(0) var<uniform> params: EngineNormals;
@group(0) @binding(1) var<uniform> view: View;
// Linear view depth (the depth pass's output), 0 = background (`main` only).
@group(0) @binding(2) var depth: texture_2d<f32>;
// The engine's normals (`main_fused` only).
@group(0) @binding(3) var normals_in: texture_2d<f32>;
@group(0) @binding(4) var normals_out: texture_storage_2d<rgba16float, write>;
// `main_fused` only: the engine's depth and its conversion, and where the linear depth goes.
@group(0) @binding(5) var<uniform> depth_params: EngineDepth;
// Depth32Float, Depth24Plus, Depth16Unorm or R32Float holding NDC z.
@group(0) @binding(6) var engine_depth: texture_2d<f32>;
@group(0) @binding(7) var depth_out: texture_storage_2d<r32float, write>;

fn depth_at(p: vec2<i32>) -> f32 {
    let size = vec2<i32>(view.full_size);
    if (any(p < vec2<i32>(0)) || any(p >= size)) {
        return 0.0;
    }
    return textureLoad(depth, vec2<u32>(p), 0).r;
}

fn position_at(p: vec2<i32>, z: f32) -> vec3<f32> {
    return pixel_to_view(view, vec2<f32>(p) + 0.5, z);
}

// The view-space step of one pixel along `axis` (+x right, or +y down), taken on the side whose
// two taps continue the centre's surface.
fn surface_step(c: vec2<i32>, zc: f32, axis: vec2<i32>) -> vec3<f32> {
    let z_back1 = depth_at(c - axis);
    let z_back2 = depth_at(c - 2 * axis);
    let z_fwd1 = depth_at(c + axis);
    let z_fwd2 = depth_at(c + 2 * axis);
    // Extrapolation error of each side (background taps: never chosen over a real one).
    let err_back = select(3.0e38, abs(2.0 * z_back1 - z_back2 - zc), z_back1 > 0.0 && z_back2 > 0.0);
    let err_fwd = select(3.0e38, abs(2.0 * z_fwd1 - z_fwd2 - zc), z_fwd1 > 0.0 && z_fwd2 > 0.0);
    let pc = position_at(c, zc);
    if (err_fwd <= err_back && z_fwd1 > 0.0) {
        return position_at(c + axis, z_fwd1) - pc;
    }
    if (z_back1 > 0.0) {
        return pc - position_at(c - axis, z_back1);
    }
    return vec3<f32>(0.0);
}

fn reconstructed(c: vec2<i32>, zc: f32) -> vec3<f32> {
    let dx = surface_step(c, zc, vec2<i32>(1, 0));
    // Rows grow downwards; the cross product wants the step upwards.
    let dy_up = -surface_step(c, zc, vec2<i32>(0, 1));
    return cross(dx, dy_up);
}

fn decoded(c: vec2<i32>) -> vec3<f32> {
    var n = textureLoad(normals_in, vec2<u32>(c), 0).xyz;
    if (BIASED) {
        n = n * 2.0 - 1.0;
    }
    if (WORLD) {
        n = (params.world_to_view * vec4<f32>(n, 0.0)).xyz;
    }
    return n;
}

// `n` (any length) as a unit normal facing the camera at pixel `c` of depth `zc`; a degenerate
// one (a lone pixel, a zero texel) faces the camera.
fn facing_camera(c: vec2<i32>, zc: f32, n: vec3<f32>) -> vec3<f32> {
    let toward = toward_camera(view, position_at(c, zc));
    let unit = select(toward, normalize(n), length(n) > 0.0);
    return select(unit, -unit, dot(unit, toward) < 0.0);
}

@compute @workgroup_size(32, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if (any(id.xy >= view.full_size)) {
        return;
    }
    let c = vec2<i32>(id.xy);
    let zc = textureLoad(depth, id.xy, 0).r;
    var n = vec3<f32>(0.0);
    if (zc > 0.0) {
        n = facing_camera(c, zc, reconstructed(c, zc));
    }
    textureStore(normals_out, id.xy, vec4<f32>(n, 0.0));
}

@compute @workgroup_size(32, 8)
fn main_fused(@builtin(global_invocation_id) id: vec3<u32>) {
    if (any(id.xy >= view.full_size)) {
        return;
    }
    let c = vec2<i32>(id.xy);
    let zc = engine_linear_depth(depth_params, view, id.xy, textureLoad(engine_depth, id.xy, 0).r);
    textureStore(depth_out, id.xy, vec4<f32>(zc, 0.0, 0.0, 0.0));
    var n = vec3<f32>(0.0);
    if (zc > 0.0) {
        n = facing_camera(c, zc, decoded(c));
    }
    textureStore(normals_out, id.xy, vec4<f32>(n, 0.0));
}
