// Orthonormal basis around a unit vector without branches on the vector's direction:
// Duff et al., "Building an Orthonormal Basis, Revisited", JCGT 6(1), 2017, Listing 3.
// Mirrored by `orthonormal_basis` in src/estimators/vao.rs.
fn orthonormal_basis(n: vec3<f32>) -> array<vec3<f32>, 2> {
    let s = select(-1.0, 1.0, n.z >= 0.0);
    let a = -1.0 / (s + n.z);
    let b = n.x * n.y * a;
    return array<vec3<f32>, 2>(
        vec3<f32>(1.0 + s * n.x * n.x * a, s * b, -s * n.x),
        vec3<f32>(b, s + n.y * n.y * a, -n.y),
    );
}
