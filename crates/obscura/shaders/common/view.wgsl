// Pixel <-> view-space conversion for the guard-banded framebuffer (mirrors src/view.rs).
// View space is right-handed, the camera looks down -Z, linear depth = -z (DESIGN.md).

struct View {
    full_size: vec2<u32>,
    visible_size: vec2<u32>,
    tan_half_fov: vec2<f32>,
    guard_band: u32,
    _pad: u32,
}

// View-space point of framebuffer pixel coordinates `px` (pixel centres at +0.5) at depth `z`.
fn pixel_to_view(v: View, px: vec2<f32>, z: f32) -> vec3<f32> {
    let size = vec2<f32>(v.full_size);
    let ndc = vec2<f32>(px.x / size.x * 2.0 - 1.0, 1.0 - px.y / size.y * 2.0);
    return vec3<f32>(ndc.x * v.tan_half_fov.x * z, ndc.y * v.tan_half_fov.y * z, -z);
}

// Framebuffer pixel coordinates of a view-space point.
fn view_to_pixel(v: View, p: vec3<f32>) -> vec2<f32> {
    let size = vec2<f32>(v.full_size);
    let ndc = vec2<f32>(p.x / (-p.z * v.tan_half_fov.x), p.y / (-p.z * v.tan_half_fov.y));
    return vec2<f32>((ndc.x + 1.0) * 0.5 * size.x, (1.0 - ndc.y) * 0.5 * size.y);
}

// Background (no geometry) is stored as linear depth 0 in the G-buffer.
fn is_background(z: f32) -> bool {
    return !(z > 0.0);
}
