// The cosine-weighted visibility inside one GTAO slice (Jimenez et al. 2016, Eq. 10): with θ the
// angle from the view vector V in the slice plane and γ the angle of the normal projected onto
// the slice, the slice's visible directions between angles a ≤ b weigh
//     ∫_a^b cos(θ − γ) |sin θ| dθ = S(b) − S(a),    S(θ) = sign(θ) · ¼ (−cos(2θ − γ) + cos γ + 2θ sin γ)
// (S the signed integral from 0; the |sin θ| is the slice parametrisation's Jacobian), and the
// whole hemisphere of the slice, θ from γ − π/2 to γ + π/2, weighs cos γ + γ sin γ. Shared by the
// GTAO estimator (two horizons) and GTAO-VB's cosine-weighted sectors.

// ¼ (−cos(2h − γ) + cos γ + 2h sin γ): the visible weight between V and a horizon at angle h,
// either side.
fn side_visibility(h: f32, gamma: f32) -> f32 {
    return 0.25 * (-cos(2.0 * h - gamma) + cos(gamma) + 2.0 * h * sin(gamma));
}

// The visible weight of the slice's directions between angles a ≤ b.
fn span_visibility(a: f32, b: f32, gamma: f32) -> f32 {
    return sign(b) * side_visibility(b, gamma) - sign(a) * side_visibility(a, gamma);
}

// The weight of the slice's whole hemisphere: both horizons on the tangent plane.
fn open_slice_visibility(gamma: f32) -> f32 {
    return cos(gamma) + gamma * sin(gamma);
}

// Bent normals (seed 001 §4, Fig. 9; `bent_normals`): the weighted mean of the visible directions
// of a slice, as (tangent, V) components of ∫ ω(θ) weight dθ with ω(θ) = sin θ·tangent + cos θ·V.
// Angles are passed as (sin, cos) pairs: the callers have them without trigonometry (GTAO from
// its horizon cosines, the hemisphere's edges from γ). Cosine-weighted (GTAO, GTAO-VB's cosine
// sectors; ours, derived as slice_visibility above): the signed integral from 0,
// G(θ) = sign(θ)·F(θ), with
//     F_t(θ) = cos γ · sin³θ/3 + sin γ · (2/3 − cos θ + cos³θ/3)
//     F_v(θ) = cos γ · (1 − cos³θ)/3 + sin γ · sin³θ/3,
// the antiderivatives of cos(θ − γ)·sin θ·(sin θ, cos θ) from 0; θ in [−π, π], so sign(θ) is
// the sign of sin θ.
fn signed_bent(theta: vec2<f32>, gamma: vec2<f32>) -> vec2<f32> {
    let s = theta.x;
    let c = theta.y;
    let s3 = s * s * s;
    let c3 = c * c * c;
    let f = vec2<f32>(
        gamma.y * s3 / 3.0 + gamma.x * (2.0 / 3.0 - c + c3 / 3.0),
        gamma.y * (1.0 - c3) / 3.0 + gamma.x * s3 / 3.0,
    );
    return sign(s) * f;
}

// The cosine-weighted bent vector of the slice's directions between angles a ≤ b ((sin, cos)
// pairs; γ likewise).
fn span_bent(a: vec2<f32>, b: vec2<f32>, gamma: vec2<f32>) -> vec2<f32> {
    return signed_bent(b, gamma) - signed_bent(a, gamma);
}

// The uniformly weighted bent vector (∫ ω dθ) of the directions between a ≤ b ((sin, cos)
// pairs): GTAO-VB's sectors.
fn span_direction(a: vec2<f32>, b: vec2<f32>) -> vec2<f32> {
    return vec2<f32>(a.y - b.y, b.x - a.x);
}

// The edges of the slice's hemisphere, γ − π/2 and γ + π/2, as (sin, cos) pairs from γ's.
fn hemisphere_edges(gamma: vec2<f32>) -> array<vec2<f32>, 2> {
    return array<vec2<f32>, 2>(vec2<f32>(-gamma.y, gamma.x), vec2<f32>(gamma.y, -gamma.x));
}

// The cosine-weighted bent vector of the slice's whole hemisphere, span_bent between its edges.
// With cos γ > 0 (a normal facing the camera) the edges' sines are cos γ and −cos γ, and
// G(γ + π/2) − G(γ − π/2) = F(γ + π/2) + F(γ − π/2) reduces to (4/3 sin γ, 2/3 cos γ); other
// normals take the general form.
fn open_slice_bent(gamma: vec2<f32>) -> vec2<f32> {
    if (gamma.y > 0.0) {
        return vec2<f32>(4.0 / 3.0 * gamma.x, 2.0 / 3.0 * gamma.y);
    }
    let edges = hemisphere_edges(gamma);
    return span_bent(edges[0], edges[1], gamma);
}
