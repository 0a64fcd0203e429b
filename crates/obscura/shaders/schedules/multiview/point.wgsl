// Multi-view (seed 001 §3.4, Algorithm 3, lines 9–11), the second view's pass: the shading point of
// the camera's visible pixel `id`, read from the camera's depth and normals (group 0 holds the
// camera's textures; `view` is the second view's geometry), carried into the second view's space
// and projected onto its framebuffer. Composed in place of frame/point.wgsl. A point outside the
// second view's framebuffer or behind it is not valid there: the camera's AO stands alone.

struct MultiviewFrame {
    // The camera's view (its pixels, depth and normals).
    main: View,
    // The camera's view space to the second view's (rigid).
    to_second: mat4x4<f32>,
}

@group(GROUP_SOURCE) @binding(SOURCE_MULTIVIEW) var<uniform> multiview: MultiviewFrame;

fn frame_point(id: vec2<u32>) -> FramePoint {
    var p: FramePoint;
    let main_pixel = id + vec2<u32>(multiview.main.guard_band);
    let z = textureLoad(depth_tex, main_pixel, 0).r;
    p.valid = !is_background(z);
    if (!p.valid) {
        return p;
    }
    let main_pos = pixel_to_view(multiview.main, vec2<f32>(main_pixel) + 0.5, z);
    let main_normal = normalize(textureLoad(normal_tex, main_pixel, 0).xyz);
    p.pos = (multiview.to_second * vec4<f32>(main_pos, 1.0)).xyz;
    p.normal = normalize((multiview.to_second * vec4<f32>(main_normal, 0.0)).xyz);
    let px = view_to_pixel(view, p.pos);
    p.valid = p.pos.z < 0.0 && all(px >= vec2<f32>(0.0)) && all(px < vec2<f32>(view.full_size));
    p.pixel = vec2<u32>(max(px, vec2<f32>(0.0)));
    return p;
}
