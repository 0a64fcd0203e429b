// Bent normals (seed 001 §4, Fig. 9; `bent_normals`): the weighted mean unoccluded direction, from
// an estimator's sums of bent vectors over what it found visible and over the whole open
// hemisphere (or ball), each a view-space vector: n·|open| + (visible − open), normalised.
// Unoccluded, visible = open and the bent normal is the normal exactly, with any number of samples
// or slices (the plain sum of a few open vectors leans off the normal on a tilted plane); as the
// samples cover the hemisphere, open tends to |open|·n and this to the plain mean visible
// direction (as our AO's visible / open ratios). Shared by GTAO, GTAO-VB (slice_visibility.wgsl's
// bent vectors) and VAO (its columns' free centroids).
fn bent_from_sums(normal: vec3<f32>, visible: vec3<f32>, open: vec3<f32>) -> vec3<f32> {
    let bent = normal * length(open) + (visible - open);
    let len = length(bent);
    return select(normal, bent / len, len > 1e-12);
}
