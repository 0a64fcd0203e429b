// What the spiral-tap estimators (`sao`, `ssao`; McGuire et al. 2011, 2012) share: the pixel
// set-up (the shading point, its normal, the radius in pixels and the rotation of the 4×4 pattern,
// `params.pattern[..].x`, which both estimators' parameter blocks hold) and the taps' placement on
// SAO's spiral. Put between screen_space.wgsl and the estimator (their Rust modules concatenate
// the three).

struct EstimatorPixel {
    pos: vec3<f32>,
    normal: vec3<f32>,
    pixel: vec2<u32>,
    rotation: f32,
    radius_px: f32,
    // R², and R over the estimator's R, for R capped on screen (screen_space.wgsl).
    radius2: f32,
    radius_scale: f32,
    valid: bool,
}

fn estimator_pixel(id: vec2<u32>) -> EstimatorPixel {
    let base = screen_pixel(id, params.radius);
    var p: EstimatorPixel;
    p.pixel = base.pixel;
    p.valid = base.valid;
    if (!p.valid) {
        return p;
    }
    p.pos = base.pos;
    p.normal = base.normal;
    p.rotation = params.pattern[pattern_index(id)].x;
    p.radius_px = select(0.0, base.radius_px, base.radius_px >= 1.0);
    p.radius2 = params.radius2 * (base.radius_scale * base.radius_scale);
    p.radius_scale = base.radius_scale;
    return p;
}

// Tap i of n on SAO's spiral (McGuire et al. 2012): at α = (i + 0.5)/n of `radius_px` and angle
// 2π·α·turns + rotation. xy: the framebuffer offset (view y up,
// framebuffer y down), z: the distance in pixels.
fn spiral_tap(i: u32, n: u32, turns: f32, rotation: f32, radius_px: f32) -> vec3<f32> {
    let alpha = (f32(i) + 0.5) / f32(n);
    let angle = alpha * 6.283185307179586 * turns + rotation;
    let distance = alpha * radius_px;
    return vec3<f32>(vec2<f32>(cos(angle), -sin(angle)) * distance, distance);
}
