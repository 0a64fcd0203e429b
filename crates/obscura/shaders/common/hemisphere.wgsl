// The hemisphere model's rays, written once for the ground truth (reference/reference.wgsl) and
// the `hemisphere` estimator (estimators/hemisphere.wgsl): ray i of a set of n is the Hammersley
// point i of n (stratified in both dimensions), shifted by a per-pixel Cranley-Patterson rotation
// from a PCG hash of the seed and the pixel, and lifted to a cosine-weighted direction (Malley's
// method: a uniform point on the unit disc raised to the hemisphere). Mirrored on the CPU by
// `hammersley`, `pixel_rotation_2d` and `hemisphere_ao_at` in src/reference/ground_truth.rs.
//
// Why this set (ours): it is the ground truth's, so the estimator with the same seed and count
// traces the very rays the reference traces (tests/it/hemisphere.rs holds them equal); n points
// of it are stratified for any n, and a new seed per frame (the frame number) rotates each
// pixel's set independently, so frames average like independent estimates.
//
// Needs common/hash.wgsl in front.

// Per-pixel rotation in [0, 1)² from the seed and the pixel.
fn pixel_rotation_2d(seed: u32, x: u32, y: u32) -> vec2<f32> {
    let h1 = pcg_hash(seed ^ pcg_hash(x + pcg_hash(y)));
    let h2 = pcg_hash(h1);
    return vec2<f32>(f32(h1 >> 8u), f32(h2 >> 8u)) / 16777216.0;
}

fn hammersley(i: u32, n: u32) -> vec2<f32> {
    return vec2<f32>((f32(i) + 0.5) / f32(n), f32(reverseBits(i)) * 2.3283064365386963e-10);
}

// Ray i of n about unit normal `n` (basis from common/basis.wgsl's orthonormal_basis(n)),
// cosine-weighted.
fn hemisphere_direction(i: u32, count: u32, rotation: vec2<f32>, n: vec3<f32>, basis: array<vec3<f32>, 2>) -> vec3<f32> {
    let h = hammersley(i, count) + rotation;
    let u = h - floor(h);
    let r = sqrt(u.x);
    let phi = 6.283185307179586 * u.y;
    let local = vec3<f32>(r * cos(phi), r * sin(phi), sqrt(max(1.0 - u.x, 0.0)));
    return basis[0] * local.x + basis[1] * local.y + n * local.z;
}
