//! Halo error: signed AO error next to depth discontinuities.
//!
//! Screen-space AO typically produces bright or dark halos around silhouettes
//! (a foreground object darkening or failing to darken the background behind
//! it). This metric restricts the error to a band around depth
//! discontinuities and splits it into its bright (over-estimated visibility)
//! and dark (over-occluded) parts, which a plain MSE would mix.

use super::input::{check_pair, check_same_size};
use super::sum::Sum;
use super::{Image, MetricsError};

/// Mean signed error of a technique inside the halo band (see [`halo_error`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HaloError {
    /// Mean of `max(technique − reference, 0)` over the band (≥ 0): how much
    /// too bright the technique is next to discontinuities.
    pub bright: f64,
    /// Mean of `min(technique − reference, 0)` over the band (≤ 0): how much
    /// too dark it is there.
    pub dark: f64,
    /// Number of pixels in the band (the denominator of both means).
    pub pixels: usize,
}

/// Whether a linear view depth sample is geometry: positive and finite.
/// Anything else (≤ 0, NaN, ±∞) is background.
#[inline]
pub fn has_geometry(d: f32) -> bool {
    d.is_finite() && d > 0.0
}

/// Whether the edge between two 4-neighbours is a depth discontinuity.
#[inline]
fn is_jump(d0: f32, d1: f32, relative_jump: f64) -> bool {
    match (has_geometry(d0), has_geometry(d1)) {
        (true, true) => {
            // In f64 so that the difference of two large f32 depths cannot
            // overflow and the threshold is not rounded to f32.
            let (a, b) = (f64::from(d0), f64::from(d1));
            (a - b).abs() > relative_jump * a.min(b)
        }
        (false, false) => false,
        // A silhouette against the background is always a discontinuity.
        _ => true,
    }
}

fn assert_layout(depth: &Image) {
    assert!(
        depth.check_layout().is_ok(),
        "depth image layout is invalid: {}x{} with {} samples",
        depth.width,
        depth.height,
        depth.data.len()
    );
}

/// Row-major mask of depth-discontinuity pixels.
///
/// A pixel is a discontinuity pixel if, for any of its 4-neighbours, either
/// * both have geometry and their depths differ by more than
///   `relative_jump × min(depth₀, depth₁)` (strictly), or
/// * exactly one of the two is background (depth ≤ 0 or non-finite).
///
/// Both pixels of such a pair are marked, so background pixels bordering
/// geometry are marked too (they are excluded later from the band).
/// `relative_jump` is meant to be ≥ 0; [`halo_error`] rejects other values.
///
/// # Panics
/// If `depth.data.len() != depth.width * depth.height` or the image is empty
/// (impossible for an [`Image`] built with [`Image::new`]).
pub fn discontinuity_mask(depth: &Image, relative_jump: f32) -> Vec<bool> {
    assert_layout(depth);
    let (w, h) = (depth.width, depth.height);
    let rel = f64::from(relative_jump);
    let mut mask = vec![false; w * h];
    // Each 4-neighbour pair is visited once, via its right or lower edge.
    for y in 0..h {
        for x in 0..w {
            let i = y * w + x;
            let d = depth.data[i];
            if x + 1 < w && is_jump(d, depth.data[i + 1], rel) {
                mask[i] = true;
                mask[i + 1] = true;
            }
            if y + 1 < h && is_jump(d, depth.data[i + w], rel) {
                mask[i] = true;
                mask[i + w] = true;
            }
        }
    }
    mask
}

/// Row-major mask of the halo band: every pixel *with geometry* within
/// Chebyshev distance `radius_px` of a [`discontinuity_mask`] pixel
/// (`radius_px = 0` is the geometry part of the discontinuity mask itself).
///
/// Runs in `O(width × height)` regardless of the radius: a Chebyshev ball is
/// a square, so the dilation is separable into a horizontal and a vertical
/// running-window pass.
///
/// # Panics
/// As [`discontinuity_mask`].
pub fn halo_band(depth: &Image, radius_px: usize, relative_jump: f32) -> Vec<bool> {
    let discontinuities = discontinuity_mask(depth, relative_jump);
    let mut band = dilate_square(&discontinuities, depth.width, depth.height, radius_px);
    for (inside, &d) in band.iter_mut().zip(depth.data) {
        *inside &= has_geometry(d);
    }
    band
}

/// Dilation of a `w × h` mask by the `(2r+1) × (2r+1)` square, clipped to the
/// image, as two 1-D running-count passes: O(w·h) time for any `r`, one
/// intermediate mask plus O(w) counters.
fn dilate_square(mask: &[bool], w: usize, h: usize, r: usize) -> Vec<bool> {
    // A radius past the image extent covers the same pixels as one at it;
    // clamping also keeps the index arithmetic below far from overflow.
    let r = r.min(w.max(h));

    // Horizontal: a prefix count per row answers "any set pixel in
    // [x − r, x + r]" in O(1).
    let mut horizontal = vec![false; w * h];
    let mut prefix = vec![0usize; w + 1];
    for (src, dst) in mask.chunks_exact(w).zip(horizontal.chunks_exact_mut(w)) {
        for (x, &m) in src.iter().enumerate() {
            prefix[x + 1] = prefix[x] + usize::from(m);
        }
        for (x, out) in dst.iter_mut().enumerate() {
            let lo = x.saturating_sub(r);
            let hi = (x + r).min(w - 1);
            *out = prefix[hi + 1] > prefix[lo];
        }
    }

    // Vertical: per-column count of set pixels in rows [y − r, y + r], slid
    // down one row at a time (rows are contiguous, so this stays cache
    // friendly, unlike a column-by-column pass).
    let mut out = vec![false; w * h];
    let mut count = vec![0usize; w];
    let add_row = |count: &mut [usize], y: usize, entering: bool| {
        for (c, &m) in count.iter_mut().zip(&horizontal[y * w..(y + 1) * w]) {
            if m {
                if entering {
                    *c += 1;
                } else {
                    *c -= 1;
                }
            }
        }
    };
    for y in 0..=r.min(h - 1) {
        add_row(&mut count, y, true);
    }
    for y in 0..h {
        for (o, &c) in out[y * w..(y + 1) * w].iter_mut().zip(&count) {
            *o = c > 0;
        }
        // Slide the window from [y − r, y + r] to [y + 1 − r, y + 1 + r].
        if y >= r {
            add_row(&mut count, y - r, false);
        }
        if y + r + 1 < h {
            add_row(&mut count, y + r + 1, true);
        }
    }
    out
}

/// Bright/dark AO error inside the halo band of `depth` (see [`halo_band`]).
///
/// With `e = technique − reference` per pixel (in `f64`), `bright` is the
/// mean of `max(e, 0)` and `dark` the mean of `min(e, 0)` over the band, and
/// `pixels` its size. An empty band gives all zeros.
///
/// # Errors
/// Invalid layout or size mismatch of any of the three images, a non-finite
/// sample in `technique` or `reference` (the depth may hold any value), or a
/// `relative_jump` that is negative or NaN
/// ([`MetricsError::InvalidParameter`]).
pub fn halo_error(
    technique: &Image,
    reference: &Image,
    depth: &Image,
    radius_px: usize,
    relative_jump: f32,
) -> Result<HaloError, MetricsError> {
    check_pair(technique, reference, "technique", "reference")?;
    depth.check_layout()?;
    check_same_size(technique, depth)?;
    // +∞ is allowed: it means "only silhouettes against the background count".
    if relative_jump.is_nan() || relative_jump < 0.0 {
        return Err(MetricsError::InvalidParameter {
            name: "relative_jump",
            requirement: "non-negative (and not NaN)",
        });
    }

    let band = halo_band(depth, radius_px, relative_jump);
    let (mut bright, mut dark, mut pixels) = (Sum::default(), Sum::default(), 0usize);
    for ((&inside, &t), &r) in band.iter().zip(technique.data).zip(reference.data) {
        if inside {
            let e = f64::from(t) - f64::from(r);
            if e > 0.0 {
                bright.add(e);
            } else {
                dark.add(e);
            }
            pixels += 1;
        }
    }
    if pixels == 0 {
        return Ok(HaloError {
            bright: 0.0,
            dark: 0.0,
            pixels: 0,
        });
    }
    let n = pixels as f64;
    Ok(HaloError {
        bright: bright.value() / n,
        dark: dark.value() / n,
        pixels,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const FAR: f32 = 10.0;
    const NEAR: f32 = 2.0;

    /// 16×16 far plane (depth 10) with a near 4×4 square (depth 2) covering
    /// columns and rows 5..=8.
    fn square_scene() -> Vec<f32> {
        (0..16 * 16)
            .map(|i| {
                let (x, y) = (i % 16, i / 16);
                if (5..=8).contains(&x) && (5..=8).contains(&y) {
                    NEAR
                } else {
                    FAR
                }
            })
            .collect()
    }

    fn picture(mask: &[bool], w: usize) -> Vec<String> {
        mask.chunks(w)
            .map(|row| row.iter().map(|&m| if m { '#' } else { '.' }).collect())
            .collect()
    }

    fn count(mask: &[bool]) -> usize {
        mask.iter().filter(|&&m| m).count()
    }

    #[test]
    fn square_on_plane_band_sizes() {
        // |10 − 2| = 8 > 0.1 × 2, so every near/far 4-neighbour pair is a
        // discontinuity. Marked pixels: the 12 boundary pixels of the 4×4
        // square (its 2×2 interior has only near neighbours) plus the 16 far
        // pixels sharing an edge with it (4 per side; the diagonal corners
        // at (4,4), (9,4), (4,9), (9,9) only touch it diagonally). They lie
        // in the 6×6 block rows/cols 4..=9:
        //     radius 0: 36 − 4 corners − 4 interior       = 28
        // Dilating by r fills the (6 + 2r)² block except its 4 corner pixels,
        // whose nearest marked pixel (e.g. (5,4) for the corner (4−r, 4−r))
        // is at Chebyshev distance r + 1:
        //     radius 1: 8² − 4  = 60
        //     radius 2: 10² − 4 = 96
        //     radius 3: 12² − 4 = 140
        //     radius 4: 14² − 4 = 192   (block rows/cols 0..=13, still inside)
        // From radius 5 the block (4 − r ..= 9 + r) is clipped by the 16×16
        // image, and only its bottom-right corner stays inside:
        //     radius 5: rows/cols 0..=14 → 15² − 1 = 224
        //     radius 6: rows/cols 0..=15 → 16² − 1 = 255 ((15,15) is at
        //               distance 7 from its nearest marked pixel, (8,9))
        //     radius ≥ 7: 256.
        let depth = square_scene();
        let depth = Image::new(16, 16, &depth).unwrap();
        let mask = discontinuity_mask(&depth, 0.1);
        #[rustfmt::skip]
        let expected_mask = [
            "................",
            "................",
            "................",
            "................",
            ".....####.......",
            "....######......",
            "....##..##......",
            "....##..##......",
            "....######......",
            ".....####.......",
            "................",
            "................",
            "................",
            "................",
            "................",
            "................",
        ];
        assert_eq!(picture(&mask, 16), expected_mask);
        assert_eq!(count(&mask), 28);
        // All pixels have geometry, so the radius-0 band is the mask itself.
        assert_eq!(halo_band(&depth, 0, 0.1), mask);

        #[rustfmt::skip]
        let expected_r1 = [
            "................",
            "................",
            "................",
            "....######......",
            "...########.....",
            "...########.....",
            "...########.....",
            "...########.....",
            "...########.....",
            "...########.....",
            "....######......",
            "................",
            "................",
            "................",
            "................",
            "................",
        ];
        let band1 = halo_band(&depth, 1, 0.1);
        assert_eq!(picture(&band1, 16), expected_r1);
        let counts: Vec<usize> = [0, 1, 2, 3, 4, 5, 6, 7, 100, usize::MAX]
            .iter()
            .map(|&r| count(&halo_band(&depth, r, 0.1)))
            .collect();
        assert_eq!(counts, [28, 60, 96, 140, 192, 224, 255, 256, 256, 256]);

        // A threshold above the jump (|10 − 2| = 8 = 4 × 2) finds nothing.
        assert_eq!(count(&halo_band(&depth, 2, 4.0)), 0);
        assert_eq!(count(&halo_band(&depth, 2, 3.99)), 96);
    }

    #[test]
    fn background_is_a_discontinuity_but_not_part_of_the_band() {
        // 8×6: columns 0..=3 geometry at depth 5, columns 4..=7 background in
        // every spelling (0, negative, NaN, +∞, −∞). Discontinuity pixels:
        // columns 3 and 4 (12). The band keeps geometry only, growing left
        // one column per unit of radius: 6, 12, 18, 24 (all geometry) pixels.
        let background = [0.0, -1.0, f32::NAN, f32::INFINITY, f32::NEG_INFINITY, -0.0];
        let depth: Vec<f32> = (0..8 * 6)
            .map(|i| {
                let (x, y) = (i % 8, i / 8);
                if x < 4 {
                    5.0
                } else {
                    background[(x + y) % background.len()]
                }
            })
            .collect();
        let depth = Image::new(8, 6, &depth).unwrap();
        let mask = discontinuity_mask(&depth, 0.1);
        assert_eq!(count(&mask), 12);
        assert!(mask
            .iter()
            .enumerate()
            .all(|(i, &m)| m == matches!(i % 8, 3 | 4)));
        let counts: Vec<usize> = (0..5).map(|r| count(&halo_band(&depth, r, 0.1))).collect();
        assert_eq!(counts, [6, 12, 18, 24, 24]);
        // Even an infinite threshold keeps silhouettes against background.
        assert_eq!(count(&halo_band(&depth, 0, f32::INFINITY)), 6);

        // All background: nothing anywhere.
        let none = [0.0f32; 9];
        let none = Image::new(3, 3, &none).unwrap();
        assert_eq!(count(&discontinuity_mask(&none, 0.1)), 0);
        assert_eq!(count(&halo_band(&none, 3, 0.1)), 0);
    }

    #[test]
    fn threshold_is_relative_to_the_smaller_depth_and_strict() {
        let pair = |d0: f32, d1: f32, rel: f32| {
            let d = [d0, d1];
            discontinuity_mask(&Image::new(2, 1, &d).unwrap(), rel)
        };
        // |4.5 − 4| = 0.5.
        assert_eq!(pair(4.0, 4.5, 0.1), [true, true]); // 0.5 > 0.4
        assert_eq!(pair(4.0, 4.5, 0.12), [true, true]); // 0.5 > 0.48 (vs 0.54 for the larger depth)
        assert_eq!(pair(4.5, 4.0, 0.12), [true, true]); // order does not matter
        assert_eq!(pair(4.0, 4.5, 0.125), [false, false]); // 0.5 > 0.5 is false
        assert_eq!(pair(4.0, 4.5, 0.2), [false, false]);
        // Vertical neighbours count the same way.
        let d = [4.0f32, 4.5];
        assert_eq!(
            discontinuity_mask(&Image::new(1, 2, &d).unwrap(), 0.1),
            [true, true]
        );
    }

    /// The band by its definition, O(n·r²): for each geometry pixel, look for
    /// a discontinuity pixel (tested directly on its four neighbours) inside
    /// the clipped (2r+1)² square.
    fn brute_force_band(depth: &[f32], w: usize, h: usize, r: usize, rel: f32) -> Vec<bool> {
        let geo = |d: f32| d.is_finite() && d > 0.0;
        let jump = |a: f32, b: f32| {
            if geo(a) && geo(b) {
                (f64::from(a) - f64::from(b)).abs() > f64::from(rel) * f64::from(a.min(b))
            } else {
                geo(a) != geo(b)
            }
        };
        let disc = |x: usize, y: usize| {
            let d = depth[y * w + x];
            (x > 0 && jump(d, depth[y * w + x - 1]))
                || (x + 1 < w && jump(d, depth[y * w + x + 1]))
                || (y > 0 && jump(d, depth[(y - 1) * w + x]))
                || (y + 1 < h && jump(d, depth[(y + 1) * w + x]))
        };
        let mut band = vec![false; w * h];
        for y in 0..h {
            for x in 0..w {
                if !geo(depth[y * w + x]) {
                    continue;
                }
                'search: for yy in y.saturating_sub(r)..=(y + r).min(h - 1) {
                    for xx in x.saturating_sub(r)..=(x + r).min(w - 1) {
                        if disc(xx, yy) {
                            band[y * w + x] = true;
                            break 'search;
                        }
                    }
                }
            }
        }
        band
    }

    #[test]
    fn separable_band_matches_brute_force_definition() {
        // Pseudo-random blocky depth with background holes, several radii
        // and thresholds, odd sizes so clipping at every border is exercised.
        let (w, h) = (37, 23);
        let mut state = 0x1234_5678u32;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            state
        };
        let depth: Vec<f32> = (0..w * h)
            .map(|_| match next() % 10 {
                0 => 0.0,
                1 => f32::NAN,
                k => 1.0 + (k as f32) * 0.35,
            })
            .collect();
        let img = Image::new(w, h, &depth).unwrap();
        for rel in [0.05f32, 0.2, 0.5, 10.0] {
            for r in [0, 1, 2, 3, 7, 40] {
                assert_eq!(
                    halo_band(&img, r, rel),
                    brute_force_band(&depth, w, h, r, rel),
                    "rel {rel}, r {r}"
                );
            }
        }
        // Single row / column images.
        for (w, h) in [(1, 9), (9, 1), (1, 1)] {
            let d: Vec<f32> = (0..w * h)
                .map(|i| if i % 3 == 0 { 1.0 } else { 3.0 })
                .collect();
            let img = Image::new(w, h, &d).unwrap();
            for r in 0..4 {
                assert_eq!(halo_band(&img, r, 0.1), brute_force_band(&d, w, h, r, 0.1));
            }
        }
    }

    /// Reference AO: varied values in [0.3, 0.7].
    fn reference_ao(n: usize) -> Vec<f32> {
        (0..n)
            .map(|i| 0.3 + 0.4 * ((i * 37 % 17) as f32 / 16.0))
            .collect()
    }

    #[test]
    fn bright_halo_inside_band_only() {
        let depth = square_scene();
        let depth = Image::new(16, 16, &depth).unwrap();
        let band = halo_band(&depth, 2, 0.1);
        assert_eq!(count(&band), 96);
        let reference = reference_ao(256);
        let technique: Vec<f32> = reference
            .iter()
            .zip(&band)
            .map(|(&r, &inside)| if inside { r + 0.2 } else { r })
            .collect();
        let t = Image::new(16, 16, &technique).unwrap();
        let r = Image::new(16, 16, &reference).unwrap();
        let halo = halo_error(&t, &r, &depth, 2, 0.1).unwrap();
        // e = (r + 0.2 rounded to f32) − r = 0.2 up to one f32 ulp of ~0.9.
        assert!((halo.bright - 0.2).abs() < 1e-6, "{halo:?}");
        assert_eq!(halo.dark, 0.0);
        assert_eq!(halo.pixels, 96);

        // A uniform error outside the band (here −0.3) changes nothing.
        let technique_outside: Vec<f32> = technique
            .iter()
            .zip(&band)
            .map(|(&v, &inside)| if inside { v } else { v - 0.3 })
            .collect();
        let t2 = Image::new(16, 16, &technique_outside).unwrap();
        assert_eq!(halo_error(&t2, &r, &depth, 2, 0.1).unwrap(), halo);

        // A smaller radius sees the same +0.2 over fewer pixels.
        let halo1 = halo_error(&t2, &r, &depth, 1, 0.1).unwrap();
        assert_eq!(halo1.pixels, 60);
        assert!((halo1.bright - 0.2).abs() < 1e-6 && halo1.dark == 0.0);
    }

    #[test]
    fn dark_and_mixed_halos() {
        let depth = square_scene();
        let depth = Image::new(16, 16, &depth).unwrap();
        let band = halo_band(&depth, 2, 0.1);
        let reference = reference_ao(256);
        let r = Image::new(16, 16, &reference).unwrap();

        let darker: Vec<f32> = reference
            .iter()
            .zip(&band)
            .map(|(&v, &inside)| if inside { v - 0.1 } else { v })
            .collect();
        let halo = halo_error(&Image::new(16, 16, &darker).unwrap(), &r, &depth, 2, 0.1).unwrap();
        assert_eq!(halo.bright, 0.0);
        assert!((halo.dark + 0.1).abs() < 1e-6, "{halo:?}");

        // Band pixels alternately +0.25 and −0.25 (48 each of 96):
        // bright = 48·0.25/96 = 0.125, dark = −0.125.
        let mut k = 0;
        let mixed: Vec<f32> = reference
            .iter()
            .zip(&band)
            .map(|(&v, &inside)| {
                if inside {
                    k += 1;
                    if k % 2 == 0 {
                        v + 0.25
                    } else {
                        v - 0.25
                    }
                } else {
                    v
                }
            })
            .collect();
        let halo = halo_error(&Image::new(16, 16, &mixed).unwrap(), &r, &depth, 2, 0.1).unwrap();
        assert!((halo.bright - 0.125).abs() < 1e-6, "{halo:?}");
        assert!((halo.dark + 0.125).abs() < 1e-6, "{halo:?}");
        assert_eq!(halo.pixels, 96);
    }

    #[test]
    fn empty_band_is_all_zero() {
        let depth = [3.0f32; 12 * 12];
        let depth = Image::new(12, 12, &depth).unwrap();
        let a = reference_ao(144);
        let b = vec![0.0f32; 144];
        let halo = halo_error(
            &Image::new(12, 12, &a).unwrap(),
            &Image::new(12, 12, &b).unwrap(),
            &depth,
            4,
            0.1,
        )
        .unwrap();
        assert_eq!(
            halo,
            HaloError {
                bright: 0.0,
                dark: 0.0,
                pixels: 0
            }
        );
    }

    #[test]
    fn errors_instead_of_panics() {
        let ao = vec![0.5f32; 16 * 16];
        let ao = Image::new(16, 16, &ao).unwrap();
        let depth = square_scene();
        let depth_img = Image::new(16, 16, &depth).unwrap();

        let small = vec![1.0f32; 16 * 15];
        let small = Image::new(16, 15, &small).unwrap();
        assert_eq!(
            halo_error(&ao, &ao, &small, 1, 0.1),
            Err(MetricsError::SizeMismatch {
                expected: (16, 16),
                found: (16, 15)
            })
        );
        assert!(matches!(
            halo_error(&ao, &small, &depth_img, 1, 0.1),
            Err(MetricsError::SizeMismatch { .. })
        ));

        let mut nan = vec![0.5f32; 16 * 16];
        nan[16 * 2 + 1] = f32::NAN;
        let nan = Image::new(16, 16, &nan).unwrap();
        assert_eq!(
            halo_error(&nan, &ao, &depth_img, 1, 0.1),
            Err(MetricsError::NonFinite {
                image: "technique",
                x: 1,
                y: 2
            })
        );
        // NaN depth is background, not an error.
        assert!(halo_error(&ao, &ao, &nan, 1, 0.1).is_ok());

        for bad in [f32::NAN, -0.1, f32::NEG_INFINITY] {
            assert!(matches!(
                halo_error(&ao, &ao, &depth_img, 1, bad),
                Err(MetricsError::InvalidParameter {
                    name: "relative_jump",
                    ..
                })
            ));
        }

        let broken = Image {
            width: 16,
            height: 16,
            data: &depth[..10],
        };
        assert!(matches!(
            halo_error(&ao, &ao, &broken, 1, 0.1),
            Err(MetricsError::DataLength { .. })
        ));
    }
}
