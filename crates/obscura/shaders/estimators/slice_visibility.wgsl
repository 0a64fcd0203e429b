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
