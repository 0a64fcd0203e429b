//! Between Bevy and obscura: matrices (Bevy 0.19 uses glam 0.32, obscura glam 0.34; the same
//! column-major layout).

/// A Bevy matrix as obscura's.
pub(crate) fn mat4(m: bevy::math::Mat4) -> glam::Mat4 {
    glam::Mat4::from_cols_array(&m.to_cols_array())
}
