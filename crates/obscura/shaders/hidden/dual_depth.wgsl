// Hidden-depth source "dual depth" (`vao-dual`, seed 000 §2.1 / seed-code-notes §1.2): as
// depth_buffer.wgsl, but a sample whose first surface is occluded (beyond the constant area) also
// reads the second depth layer from depth peeling and keeps the lower visibility of the two.

@group(0) @binding(5) var second_depth: texture_2d<f32>;

fn sample_free_length(f: VaoFrame, c: VaoColumn) -> f32 {
    let full = c.start - c.end;
    let sample_pixel = sample_pixel_of(c);
    if (all(sample_pixel == f.pixel)) {
        return full;
    }
    let z = textureLoad(depth_tex, sample_pixel, 0).r;
    if (is_background(z)) {
        return full;
    }
    let centre = vec2<f32>(sample_pixel) + 0.5;
    let height = column_height(f, c, pixel_to_view(view, centre, z));
    let first = column_visibility(height, c.start, c.end);
    if (height <= (1.0 + params.thickness) * params.radius) {
        return first;
    }
    let z2 = textureLoad(second_depth, sample_pixel, 0).r;
    if (is_background(z2)) {
        return first;
    }
    let second = column_visibility(column_height(f, c, pixel_to_view(view, centre, z2)), c.start, c.end);
    return min(first, second);
}
