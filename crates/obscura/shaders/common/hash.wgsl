// PCG hash (Jarzynski and Olano, "Hash Functions for GPU Rendering", JCGT 9(3), 2020), mirrored by
// `pcg_hash` in src/reference/ground_truth.rs: the ground truth's per-pixel rotation and the
// stochastic depth map's per-fragment random numbers (WGSL has no 64-bit integers).

fn pcg_hash(v: u32) -> u32 {
    let state = v * 747796405u + 2891336453u;
    let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// A uniform number in [0, 1) from the top 24 bits of a hash.
fn hash_to_unit(h: u32) -> f32 {
    return f32(h >> 8u) / 16777216.0;
}
