// Schedule "two-phase" (seed 000 §3.8 RT-SVAO, §3.9 SD-SVAO): what phase 1 stores per visible pixel
// for phase 2, and how phase 2 finds its work (shared by two_phase_1.wgsl and two_phase_2.wgsl).
// Works for any estimator with at most 32 samples (one mask bit each).

struct TwoPhasePixel {
    // Samples the source still has to resolve.
    mask: u32,
    // The estimator's partial state over the other samples.
    accum: EstimatorAccum,
}

// true: phase 1 compacts flagged pixels into a work list for an indirect phase 2;
// false: phase 2 walks every pixel and returns at once where the mask is empty.
override COMPACT: bool = true;
