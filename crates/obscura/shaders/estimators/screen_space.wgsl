// What the screen-space estimators (HBAO, HBAO+, GTAO, GTAO-VB, SSAO, SAO, Pyramid HBAO) start a
// pixel from: the shading point and its normal from the frame, and the world radius R they use,
// capped on screen (`max_radius_px`, seed 002 §3.5; common/view.wgsl capped_radius), in world
// units and in framebuffer pixels. Put in front of such an estimator (its Rust module
// concatenates the two); the hemisphere estimator takes only its accessors.

struct ScreenPixel {
    pos: vec3<f32>,
    normal: vec3<f32>,
    // Framebuffer pixel of the shading point.
    pixel: vec2<u32>,
    valid: bool,
    // The pixel's R over the estimator's: 1 unless the on-screen cap shrinks R (without a cap
    // the literal 1, so that the terms the estimators scale by it stay uniform values). The
    // estimators scale their world-radius terms (falloff, radius²) by it.
    radius_scale: f32,
    // Pixels per R world units at the point's depth (square pixels).
    radius_px: f32,
}

fn screen_pixel(id: vec2<u32>, radius: f32) -> ScreenPixel {
    let point = frame_point(id);
    var p: ScreenPixel;
    p.pixel = point.pixel;
    p.valid = point.valid;
    if (!p.valid) {
        return p;
    }
    p.pos = point.pos;
    p.normal = point.normal;
    let capped = capped_radius(view, radius, -point.pos.z);
    p.radius_scale = select(1.0, capped / radius, MAX_RADIUS_PX > 0.0);
    p.radius_px = capped * pixels_per_unit(view, -point.pos.z).y;
    return p;
}

// The surface at framebuffer point `px` and linear depth `z` as the sample's occluder (the
// contract's estimator_occluder_at; VAO has its own, which needs no view-space point).
fn estimator_occluder_at(p: EstimatorPixel, s: EstimatorSample, px: vec2<f32>, z: f32) -> Occluder {
    return estimator_occluder(p, s, pixel_to_view(view, px, z));
}

// The estimator contract's accessors, alike for every screen-space estimator: each names its
// EstimatorPixel fields `valid` and `pixel` and its EstimatorSample fields `on` and `px`.

fn estimator_pixel_valid(p: EstimatorPixel) -> bool {
    return p.valid;
}

fn estimator_shading_pixel(p: EstimatorPixel) -> vec2<u32> {
    return p.pixel;
}

fn estimator_sample_active(s: EstimatorSample) -> bool {
    return s.on;
}

fn estimator_sample_px(p: EstimatorPixel, s: EstimatorSample) -> vec2<f32> {
    return s.px;
}
