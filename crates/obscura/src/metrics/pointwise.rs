//! Pointwise error metrics: MSE, MAE, PSNR.

use super::input::check_pair;
use super::sum::Sum;
use super::{Image, MetricsError};

/// Mean squared error `Σ (a − b)² / n`, accumulated in `f64`.
///
/// # Errors
/// Invalid layout, size mismatch, or a non-finite sample in either image.
pub fn mse(a: &Image, b: &Image) -> Result<f64, MetricsError> {
    check_pair(a, b, "a", "b")?;
    // Differences are taken in f64 so that the squared error of two nearby
    // f32 values is not rounded to f32 precision before summing.
    let sum: Sum = a
        .data
        .iter()
        .zip(b.data)
        .map(|(&x, &y)| {
            let d = f64::from(x) - f64::from(y);
            d * d
        })
        .collect();
    Ok(sum.value() / a.data.len() as f64)
}

/// Mean absolute error `Σ |a − b| / n`, accumulated in `f64`.
///
/// # Errors
/// Invalid layout, size mismatch, or a non-finite sample in either image.
pub fn mae(a: &Image, b: &Image) -> Result<f64, MetricsError> {
    check_pair(a, b, "a", "b")?;
    let sum: Sum = a
        .data
        .iter()
        .zip(b.data)
        .map(|(&x, &y)| (f64::from(x) - f64::from(y)).abs())
        .collect();
    Ok(sum.value() / a.data.len() as f64)
}

/// Peak signal-to-noise ratio in dB for data range `L = 1`:
/// `10 · log10(L² / MSE)`. Identical images give `f64::INFINITY`.
///
/// # Errors
/// As [`mse`].
pub fn psnr(a: &Image, b: &Image) -> Result<f64, MetricsError> {
    mse(a, b).map(psnr_from_mse)
}

/// `10 · log10(1 / mse)`, with `mse == 0` mapped to `+∞` explicitly (rather
/// than relying on `log10(inf)`) so the intent is visible.
pub(super) fn psnr_from_mse(mse: f64) -> f64 {
    if mse == 0.0 {
        f64::INFINITY
    } else {
        -10.0 * mse.log10()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_by_two_hand_computed() {
        // a − b = [0 − 0.5, 0.25 − 0.25, 0.5 − 0, 1 − 0.75] = [−0.5, 0, 0.5, 0.25]
        // squares: 0.25 + 0 + 0.25 + 0.0625 = 0.5625 → MSE = 0.5625 / 4 = 0.140625
        // |·|:     0.5 + 0 + 0.5 + 0.25     = 1.25   → MAE = 1.25 / 4   = 0.3125
        // PSNR = 10·log10(1 / 0.140625) = 10·log10(64 / 9) = 8.519374645445623 dB
        // All values are dyadic, so MSE and MAE are exact in binary floating point.
        let a = [0.0, 0.25, 0.5, 1.0];
        let b = [0.5, 0.25, 0.0, 0.75];
        let a = Image::new(2, 2, &a).unwrap();
        let b = Image::new(2, 2, &b).unwrap();
        assert_eq!(mse(&a, &b).unwrap(), 0.140625);
        assert_eq!(mae(&a, &b).unwrap(), 0.3125);
        assert!((psnr(&a, &b).unwrap() - 8.519374645445623).abs() < 1e-12);
        // Symmetric in the arguments.
        assert_eq!(mse(&b, &a).unwrap(), 0.140625);
        assert_eq!(mae(&b, &a).unwrap(), 0.3125);
    }

    #[test]
    fn three_by_three_single_outlier() {
        // One pixel differs by 0.5, eight are equal:
        // MSE = 0.25 / 9, MAE = 0.5 / 9, PSNR = 10·log10(9 / 0.25) = 10·log10(36)
        //     = 15.563025007672874 dB.
        let a = [0.5f32; 9];
        let mut b = [0.5f32; 9];
        b[4] = 1.0;
        let a = Image::new(3, 3, &a).unwrap();
        let b = Image::new(3, 3, &b).unwrap();
        assert!((mse(&a, &b).unwrap() - 0.25 / 9.0).abs() < 1e-15);
        assert!((mae(&a, &b).unwrap() - 0.5 / 9.0).abs() < 1e-15);
        assert!((psnr(&a, &b).unwrap() - 15.563025007672874).abs() < 1e-12);
    }

    #[test]
    fn uniform_half_offset_gives_six_db() {
        // Every pixel off by 0.5: MSE = 0.25, PSNR = 10·log10(4) = 6.020599913279624 dB.
        let a = [0.0f32, 0.25, 0.5, 0.125];
        let b = [0.5f32, 0.75, 0.0, 0.625];
        let a = Image::new(4, 1, &a).unwrap();
        let b = Image::new(4, 1, &b).unwrap();
        assert_eq!(mse(&a, &b).unwrap(), 0.25);
        assert_eq!(mae(&a, &b).unwrap(), 0.5);
        assert!((psnr(&a, &b).unwrap() - 6.020599913279624).abs() < 1e-12);
    }

    #[test]
    fn identical_images_have_infinite_psnr() {
        let a = [0.1f32, 0.2, 0.3, 0.4, 0.5, 0.6];
        let a = Image::new(3, 2, &a).unwrap();
        assert_eq!(mse(&a, &a).unwrap(), 0.0);
        assert_eq!(mae(&a, &a).unwrap(), 0.0);
        assert_eq!(psnr(&a, &a).unwrap(), f64::INFINITY);
    }

    #[test]
    fn accumulates_in_f64_on_large_images() {
        // 1920×1080 pixels each off by d = 0.1f32. The exact answers are d²
        // and d. An f32 running sum would be visibly wrong here, and even a
        // plain f64 running sum misses 1e-12 relative (its rounding error
        // grows with the pixel count); the compensated sum does not.
        let (w, h) = (1920, 1080);
        let a = vec![0.1f32; w * h];
        let b = vec![0.0f32; w * h];
        let a = Image::new(w, h, &a).unwrap();
        let b = Image::new(w, h, &b).unwrap();
        let d = f64::from(0.1f32);
        assert!((mse(&a, &b).unwrap() / (d * d) - 1.0).abs() < 1e-12);
        assert!((mae(&a, &b).unwrap() / d - 1.0).abs() < 1e-12);
    }

    #[test]
    fn errors_instead_of_panics() {
        let a = [0.5f32; 6];
        let b = [0.5f32; 6];
        let a32 = Image::new(3, 2, &a).unwrap();
        let b23 = Image::new(2, 3, &b).unwrap();
        let expected = Err(MetricsError::SizeMismatch {
            expected: (3, 2),
            found: (2, 3),
        });
        assert_eq!(mse(&a32, &b23), expected);
        assert_eq!(mae(&a32, &b23), expected);
        assert_eq!(psnr(&a32, &b23), expected);

        let mut n = [0.5f32; 6];
        n[3] = f32::NAN;
        let n = Image::new(3, 2, &n).unwrap();
        let nan_err = Err(MetricsError::NonFinite {
            image: "b",
            x: 0,
            y: 1,
        });
        assert_eq!(mse(&a32, &n), nan_err);
        assert_eq!(mae(&a32, &n), nan_err);
        assert_eq!(psnr(&a32, &n), nan_err);
        let mut inf = [0.5f32; 6];
        inf[0] = f32::NEG_INFINITY;
        let inf = Image::new(3, 2, &inf).unwrap();
        assert!(matches!(
            mse(&inf, &a32),
            Err(MetricsError::NonFinite { image: "a", .. })
        ));

        // A hand-built Image with an inconsistent length is caught too.
        let bad = Image {
            width: 4,
            height: 2,
            data: &a,
        };
        assert!(matches!(
            mse(&bad, &bad),
            Err(MetricsError::DataLength { .. })
        ));
        let empty = Image {
            width: 0,
            height: 0,
            data: &[],
        };
        assert!(matches!(
            mae(&empty, &empty),
            Err(MetricsError::Empty { .. })
        ));
    }
}
