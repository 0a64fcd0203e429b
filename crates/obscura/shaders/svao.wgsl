// Stenciled VAO (seed 000 §3.8): what phase 1 stores per visible pixel for phase 2, and how
// phase 2 finds its work (shared by svao_phase1.wgsl and svao_phase2.wgsl).

struct SvaoPixel {
    // Samples that still need rays.
    mask: u32,
    // Sum of the other samples' free column fractions, and of all clipped column fractions.
    sum: f32,
    clipped_sum: f32,
    _pad: u32,
}

// true: phase 1 compacts flagged pixels into a work list for an indirect phase 2;
// false: phase 2 walks every pixel and returns at once where the mask is empty.
override COMPACT: bool = true;
