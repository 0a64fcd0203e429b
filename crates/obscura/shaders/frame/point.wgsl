// The shading point of visible pixel `id`, in the view the estimators work in: the frame's own
// (read from its depth and normals). The multi-view schedule's second view composes
// schedules/multiview/point.wgsl in its place (the same point, seen from the other camera).
// FramePoint is frame.wgsl's.
// After frame.wgsl.

fn frame_point(id: vec2<u32>) -> FramePoint {
    var p: FramePoint;
    p.pixel = id + vec2<u32>(view.guard_band);
    let z = textureLoad(depth_tex, p.pixel, 0).r;
    p.valid = !is_background(z);
    if (!p.valid) {
        return p;
    }
    p.pos = pixel_to_view(view, vec2<f32>(p.pixel) + 0.5, z);
    p.normal = normalize(textureLoad(normal_tex, p.pixel, 0).xyz);
    return p;
}
