// The 4×4 per-pixel pattern every estimator turns its sample table by (src/estimators/mod.rs
// `bayer_table`; VAO's rotation table is made the same way): the pixel's table entry and the
// rotation itself.

// Index of visible pixel `id` in a 4×4 pattern table: x % 4 + 4 (y % 4), turned by the frame's
// `pattern_offset` (0 unless temporal accumulation is on; the frame's `view` uniform).
fn pattern_index(id: vec2<u32>) -> u32 {
    return ((id.x % 4u) + 4u * (id.y % 4u) + view.pattern_offset) % 16u;
}

// `v` turned by the angle whose (cos, sin) is `cs`: a sample table direction by a pixel's
// pattern rotation.
fn rotate_by(v: vec2<f32>, cs: vec2<f32>) -> vec2<f32> {
    return vec2<f32>(v.x * cs.x - v.y * cs.y, v.x * cs.y + v.y * cs.x);
}
