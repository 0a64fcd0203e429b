// The estimator contract's bent normal (docs/ARCHITECTURE.md) for estimators that report none
// (Estimator::bent_normals false: `bent_normals` is refused for them by name). Appended by their
// Rust modules, with no_bent_sample.wgsl.

fn estimator_bent_normal(
    p: EstimatorPixel,
    acc: EstimatorAccum,
    sample_visible: vec3<f32>,
    sample_open: vec3<f32>,
) -> vec3<f32> {
    return vec3<f32>(0.0);
}
