//! The error type shared by all metrics.

use std::fmt;

/// Why a metric could not be computed.
///
/// Every metric validates its inputs and returns one of these instead of
/// panicking or silently producing NaN.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MetricsError {
    /// `data.len()` is not `width × height` (or that product overflows).
    DataLength {
        /// Declared width.
        width: usize,
        /// Declared height.
        height: usize,
        /// Actual number of samples.
        len: usize,
    },
    /// The image has no pixels (zero width or zero height); every metric is a
    /// mean over pixels, which would be 0/0.
    Empty {
        /// Declared width.
        width: usize,
        /// Declared height.
        height: usize,
    },
    /// Two images that must be compared pixel by pixel differ in size.
    SizeMismatch {
        /// `(width, height)` of the first image.
        expected: (usize, usize),
        /// `(width, height)` of the other image.
        found: (usize, usize),
    },
    /// An AO image holds NaN or ±∞ (depth images may; there it means
    /// background).
    NonFinite {
        /// Which argument: `"a"`, `"b"`, `"technique"` or `"reference"`.
        image: &'static str,
        /// Column of the first offending pixel.
        x: usize,
        /// Row of the first offending pixel.
        y: usize,
    },
    /// The image is smaller than the metric's window in some dimension (SSIM
    /// needs at least 11×11 so that the valid region is non-empty).
    WindowTooLarge {
        /// Window side length.
        window: usize,
        /// Image width.
        width: usize,
        /// Image height.
        height: usize,
    },
    /// A scalar parameter is out of its domain (e.g. a negative or NaN
    /// `relative_jump`).
    InvalidParameter {
        /// Parameter name.
        name: &'static str,
        /// What is required of it.
        requirement: &'static str,
    },
}

impl fmt::Display for MetricsError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            MetricsError::DataLength { width, height, len } => write!(
                f,
                "image data has {len} samples but {width}x{height} needs width*height"
            ),
            MetricsError::Empty { width, height } => {
                write!(f, "image is empty ({width}x{height})")
            }
            MetricsError::SizeMismatch { expected, found } => write!(
                f,
                "image sizes differ: {}x{} vs {}x{}",
                expected.0, expected.1, found.0, found.1
            ),
            MetricsError::NonFinite { image, x, y } => {
                write!(f, "image `{image}` has a non-finite value at ({x}, {y})")
            }
            MetricsError::WindowTooLarge {
                window,
                width,
                height,
            } => write!(
                f,
                "{window}x{window} window does not fit in a {width}x{height} image"
            ),
            MetricsError::InvalidParameter { name, requirement } => {
                write!(f, "invalid parameter `{name}`: must be {requirement}")
            }
        }
    }
}

impl std::error::Error for MetricsError {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn display_is_informative_and_error_trait_is_implemented() {
        let e = MetricsError::SizeMismatch {
            expected: (4, 3),
            found: (3, 4),
        };
        assert_eq!(e.to_string(), "image sizes differ: 4x3 vs 3x4");
        let boxed: Box<dyn std::error::Error + Send + Sync> = Box::new(e);
        assert!(boxed.source().is_none());
        let e = MetricsError::NonFinite {
            image: "technique",
            x: 2,
            y: 7,
        };
        assert_eq!(
            e.to_string(),
            "image `technique` has a non-finite value at (2, 7)"
        );
        let e = MetricsError::WindowTooLarge {
            window: 11,
            width: 10,
            height: 40,
        };
        assert_eq!(e.to_string(), "11x11 window does not fit in a 10x40 image");
    }
}
