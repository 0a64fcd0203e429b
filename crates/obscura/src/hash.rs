//! Hashes. The PCG hash (Jarzynski and Olano, "Hash Functions for GPU Rendering", JCGT 9(3), 2020): the CPU
//! twin of `shaders/common/hash.wgsl`, for the ground truth's per-pixel rotation and the stochastic
//! depth map's seeds. Written out because it is four lines and must match the WGSL bit for bit.

/// The PCG hash of `v` (JCGT 9(3) 2020): a well-mixed `u32`, equal to `pcg_hash` in WGSL.
pub fn pcg_hash(v: u32) -> u32 {
    let state = v.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
    let word = ((state >> ((state >> 28) + 4)) ^ state).wrapping_mul(277_803_737);
    (word >> 22) ^ word
}

/// 64-bit FNV-1a over bytes: deterministic across runs and builds (std's hasher is not promised to
/// be), for cache keys and scene fingerprints. Written out because it is two lines.
#[derive(Clone, Copy, Debug)]
pub struct Fnv1a(pub u64);

impl Default for Fnv1a {
    fn default() -> Self {
        Self(0xcbf2_9ce4_8422_2325)
    }
}

impl Fnv1a {
    /// Feed `bytes` into the hash (the state is `self.0`).
    pub fn bytes(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0 ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3);
        }
    }

    /// The hash of `bytes` alone.
    pub fn of(bytes: &[u8]) -> u64 {
        let mut h = Self::default();
        h.bytes(bytes);
        h.0
    }
}
