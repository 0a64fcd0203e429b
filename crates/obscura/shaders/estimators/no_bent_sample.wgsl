// The estimator contract's per-sample bent vector (docs/ARCHITECTURE.md) for estimators without
// one: the slice estimators form their bent normals from the accumulator, and the others have
// none (no_bent_normal.wgsl). Appended by their Rust modules.

fn estimator_bent_sample(p: EstimatorPixel, s: EstimatorSample, value: EstimatorValue) -> vec3<f32> {
    return vec3<f32>(0.0);
}
