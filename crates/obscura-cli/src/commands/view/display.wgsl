// The viewer's display pass: obscura's AO output and G-buffer (read as they are, no read-back)
// into the RGBA8 image egui shows. egui takes texture values as display (sRGB-encoded) values, so
// the AO is written as it is (grey = AO, as `render` writes PNGs) and linear colours are encoded.

struct Params {
    // 0 AO, 1 composite (base colour × AO), 2 normals, 3 linear depth.
    mode: u32,
    // Columns x < split_x show image A, the others image B (split_x ≥ width: A only).
    split_x: u32,
    // The G-buffer's guard band: visible pixel (x, y) is framebuffer texel (x + g, y + g).
    guard_band: u32,
    // Depth view: this linear depth maps to black, 0 to white.
    depth_max: f32,
};

@group(0) @binding(0) var ao_a: texture_2d<f32>;
@group(0) @binding(1) var ao_b: texture_2d<f32>;
@group(0) @binding(2) var depth: texture_2d<f32>;
@group(0) @binding(3) var normals: texture_2d<f32>;
@group(0) @binding(4) var albedo: texture_2d<f32>;
@group(0) @binding(5) var out_image: texture_storage_2d<rgba8unorm, write>;
@group(0) @binding(6) var<uniform> params: Params;

// The background (no geometry): a dark blue-grey no AO value or normal produces.
const BACKGROUND: vec4<f32> = vec4<f32>(0.12, 0.14, 0.18, 1.0);

fn srgb_from_linear(c: vec3<f32>) -> vec3<f32> {
    let lo = c * 12.92;
    let hi = 1.055 * pow(max(c, vec3<f32>(0.0)), vec3<f32>(1.0 / 2.4)) - 0.055;
    return select(hi, lo, c <= vec3<f32>(0.0031308));
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(out_image);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    let px = vec2<i32>(id.xy);
    let fb = px + vec2<i32>(i32(params.guard_band));
    let d = textureLoad(depth, fb, 0).r;
    var ao = textureLoad(ao_a, px, 0).r;
    if id.x >= params.split_x {
        ao = textureLoad(ao_b, px, 0).r;
    }
    var colour = BACKGROUND;
    if d > 0.0 {
        switch params.mode {
            case 1u: {
                let base = textureLoad(albedo, fb, 0).rgb;
                colour = vec4<f32>(srgb_from_linear(base * clamp(ao, 0.0, 1.0)), 1.0);
            }
            case 2u: {
                let n = textureLoad(normals, fb, 0).xyz;
                colour = vec4<f32>(0.5 * n + vec3<f32>(0.5), 1.0);
            }
            case 3u: {
                let v = clamp(1.0 - d / params.depth_max, 0.0, 1.0);
                colour = vec4<f32>(vec3<f32>(v), 1.0);
            }
            default: {
                colour = vec4<f32>(vec3<f32>(clamp(ao, 0.0, 1.0)), 1.0);
            }
        }
    }
    if params.split_x < size.x && (id.x == params.split_x || id.x + 1u == params.split_x) {
        colour = vec4<f32>(1.0, 0.8, 0.2, 1.0);
    }
    textureStore(out_image, px, colour);
}
