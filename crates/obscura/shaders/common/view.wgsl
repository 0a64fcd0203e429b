// Pixel <-> view-space conversion for the guard-banded framebuffer (mirrors src/view.rs).
// View space is right-handed, the camera looks down -Z, linear depth = -z (docs/ARCHITECTURE.md,
// "Conventions").
// The reciprocals are precomputed on the CPU: these run per AO sample, where divisions dominated.

struct View {
    full_size: vec2<u32>,
    visible_size: vec2<u32>,
    // Perspective: tan of half the field of view; orthographic: half the extent in world units.
    tan_half_fov: vec2<f32>,
    guard_band: u32,
    // 1: orthographic projection (the pipelines also set ORTHOGRAPHIC, which the helpers read).
    orthographic: u32,
    // 2 / full_size: normalised device coordinates per pixel.
    ndc_per_pixel: vec2<f32>,
    // 0.5 * full_size / tan_half_fov: pixels per unit of x/z (y/z) from the image centre.
    projection_scale: vec2<f32>,
    // How far the estimators' 4×4 pattern is turned this frame (common/pattern.wgsl): 0 unless
    // temporal accumulation is on, which turns it by one entry per frame.
    pattern_offset: u32,
    // The frame number (0 unless temporal accumulation is on): the seed of the `hemisphere`
    // estimator's rays this frame.
    frame: u32,
    // The camera's near plane where the renderer knows the camera, else 0 (src/view.rs).
    near: f32,
    // Pads the struct to 64 bytes, as a struct member of a uniform struct is laid out.
    pad2: u32,
}

// An orthographic projection (parallel view rays along -Z): a pipeline constant rather than a
// uniform test, so the perspective pipelines compile without it (4 % of the vao pass on an H200
// when it was read from the uniform per sample; BENCHMARKS.md).
override ORTHOGRAPHIC: bool = false;

// View-space point of framebuffer pixel coordinates `px` (pixel centres at +0.5) at depth `z`.
fn pixel_to_view(v: View, px: vec2<f32>, z: f32) -> vec3<f32> {
    let ndc = vec2<f32>(px.x * v.ndc_per_pixel.x - 1.0, 1.0 - px.y * v.ndc_per_pixel.y);
    return vec3<f32>(ndc * v.tan_half_fov * select(z, 1.0, ORTHOGRAPHIC), -z);
}

// Framebuffer pixel coordinates of a view-space point.
fn view_to_pixel(v: View, p: vec3<f32>) -> vec2<f32> {
    let s = p.xy * (v.projection_scale / select(-p.z, 1.0, ORTHOGRAPHIC));
    let half_size = 0.5 * vec2<f32>(v.full_size);
    return vec2<f32>(half_size.x + s.x, half_size.y - s.y);
}

// Pixels per world unit across the view at linear depth `z`.
fn pixels_per_unit(v: View, z: f32) -> vec2<f32> {
    return v.projection_scale / select(z, 1.0, ORTHOGRAPHIC);
}

// The AO radius cap on screen in pixels (`max_radius_px`; seed 002 §3.5, the authors' ssMaxRadius):
// a pipeline constant the estimators' pipelines set where a cap applies; 0, the default, is none.
override MAX_RADIUS_PX: f32 = 0.0;

// The world radius a shading point at linear depth `z` uses: `radius`, or where it would cover
// more than MAX_RADIUS_PX pixels, the radius that covers exactly that many (the authors shrink
// the world radius rather than clamp samples, so the kernel keeps its shape; docs/AUTHORS_CODE.md
// §2.2: radiusInPixels > ssMaxRadius). Uncapped, it is `radius` itself, bit for bit.
fn capped_radius(v: View, radius: f32, z: f32) -> f32 {
    if (MAX_RADIUS_PX > 0.0) {
        let per_unit = pixels_per_unit(v, z).y;
        if (radius * per_unit > MAX_RADIUS_PX) {
            return MAX_RADIUS_PX / per_unit;
        }
    }
    return radius;
}

// Unit vector from view-space point `p` towards the camera (along +Z when orthographic).
fn toward_camera(v: View, p: vec3<f32>) -> vec3<f32> {
    return select(normalize(-p), vec3<f32>(0.0, 0.0, 1.0), ORTHOGRAPHIC);
}

// Background (no geometry) is stored as linear depth 0 in the G-buffer.
fn is_background(z: f32) -> bool {
    return !(z > 0.0);
}
