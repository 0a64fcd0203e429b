// The estimator contract's depth interval (docs/ARCHITECTURE.md) for estimators that do not
// narrow it: every depth along the sample's ray may matter, so the ray-traced stochastic depth
// map traces the whole ray for them. Appended by their Rust modules.

fn estimator_depth_interval(p: EstimatorPixel, s: EstimatorSample, px: vec2<f32>) -> vec2<f32> {
    return vec2<f32>(0.0, 3.0e38);
}
