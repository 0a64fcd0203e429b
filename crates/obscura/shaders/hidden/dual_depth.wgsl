// Hidden-depth source "dual depth" (`vao-dual`, seed 000 §2.1 / seed-code-notes §1.2): as
// depth_buffer.wgsl, but a sample whose first surface is occluded (beyond the constant area) also
// reads the second depth layer from depth peeling and keeps the lower visibility of the two.

@group(0) @binding(5) var second_depth: texture_2d<f32>;

fn sample_free_length(f: VaoFrame, c: VaoColumn) -> f32 {
    let l = depth_buffer_lookup(f, c);
    if (!l.trace) {
        return l.free;
    }
    let z2 = textureLoad(second_depth, vec2<u32>(l.px), 0).r;
    if (is_background(z2)) {
        return l.free;
    }
    let second = column_visibility(column_height(f, c, pixel_to_view(view, l.px, z2)), c.start, c.end);
    return min(l.free, second);
}
