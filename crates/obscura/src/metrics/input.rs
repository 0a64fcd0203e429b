//! The borrowed image view the metrics operate on, and shared input checks.

use super::MetricsError;

/// A borrowed single-channel `f32` image: row-major, top row first,
/// `data.len() == width * height`.
///
/// The fields are public for convenience, so an `Image` can be built by hand
/// with an inconsistent length; every metric re-checks the layout and returns
/// [`MetricsError::DataLength`] rather than panicking. [`Image::new`] performs
/// the same check at construction.
///
/// Values are not checked here: a depth image legitimately uses non-finite or
/// non-positive values for background, whereas the AO metrics reject
/// non-finite samples themselves.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Image<'a> {
    /// Number of columns.
    pub width: usize,
    /// Number of rows.
    pub height: usize,
    /// `width × height` samples, row-major, top row first.
    pub data: &'a [f32],
}

impl<'a> Image<'a> {
    /// Wraps `data` as a `width × height` image.
    ///
    /// # Errors
    /// [`MetricsError::Empty`] if `width` or `height` is 0;
    /// [`MetricsError::DataLength`] if `data.len() != width * height`.
    pub fn new(width: usize, height: usize, data: &'a [f32]) -> Result<Self, MetricsError> {
        let image = Image {
            width,
            height,
            data,
        };
        image.check_layout()?;
        Ok(image)
    }

    /// Non-empty, and `data.len() == width * height` without overflow.
    pub(super) fn check_layout(&self) -> Result<(), MetricsError> {
        if self.width == 0 || self.height == 0 {
            return Err(MetricsError::Empty {
                width: self.width,
                height: self.height,
            });
        }
        match self.width.checked_mul(self.height) {
            Some(n) if n == self.data.len() => Ok(()),
            _ => Err(MetricsError::DataLength {
                width: self.width,
                height: self.height,
                len: self.data.len(),
            }),
        }
    }

    /// Every sample is finite; `name` identifies the argument in the error.
    pub(super) fn check_finite(&self, name: &'static str) -> Result<(), MetricsError> {
        match self.data.iter().position(|v| !v.is_finite()) {
            None => Ok(()),
            Some(i) => Err(MetricsError::NonFinite {
                image: name,
                x: i % self.width,
                y: i / self.width,
            }),
        }
    }
}

/// Same `(width, height)`.
pub(super) fn check_same_size(a: &Image, b: &Image) -> Result<(), MetricsError> {
    if (a.width, a.height) == (b.width, b.height) {
        Ok(())
    } else {
        Err(MetricsError::SizeMismatch {
            expected: (a.width, a.height),
            found: (b.width, b.height),
        })
    }
}

/// The full check for two AO images compared pixel by pixel: valid layout,
/// same size, all samples finite.
pub(super) fn check_pair(
    a: &Image,
    b: &Image,
    name_a: &'static str,
    name_b: &'static str,
) -> Result<(), MetricsError> {
    a.check_layout()?;
    b.check_layout()?;
    check_same_size(a, b)?;
    a.check_finite(name_a)?;
    b.check_finite(name_b)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn new_checks_length_and_emptiness() {
        let data = [0.0f32; 6];
        let img = Image::new(3, 2, &data).unwrap();
        assert_eq!((img.width, img.height, img.data.len()), (3, 2, 6));
        assert_eq!(
            Image::new(4, 2, &data),
            Err(MetricsError::DataLength {
                width: 4,
                height: 2,
                len: 6
            })
        );
        assert_eq!(
            Image::new(0, 2, &[]),
            Err(MetricsError::Empty {
                width: 0,
                height: 2
            })
        );
        assert_eq!(
            Image::new(3, 0, &[]),
            Err(MetricsError::Empty {
                width: 3,
                height: 0
            })
        );
        // width * height overflowing usize must not wrap around to a
        // "matching" length.
        assert!(matches!(
            Image::new(usize::MAX, 2, &data),
            Err(MetricsError::DataLength { .. })
        ));
    }

    #[test]
    fn non_finite_values_are_located() {
        let data = [0.0, 0.5, 1.0, 0.25, f32::INFINITY, 0.0];
        let img = Image::new(3, 2, &data).unwrap();
        assert_eq!(
            img.check_finite("a"),
            Err(MetricsError::NonFinite {
                image: "a",
                x: 1,
                y: 1
            })
        );
    }
}
