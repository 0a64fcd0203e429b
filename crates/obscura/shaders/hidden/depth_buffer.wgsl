// Hidden-depth source "none": the occluder of a VAO sample is the first depth layer at the pixel
// the sample falls in (clamped to the framebuffer, guard band included). Seed 000 §3.5.

fn sample_free_length(f: VaoFrame, c: VaoColumn) -> f32 {
    return depth_buffer_lookup(f, c).free;
}
