// Hidden-depth source "none": the occluder of a VAO sample is the first depth layer at the pixel
// the sample falls in (clamped to the framebuffer, guard band included). Seed 000 §3.5.

fn sample_free_length(f: VaoFrame, c: VaoColumn) -> f32 {
    let full = c.start - c.end;
    let sample_pixel = sample_pixel_of(c);
    // A sample that snaps to the shading pixel itself counts as fully visible.
    if (all(sample_pixel == f.pixel)) {
        return full;
    }
    let z = textureLoad(depth_tex, sample_pixel, 0).r;
    if (is_background(z)) {
        return full;
    }
    let occluder = pixel_to_view(view, vec2<f32>(sample_pixel) + 0.5, z);
    return column_visibility(column_height(f, c, occluder), c.start, c.end);
}
