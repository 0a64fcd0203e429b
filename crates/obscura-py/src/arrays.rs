//! numpy arrays out: C-contiguous float32, rows top to bottom, as the library's images are.

use glam::Mat4;
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray2, PyArray3};
use pyo3::prelude::*;

/// A `height × width` image (row-major) as a C-contiguous float32 array of shape
/// (height, width).
pub fn image<'py>(
    py: Python<'py>,
    values: Vec<f32>,
    width: u32,
    height: u32,
) -> PyResult<Bound<'py, PyArray2<f32>>> {
    Array2::from_shape_vec((height as usize, width as usize), values)
        .map(|a| a.into_pyarray(py))
        .map_err(|e| crate::errors::input(format!("image of the wrong size: {e}")))
}

/// Vectors of an image as a C-contiguous float32 array of shape (height, width, 3).
pub fn vectors<'py>(
    py: Python<'py>,
    values: &[glam::Vec3],
    width: u32,
    height: u32,
) -> PyResult<Bound<'py, PyArray3<f32>>> {
    let flat: Vec<f32> = values.iter().flat_map(|v| v.to_array()).collect();
    numpy::ndarray::Array3::from_shape_vec((height as usize, width as usize, 3), flat)
        .map(|a| a.into_pyarray(py))
        .map_err(|e| crate::errors::input(format!("image of the wrong size: {e}")))
}

/// A matrix as numpy reads one: shape (4, 4), `m[row][column]`, so that `m @ v` transforms a
/// column vector as glam's `m * v` does.
pub fn matrix(py: Python<'_>, m: Mat4) -> Bound<'_, PyArray2<f32>> {
    let rows = m.transpose().to_cols_array();
    Array2::from_shape_vec((4, 4), rows.to_vec())
        .expect("16 values make a 4×4 matrix")
        .into_pyarray(py)
}

/// A (4, 4) matrix given as numpy reads one (`m[row][column]`).
pub fn mat4(rows: [[f32; 4]; 4]) -> Mat4 {
    Mat4::from_cols_array_2d(&rows).transpose()
}
