// Depth peeling's pyramid (shaders/occlusion_pyramid.wgsl; read by triangle_cull.wgsl,
// `in_front_of_peel_pyramid`): per tile the largest reversed-Z depth a fragment must lie behind
// (below) to be peeled. Depth peeling (depth_peel.wgsl, `peel_keeps`) keeps a fragment at linear
// depth d only where the first layer's linear depth `first` is not background (0) and
// d > first + separation: in reversed Z (smaller is farther), only below the depth of the view
// point at linear depth first + separation. A triangle at or above that at every pixel it may
// cover cannot be peeled anywhere. Background, and pixels outside the framebuffer, keep nothing:
// -1, below every depth.

@group(0) @binding(0) var first_layer: texture_2d<f32>;
@group(0) @binding(2) var<storage, read> peel_pyramid_params: PeelPyramidParams;

struct PeelPyramidParams {
    projection: mat4x4<f32>,
    separation: f32,
    pad0: f32,
    pad1: f32,
    pad2: f32,
}

const PYRAMID_OUTSIDE: f32 = -1.0;

fn pyramid_source_size() -> vec2<u32> {
    return textureDimensions(first_layer);
}

fn pyramid_pixel(p: vec2<u32>) -> f32 {
    let first = textureLoad(first_layer, p, 0).r;
    if (first <= 0.0) {
        return PYRAMID_OUTSIDE;
    }
    let clip = peel_pyramid_params.projection
        * vec4<f32>(0.0, 0.0, -(first + peel_pyramid_params.separation), 1.0);
    return clip.z / clip.w;
}

fn pyramid_combine(a: f32, b: f32) -> f32 {
    return max(a, b);
}
