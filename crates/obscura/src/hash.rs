//! The PCG hash (Jarzynski and Olano, "Hash Functions for GPU Rendering", JCGT 9(3), 2020): the CPU
//! twin of `shaders/common/hash.wgsl`, for the ground truth's per-pixel rotation and the stochastic
//! depth map's seeds. Written out because it is four lines and must match the WGSL bit for bit.

pub fn pcg_hash(v: u32) -> u32 {
    let state = v.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
    let word = ((state >> ((state >> 28) + 4)) ^ state).wrapping_mul(277_803_737);
    (word >> 22) ^ word
}
