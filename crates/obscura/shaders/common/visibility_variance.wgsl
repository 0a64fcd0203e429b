// How uncertain a pixel's mean hemisphere visibility is after `rays` rays (ours, issue 58; read by
// the ray budget, filter/ray_budget.wgsl, and the à-trous denoiser, filter/atrous.wgsl). Each
// ray's visibility lies in [0, 1] with mean a, so its variance is at most a(1 − a) (equal for
// blocked-or-free rays) and the mean of m rays' at most a(1 − a)/m. Taken with one free and one
// blocked ray of prior (Laplace's rule of succession, a' = (a m + 1)/(m + 2)), so that a pixel
// seen fully open or fully blocked after a few rays is not taken as certain.
fn visibility_variance(a: f32, rays: f32) -> f32 {
    let prior = (a * rays + 1.0) / (rays + 2.0);
    return prior * (1.0 - prior) / (rays + 2.0);
}
