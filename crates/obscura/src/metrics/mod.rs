//! Image-quality metrics for comparing an ambient-occlusion (AO) technique
//! against a ray-traced reference.
//!
//! All images are single-channel `f32`, row-major, top row first, nominally in
//! `[0, 1]` with 1 = unoccluded. Every metric accumulates in `f64` (with
//! compensated summation for the per-pixel means). Values outside `[0, 1]`
//! are accepted (the data range is *assumed* to be 1, not measured);
//! non-finite values in an AO image are rejected with
//! [`MetricsError::NonFinite`].
//!
//! # Pointwise metrics
//! [`mse`], [`mae`] and [`psnr`] (data range `L = 1`, so
//! `PSNR = 10·log10(1 / MSE)`; identical images give `f64::INFINITY`).
//!
//! # SSIM
//! [`ssim()`] / [`ssim_map`] implement the structural similarity index of
//! Z. Wang, A. C. Bovik, H. R. Sheikh and E. P. Simoncelli, "Image quality
//! assessment: from error visibility to structural similarity", *IEEE
//! Transactions on Image Processing* 13(4), pp. 600–612, 2004:
//!
//! ```text
//! SSIM(x, y) = (2·μx·μy + C1)(2·σxy + C2) / ((μx² + μy² + C1)(σx² + σy² + C2))
//! ```
//!
//! * window: 11×11 Gaussian, σ = 1.5, weights normalised to sum 1 (built as the
//!   outer product of a normalised 1-D kernel, which is the same thing);
//! * `K1 = 0.01`, `K2 = 0.03`, `L = 1`, so `C1 = (K1·L)² = 1e-4` and
//!   `C2 = (K2·L)² = 9e-4`;
//! * moments are *population* (weighted, not sample-corrected) statistics;
//! * boundary handling: no padding. The SSIM map is evaluated only where the
//!   whole window lies inside the image (the "valid" region, size
//!   `(w − 10) × (h − 10)`), and the mean SSIM is the plain mean of that map.
//!   Images smaller than 11×11 are an error ([`MetricsError::WindowTooLarge`]).
//!
//! This matches scikit-image's
//! `structural_similarity(a, b, data_range=1, gaussian_weights=True,
//! sigma=1.5, use_sample_covariance=False)` (which filters with reflect padding
//! but then crops the 5-pixel border before averaging) on `float64` input; the
//! tests check agreement to 1e-6 against values computed with scikit-image.
//!
//! # Halo error
//! [`halo_error`] measures bright/dark halos next to depth discontinuities — the
//! characteristic artefact of screen-space AO. See [`discontinuity_mask`] and
//! [`halo_band`] for the exact definitions.
//!
//! # Temporal metrics
//! [`temporal`]: temporal error and popping along a camera path, pixels matched between frames
//! by reprojection (definitions in that module).

mod error;
mod halo;
// Not named `image`, so that it cannot be confused with the `image` crate the
// host crate depends on.
mod input;
mod pointwise;
mod ssim;
mod sum;
pub mod temporal;

// `self::` keeps these imports unambiguous whatever extern crates the host
// crate has.
pub use self::error::MetricsError;
pub use self::halo::{discontinuity_mask, halo_band, halo_error, has_geometry, HaloError};
pub use self::input::Image;
pub use self::pointwise::{mae, mse, psnr};
pub use self::ssim::{
    ssim, ssim_map, SSIM_C1, SSIM_C2, SSIM_K1, SSIM_K2, SSIM_L, SSIM_SIGMA, SSIM_WINDOW,
};

/// All metrics of one technique image against the reference, in one call.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Summary {
    /// Mean squared error, see [`mse`].
    pub mse: f64,
    /// Mean absolute error, see [`mae`].
    pub mae: f64,
    /// Peak signal-to-noise ratio in dB (data range 1), see [`psnr`].
    pub psnr: f64,
    /// Mean SSIM over the valid region, see [`ssim()`].
    pub ssim: f64,
    /// Mean positive error over the halo band, see [`HaloError::bright`].
    pub halo_bright: f64,
    /// Mean negative error over the halo band (≤ 0), see [`HaloError::dark`].
    pub halo_dark: f64,
}

/// Computes every metric of `technique` against `reference`; `depth`,
/// `radius_px` and `relative_jump` define the halo band (see [`halo_error`]).
///
/// All three images must have the same size, which must be at least 11×11
/// (the SSIM window).
pub fn summarize(
    technique: &Image,
    reference: &Image,
    depth: &Image,
    radius_px: usize,
    relative_jump: f32,
) -> Result<Summary, MetricsError> {
    // Validate everything up front so that a bad input fails before any of
    // the (comparatively expensive) metrics run.
    input::check_pair(technique, reference, "technique", "reference")?;
    depth.check_layout()?;
    input::check_same_size(technique, depth)?;
    ssim::check_window_fits(technique)?;

    let mse = mse(technique, reference)?;
    let halo = halo_error(technique, reference, depth, radius_px, relative_jump)?;
    Ok(Summary {
        mse,
        mae: mae(technique, reference)?,
        // Derived from the MSE above rather than recomputed: same value, one
        // pass fewer.
        psnr: pointwise::psnr_from_mse(mse),
        ssim: ssim(technique, reference)?,
        halo_bright: halo.bright,
        halo_dark: halo.dark,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn summarize_combines_the_individual_metrics() {
        let (w, h) = (16, 14);
        let reference: Vec<f32> = (0..w * h)
            .map(|i| 0.25 + 0.5 * ((i * 7919 % 101) as f32 / 100.0))
            .collect();
        let technique: Vec<f32> = reference
            .iter()
            .enumerate()
            .map(|(i, &v)| v + if i % 3 == 0 { 0.125 } else { -0.0625 })
            .collect();
        // Far plane with a near 4×4 square.
        let depth: Vec<f32> = (0..w * h)
            .map(|i| {
                let (x, y) = (i % w, i / w);
                if (5..9).contains(&x) && (5..9).contains(&y) {
                    2.0
                } else {
                    10.0
                }
            })
            .collect();
        let t = Image::new(w, h, &technique).unwrap();
        let r = Image::new(w, h, &reference).unwrap();
        let d = Image::new(w, h, &depth).unwrap();
        let s = summarize(&t, &r, &d, 2, 0.1).unwrap();
        let halo = halo_error(&t, &r, &d, 2, 0.1).unwrap();
        assert_eq!(s.mse, mse(&t, &r).unwrap());
        assert_eq!(s.mae, mae(&t, &r).unwrap());
        assert_eq!(s.psnr, psnr(&t, &r).unwrap());
        assert_eq!(s.ssim, ssim(&t, &r).unwrap());
        assert_eq!(s.halo_bright, halo.bright);
        assert_eq!(s.halo_dark, halo.dark);
        assert!(s.halo_bright > 0.0 && s.halo_dark < 0.0);
    }

    /// Throughput check at 1920×1080; run with
    /// `cargo test --release -- --ignored --nocapture full_hd`.
    #[test]
    #[ignore = "timing smoke test; run in release"]
    fn full_hd_timing() {
        let (w, h) = (1920, 1080);
        let reference: Vec<f32> = (0..w * h).map(|i| (i % 251) as f32 / 250.0).collect();
        let technique: Vec<f32> = (0..w * h).map(|i| (i % 241) as f32 / 240.0).collect();
        let depth: Vec<f32> = (0..w * h)
            .map(|i| {
                if (i % w) / 64 % 2 == (i / w) / 64 % 2 {
                    1.0
                } else {
                    4.0
                }
            })
            .collect();
        let t = Image::new(w, h, &technique).unwrap();
        let r = Image::new(w, h, &reference).unwrap();
        let d = Image::new(w, h, &depth).unwrap();
        let start = std::time::Instant::now();
        let s = ssim(&t, &r).unwrap();
        let t_ssim = start.elapsed();
        let start = std::time::Instant::now();
        let band = halo_band(&d, 32, 0.1);
        let t_band = start.elapsed();
        let start = std::time::Instant::now();
        let all = summarize(&t, &r, &d, 32, 0.1).unwrap();
        let t_all = start.elapsed();
        println!(
            "1920x1080: ssim {t_ssim:?} (={s:.6}), halo_band r=32 {t_band:?} ({} px), summarize {t_all:?}",
            band.iter().filter(|&&b| b).count()
        );
        assert_eq!(all.ssim, s);
    }

    #[test]
    fn summarize_rejects_bad_inputs_without_panicking() {
        let a = vec![0.5f32; 12 * 12];
        let small = vec![0.5f32; 10 * 12];
        let img = Image::new(12, 12, &a).unwrap();
        let small_img = Image::new(10, 12, &small).unwrap();
        assert!(matches!(
            summarize(&img, &img, &small_img, 1, 0.1),
            Err(MetricsError::SizeMismatch { .. })
        ));
        assert!(matches!(
            summarize(&small_img, &small_img, &small_img, 1, 0.1),
            Err(MetricsError::WindowTooLarge { .. })
        ));
        let mut nan = a.clone();
        nan[5] = f32::NAN;
        let nan_img = Image::new(12, 12, &nan).unwrap();
        assert!(matches!(
            summarize(&img, &nan_img, &img, 1, 0.1),
            Err(MetricsError::NonFinite {
                image: "reference",
                x: 5,
                y: 0
            })
        ));
    }
}
