// BVH rays without phase 1's proofs (bvh_rays.wgsl; single pass, and phase 2 of the two-phase
// row, which traces what phase 1 left): every ray is traced.

fn screen_proof(p: EstimatorPixel, s: EstimatorSample) -> u32 {
    return PROOF_NONE;
}
